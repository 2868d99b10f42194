#include "swath/base/output_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace swath::base {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
  throw std::runtime_error(path.string() + ": " + what + " (" + std::strerror(errno) + ")");
}

void write_file(const std::filesystem::path& temporary, const std::string& content) {
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail(temporary, "cannot create");
  std::size_t written = 0;
  while (written < content.size()) {
    const ssize_t n = ::write(fd, content.data() + written, content.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      ::close(fd);
      fail(temporary, "cannot write");
    }
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) fail(temporary, "cannot flush");
}

}  // namespace

void write_files_atomically(const std::filesystem::path& directory,
                            const std::vector<std::pair<std::string, std::string>>& files) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec || !std::filesystem::is_directory(directory))
    throw std::runtime_error(directory.string() + ": cannot create the output directory (" +
                             ec.message() + ")");
  const std::string suffix = ".tmp-" + std::to_string(::getpid());
  std::vector<std::filesystem::path> temporaries;
  try {
    // Every file complete on disk before any is renamed: an error leaves the old set untouched.
    for (const auto& [name, content] : files) {
      temporaries.push_back(directory / ("." + name + suffix));
      write_file(temporaries.back(), content);
    }
    for (std::size_t i = 0; i < files.size(); ++i)
      if (std::rename(temporaries[i].c_str(), (directory / files[i].first).c_str()) != 0)
        fail(directory / files[i].first, "cannot rename into place");
  } catch (...) {
    for (const auto& t : temporaries) std::filesystem::remove(t, ec);
    throw;
  }
}

}  // namespace swath::base
