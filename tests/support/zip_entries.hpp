#pragma once
// A zip archive's entries (a KMZ's), read back with libzip's own reader: the tests' independent
// decoder of the archives missions/src/zip_archive.cpp writes.

#include <zip.h>

#include <map>
#include <optional>
#include <string>

namespace swath::test {

/// Every entry of the archive in `bytes` by name, with its bytes; nullopt when the bytes are no
/// zip archive, libzip's consistency check (ZIP_CHECKCONS) refuses them, or an entry reads short.
inline std::optional<std::map<std::string, std::string>> zip_entries(const std::string& bytes) {
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* source = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error);
  zip_t* archive =
      source ? zip_open_from_source(source, ZIP_RDONLY | ZIP_CHECKCONS, &error) : nullptr;
  zip_error_fini(&error);
  if (archive == nullptr) {
    if (source) zip_source_free(source);
    return std::nullopt;
  }
  std::optional<std::map<std::string, std::string>> out{std::in_place};
  for (zip_int64_t i = 0; out && i < zip_get_num_entries(archive, 0); ++i) {
    zip_stat_t st;
    zip_stat_index(archive, static_cast<zip_uint64_t>(i), 0, &st);
    std::string content(st.size, '\0');
    zip_file_t* file = zip_fopen_index(archive, static_cast<zip_uint64_t>(i), 0);
    const bool whole =
        file && zip_fread(file, content.data(), st.size) == static_cast<zip_int64_t>(st.size);
    if (file) zip_fclose(file);
    if (whole)
      (*out)[st.name] = std::move(content);
    else
      out.reset();
  }
  zip_close(archive);
  return out;
}

}  // namespace swath::test
