#pragma once
// What a mission's fences take in ArduPilot's fence storage, and whether they fit: ArduPilot
// refuses a fence upload larger than its storage ("Fence exceeds storage size",
// AC_PolyFence_loader::write_fence), and the vehicle then flies with the fence it had before;
// PX4 refuses one of more items than its dataman keeps.

#include <cstddef>
#include <string>
#include <vector>

#include "swath/missions/mission.hpp"

namespace swath::missions {

/// A fence's polygons, their points and its circles, and the bytes ArduPilot stores them in.
struct FenceStorage {
  std::size_t polygons = 0, points = 0, circles = 0;
  std::size_t bytes = 0;
};

/// As AC_PolyFence_loader::fence_storage_space_required counts: a 4-byte header, per polygon a
/// type and a count byte and 8 bytes per point, per circle a type byte and 12 bytes.
FenceStorage ardupilot_fence_storage(const std::vector<std::size_t>& polygon_points,
                                     std::size_t circles);
/// The mission's inclusion and exclusion polygons and circles, each counted once (a
/// fence.waypoints beside a .plan repeats the .plan's fence: one upload, not two).
FenceStorage ardupilot_fence_storage(const Mission& mission);

/// The polygons once each, in their order: a fence.waypoints beside a .plan repeats the .plan's
/// fence (the same fence uploaded either way, not a second one).
std::vector<std::vector<geometry::GeoPoint>> distinct_rings(
    const std::vector<std::vector<geometry::GeoPoint>>& rings);

/// ArduPilot's fence storage on a flight controller of 16 KB or more (StorageManager's layout:
/// 48 + 256 + 256 bytes for ArduCopter, 160 + 256 + 256 for ArduPlane; larger boards keep no more
/// for the fence); BRD_SD_FENCE adds space on the SD card.
inline constexpr std::size_t kArduCopterFenceBytes = 560;
inline constexpr std::size_t kArduPlaneFenceBytes = 672;

/// The fence items PX4 takes in one upload, every polygon's vertices and circles together
/// (dataman's DM_KEY_FENCE_POINTS_MAX): a larger fence is refused (MAV_MISSION_NO_SPACE).
inline constexpr std::size_t kPx4FenceItems = 64;

/// One sentence when the fence is more items than PX4 takes (empty when it is not).
std::string px4_fence_warning(const FenceStorage& storage);

/// One sentence when the fence does not fit (empty when it does), naming the count, the limit and
/// what to do; `fixed_wing` picks ArduPlane's limit.
std::string fence_storage_warning(const FenceStorage& storage, bool fixed_wing);

}  // namespace swath::missions
