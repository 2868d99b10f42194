// Opens the GIS module on the first GIS file and forwards to it (gis_module.hpp says why).
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>

#include "field_ogr.hpp"
#include "gis_module.hpp"

namespace swath::geometry::detail {
namespace {

constexpr const char* kModuleFile = "libswath_gis.so";

// Where to look, in order: $SWATH_GIS_MODULE, beside the program, the
// installed tree's lib/swath/, the build tree.
std::vector<std::filesystem::path> candidates() {
  std::vector<std::filesystem::path> out;
  if (const char* env = std::getenv("SWATH_GIS_MODULE"); env != nullptr && *env != '\0')
    out.emplace_back(env);
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    out.push_back(exe.parent_path() / kModuleFile);
    // An installed program: PREFIX/bin/PROGRAM and PREFIX/lib/swath/ (docs/install.md).
    out.push_back(exe.parent_path().parent_path() / "lib" / "swath" / kModuleFile);
  }
  out.emplace_back(SWATH_GIS_MODULE_BUILD_PATH);
  return out;
}

}  // namespace

const GisModule& gis_module() {
  static const GisModule* loaded = nullptr;
  static std::string failure;
  static std::once_flag once;
  std::call_once(once, [] {
    std::string tried;
    for (const std::filesystem::path& path : candidates()) {
      std::error_code ec;
      if (!std::filesystem::exists(path, ec)) {
        tried += (tried.empty() ? "" : ", ") + path.string();
        continue;
      }
      void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (handle == nullptr) {
        failure = "cannot load the GIS module " + path.string() + " (" + ::dlerror() + ")";
        return;
      }
      using Entry = const GisModule* (*)();
      const auto entry = reinterpret_cast<Entry>(::dlsym(handle, "swath_gis_module"));
      const GisModule* m = entry == nullptr ? nullptr : entry();
      if (m == nullptr || m->abi != kGisModuleAbi) {
        failure = "the GIS module " + path.string() +
                  " belongs to another build of swath (rebuild it, or unset SWATH_GIS_MODULE)";
        return;
      }
      loaded = m;  // open for the life of the process
      return;
    }
    failure = "cannot find the GIS module " + std::string(kModuleFile) + " (looked at " + tried +
              "); GIS files other than GeoJSON, KML and CSV need it";
  });
  // A missing module is an installation fault, not bad input: std::runtime_error (exit 1).
  if (loaded == nullptr) throw std::runtime_error(failure);
  return *loaded;
}

RawField read_ogr(const std::string& path, const FieldReadOptions& options) {
  RawField out;
  std::string error;
  if (!gis_module().read(path, options, out, error)) throw InputError(error);
  return out;
}

std::vector<AreaEntry> list_ogr_areas(const std::string& path, const FieldReadOptions& options) {
  std::vector<AreaEntry> out;
  std::string error;
  if (!gis_module().list(path, options, out, error)) throw InputError(error);
  return out;
}

std::size_t area_reads(const std::string& path) {
  return gis_module().area_reads(path);
}

RawField parse_wkt(const std::string& text, const std::string& source) {
  RawField out;
  std::string error;
  if (!gis_module().wkt(text, source, out, error)) throw InputError(error);
  return out;
}

}  // namespace swath::geometry::detail
