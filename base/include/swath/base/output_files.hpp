#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace swath::base {

/// Writes every file into `directory` (created if missing) atomically: each goes to a temporary
/// name in the same directory, is flushed, then renamed over its final name, so a reader sees the
/// old complete file or the new complete file, never a part. Contents are all computed before
/// this is called, so bad input never leaves partial output. Throws std::runtime_error (with the
/// path and the system's reason) if the directory or a file cannot be written; temporaries are
/// removed.
void write_files_atomically(const std::filesystem::path& directory,
                            const std::vector<std::pair<std::string, std::string>>& files);

}  // namespace swath::base
