#pragma once
// libzip, loaded when a zip archive is first read or written (a DJI KMZ), not at every start: with
// it the dynamic linker also loads and relocates libcrypto (libzip's encryption), about half of
// the symbol relocations of every swath program's start-up, for a file few plans write.
#include <zip.h>

namespace swath::missions {

// The libzip functions swath calls, each named as in <zip.h>.
#define SWATH_LIBZIP_FUNCTIONS(F)                                                              \
  F(zip_close)                                                                                 \
  F(zip_discard)                                                                               \
  F(zip_error_fini) F(zip_error_init) F(zip_error_strerror) F(zip_fclose) F(zip_file_add)      \
      F(zip_file_set_mtime) F(zip_fopen) F(zip_fread) F(zip_get_error) F(zip_open_from_source) \
          F(zip_set_file_compression) F(zip_source_buffer) F(zip_source_buffer_create)         \
              F(zip_source_close) F(zip_source_error) F(zip_source_free) F(zip_source_keep)    \
                  F(zip_source_open) F(zip_source_read) F(zip_source_seek) F(zip_source_tell)  \
                      F(zip_stat)

struct LibZip {
#define SWATH_LIBZIP_FIELD(name) decltype(&::name) name = nullptr;
  SWATH_LIBZIP_FUNCTIONS(SWATH_LIBZIP_FIELD)
#undef SWATH_LIBZIP_FIELD
};

/// libzip's functions, the library loaded on the first call (thread-safe); throws
/// std::runtime_error naming the library when it cannot be loaded.
const LibZip& libzip();

}  // namespace swath::missions
