#pragma once
// Reading whole input files, with the size capped so that a wrong path (/dev/zero, a disk image)
// is refused at once instead of filling memory.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>

namespace swath::base {

/// Area files, missions, plans and power traces: 1,000,000 vertices of GeoJSON fit in ~60 MiB.
inline constexpr std::size_t kMaxDataFileBytes = std::size_t{256} << 20;
/// YAML and other hand-written configuration (cameras, fleets, drones, vehicles, schedulers).
inline constexpr std::size_t kMaxConfigFileBytes = std::size_t{4} << 20;

/// The whole file at `path`. `what` names what it should be ("area file", "fleet file") for the
/// messages. Throws InputError "<path>: cannot open the <what> (<reason>)", "<path>: is a
/// directory, not a <what>", or "<path>: the <what> is larger than swath's limit of N MiB" (read
/// stops at the limit, so endless files such as /dev/zero are refused too).
std::string read_text_file(const std::filesystem::path& path, std::string_view what,
                           std::size_t max_bytes = kMaxDataFileBytes);

/// 1-based line and column of byte `offset` in `text` (offsets past the end count to the end).
std::pair<int, int> line_column(std::string_view text, std::size_t offset);

}  // namespace swath::base
