#pragma once
// Zip archives built in memory (libzip): the DJI KMZ's writer.

#include <string>
#include <utility>
#include <vector>

namespace swath::missions {

/// A zip archive of `entries` (name, bytes) in order, deflated, with a fixed modification time
/// (2020-01-01 00:00 in whatever time zone libzip converts with): same entries, same bytes.
std::string zip_archive(const std::vector<std::pair<std::string, std::string>>& entries);

}  // namespace swath::missions
