#pragma once

#include <cstdlib>
#include <filesystem>

namespace swath::apps {

/// Where swath's data lives (cameras, examples): $SWATH_SHARE_DIR, else the build's share/.
inline std::filesystem::path share_dir() {
  if (const char* env = std::getenv("SWATH_SHARE_DIR"); env && *env) return env;
  return SWATH_SHARE_DIR;
}

}  // namespace swath::apps
