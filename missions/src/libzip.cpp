// libzip loaded with dlopen on first use (libzip.hpp says why).
#include "libzip.hpp"

#include <dlfcn.h>

#include <stdexcept>
#include <string>

#ifndef SWATH_LIBZIP_SONAME
#error "SWATH_LIBZIP_SONAME: the libzip soname, set by missions/CMakeLists.txt"
#endif

namespace swath::missions {
namespace {

[[noreturn]] void load_failed(const std::string& why) {
  throw std::runtime_error(std::string("libzip (") + SWATH_LIBZIP_SONAME +
                           ") cannot be loaded: " + why);
}

LibZip load() {
  // Never closed: the functions stay valid for the process's life.
  void* library = ::dlopen(SWATH_LIBZIP_SONAME, RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) load_failed(::dlerror());
  LibZip z;
#define SWATH_LIBZIP_LOAD(name)                                          \
  z.name = reinterpret_cast<decltype(&::name)>(::dlsym(library, #name)); \
  if (z.name == nullptr) load_failed(std::string("no ") + #name);
  SWATH_LIBZIP_FUNCTIONS(SWATH_LIBZIP_LOAD)
#undef SWATH_LIBZIP_LOAD
  return z;
}

}  // namespace

const LibZip& libzip() {
  static const LibZip z = load();  // a failed load throws and is tried again on the next call
  return z;
}

}  // namespace swath::missions
