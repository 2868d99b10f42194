// Zip archives (the DJI KMZ) through libzip (docs/swath-plan.md: libzip-dev), built in memory.
#include <ctime>
#include <memory>
#include <stdexcept>

#include "libzip.hpp"
#include "zip_archive.hpp"

namespace swath::missions {
namespace {

[[noreturn]] void fail(const std::string& what, const std::string& why) {
  throw std::runtime_error("zip archive: " + what + ": " + why);
}

// libzip stores an entry's time as an MS-DOS local date and time converted with localtime(), so
// a fixed time_t would give different bytes in different time zones: the time_t of a fixed local
// time (mktime) converts back to that same local time everywhere. Midnight of 1 January has no
// daylight-saving transition anywhere.
std::time_t fixed_mtime() {
  std::tm t{};
  t.tm_year = 2020 - 1900;
  t.tm_mon = 0;
  t.tm_mday = 1;
  t.tm_isdst = -1;
  return std::mktime(&t);
}

// The bytes an in-memory source holds.
std::string source_bytes(zip_source_t* source) {
  const LibZip& z = libzip();
  if (z.zip_source_open(source) < 0)
    fail("reading back", z.zip_error_strerror(z.zip_source_error(source)));
  z.zip_source_seek(source, 0, SEEK_END);
  const zip_int64_t size = z.zip_source_tell(source);
  z.zip_source_seek(source, 0, SEEK_SET);
  std::string bytes(static_cast<std::size_t>(size < 0 ? 0 : size), '\0');
  const zip_int64_t read = z.zip_source_read(source, bytes.data(), bytes.size());
  z.zip_source_close(source);
  if (size < 0 || read != size) fail("reading back", "short read");
  return bytes;
}

}  // namespace

std::string zip_archive(const std::vector<std::pair<std::string, std::string>>& entries) {
  const LibZip& z = libzip();
  zip_error_t error;
  z.zip_error_init(&error);
  zip_source_t* memory = z.zip_source_buffer_create(nullptr, 0, 0, &error);
  if (memory == nullptr) fail("creating the buffer", z.zip_error_strerror(&error));
  // Ours until the end: the archive takes a reference of its own (zip_source_keep) and drops it
  // when closed; the bytes are read from it after that.
  std::unique_ptr<zip_source_t, decltype(&::zip_source_free)> owner(memory, z.zip_source_free);
  zip_t* archive = z.zip_open_from_source(memory, ZIP_TRUNCATE, &error);
  if (archive == nullptr) {
    const std::string why = z.zip_error_strerror(&error);
    z.zip_error_fini(&error);
    fail("opening", why);
  }
  z.zip_error_fini(&error);
  z.zip_source_keep(memory);
  auto abandon = [&](const std::string& what) {
    const std::string why = z.zip_error_strerror(z.zip_get_error(archive));
    z.zip_discard(archive);
    fail(what, why);
  };
  const std::time_t mtime = fixed_mtime();
  for (const auto& [name, bytes] : entries) {
    zip_source_t* data = z.zip_source_buffer(archive, bytes.data(), bytes.size(), 0);
    if (data == nullptr) abandon("adding " + name);
    const zip_int64_t index = z.zip_file_add(archive, name.c_str(), data, ZIP_FL_ENC_UTF_8);
    if (index < 0) {
      z.zip_source_free(data);
      abandon("adding " + name);
    }
    const auto i = static_cast<zip_uint64_t>(index);
    if (z.zip_set_file_compression(archive, i, ZIP_CM_DEFLATE, 9) < 0 ||
        z.zip_file_set_mtime(archive, i, mtime, 0) < 0)
      abandon("setting up " + name);
  }
  if (z.zip_close(archive) < 0) abandon("writing");
  return source_bytes(memory);
}

}  // namespace swath::missions
