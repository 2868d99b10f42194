#pragma once

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace swath::apps {

/// Where swath's data lives (cameras, fields, worlds, ...), in order: $SWATH_SHARE_DIR; the
/// installed tree's PREFIX/share/swath when the program runs as PREFIX/bin/PROGRAM (so an installed
/// or unpacked tree works wherever it is moved); the source tree's share/ for in-tree runs.
inline std::filesystem::path share_dir() {
  if (const char* env = std::getenv("SWATH_SHARE_DIR"); env && *env) return env;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    // Checked by its cameras/ folder: an unrelated PREFIX/share/swath is not taken for ours.
    const std::filesystem::path installed = exe.parent_path().parent_path() / "share" / "swath";
    if (std::filesystem::is_directory(installed / "cameras", ec)) return installed;
  }
  return SWATH_SHARE_DIR;
}

}  // namespace swath::apps
