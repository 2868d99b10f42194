#include "swath/base/file_text.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "swath/base/input_error.hpp"

namespace swath::base {
namespace {

std::string with_article(std::string_view noun) {
  const bool vowel =
      !noun.empty() && std::string_view("aeiou").find(noun.front()) != std::string_view::npos;
  return (vowel ? "an " : "a ") + std::string(noun);
}

}  // namespace

std::string read_text_file(const std::filesystem::path& path, std::string_view what,
                           std::size_t max_bytes) {
  const std::string source = path.string();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(source + ": is a directory, not " + with_article(what));
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(source + ": cannot open the " + std::string(what) + " (" +
                     std::strerror(errno) + ")");
  std::string text;
  char chunk[1 << 16];
  while (in) {
    in.read(chunk, sizeof chunk);
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes)
      throw InputError(source + ": the " + std::string(what) + " is larger than swath's limit of " +
                       std::to_string(max_bytes >> 20) + " MiB");
  }
  if (in.bad())
    throw InputError(source + ": cannot read the " + std::string(what) + " (" +
                     std::strerror(errno) + ")");
  return text;
}

std::pair<int, int> line_column(std::string_view text, std::size_t offset) {
  int line = 1, column = 1;
  for (std::size_t i = 0; i < std::min(offset, text.size()); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

}  // namespace swath::base
