// Opens the drawing module on first use and forwards the public drawing functions to it
// (draw_module.hpp says why the module exists).
#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

#include "draw_module.hpp"
#include "swath/render/image.hpp"

namespace swath::render {
namespace {

constexpr const char* kModuleFile = "libswath_draw.so";

// Where to look, in order: $SWATH_RENDER_MODULE, beside the program, the
// installed tree's lib/swath/, the build tree.
std::vector<std::filesystem::path> candidates() {
  std::vector<std::filesystem::path> out;
  if (const char* env = std::getenv("SWATH_RENDER_MODULE"); env != nullptr && *env != '\0')
    out.emplace_back(env);
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    out.push_back(exe.parent_path() / kModuleFile);
    // An installed program: PREFIX/bin/PROGRAM and PREFIX/lib/swath/ (docs/install.md).
    out.push_back(exe.parent_path().parent_path() / "lib" / "swath" / kModuleFile);
  }
  out.emplace_back(SWATH_RENDER_MODULE_BUILD_PATH);
  return out;
}

const detail::DrawModule& module() {
  static const detail::DrawModule* loaded = nullptr;
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
        failure = "cannot load the drawing module " + path.string() + " (" + ::dlerror() + ")";
        return;
      }
      using Entry = const detail::DrawModule* (*)();
      const auto entry = reinterpret_cast<Entry>(::dlsym(handle, "swath_draw_module"));
      const detail::DrawModule* m = entry == nullptr ? nullptr : entry();
      if (m == nullptr || m->abi != detail::kDrawModuleAbi) {
        failure = "the drawing module " + path.string() +
                  " belongs to another build of swath (rebuild it, or unset SWATH_RENDER_MODULE)";
        return;
      }
      loaded = m;  // the handle stays open for the life of the process
      return;
    }
    failure =
        "cannot find the drawing module " + std::string(kModuleFile) + " (looked at " + tried + ")";
  });
  if (loaded == nullptr) throw RenderError(failure);
  return *loaded;
}

template <typename Call>
void call(Call&& f) {
  std::string error;
  if (!f(module(), error)) throw RenderError(error);
}

}  // namespace

Image draw(const Scene& scene, const View& view) {
  Image out;
  call([&](const detail::DrawModule& m, std::string& e) { return m.draw(scene, view, out, e); });
  return out;
}

std::string encode_png(const Image& image) {
  std::string out;
  call([&](const detail::DrawModule& m, std::string& e) { return m.encode_png(image, out, e); });
  return out;
}

Image decode_png(const std::string& png) {
  Image out;
  call([&](const detail::DrawModule& m, std::string& e) { return m.decode_png(png, out, e); });
  return out;
}

TextExtent text_extent(const std::string& text, double height_px) {
  TextExtent out;
  call([&](const detail::DrawModule& m, std::string& e) {
    return m.text_extent(text, height_px, out, e);
  });
  return out;
}

}  // namespace swath::render
