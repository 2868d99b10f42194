#pragma once
// The ranges swath accepts for every number a user gives to `swath plan` (docs/reliability.md).
// Each is wide enough for any real survey aircraft and camera, and narrow enough that the work
// the number drives (lines, waypoints, scan steps, files) stays bounded: a value outside is a
// typo or a unit mistake, refused before any work with base::check_range().

#include <string>

#include "swath/base/range_check.hpp"
#include "swath/vehicle/drone.hpp"

namespace swath::planning::limits {

// Camera file (share/cameras/*.yaml keys).
inline constexpr base::Range kSensorSize_mm{0.5, 100, "mm", "phone sensors to medium format"};
inline constexpr base::Range kFocalLength_mm{1, 2000, "mm", "fisheye to long telephoto"};
inline constexpr base::Range kImageSize_px{16, 100'000, "px", "thermal cores to 100 k pixels"};
inline constexpr base::Range kTriggerInterval_s{0, 3600, "s", ""};

// Imaging.
inline constexpr base::Range kAltitude_m{1, 5000, "m", "above any survey aircraft's ceiling"};
inline constexpr base::Range kGsd_cm{0.01, 1000, "cm/px", ""};
/// Both overlaps; 1 would mean photos or lines on top of each other. An overlap given in percent
/// (> 1 and <= 100) gets its own hint.
inline constexpr base::Range kOverlap{0, 0.99, "", "a fraction: 0.8 for 80 %"};
inline constexpr base::Range kDetectionOverlap{0, 1, "", "a fraction, paper 001 eq. 6"};
inline constexpr base::Range kPattern_m{0.01, 1000, "m", ""};
inline constexpr base::Range kMinPixels{1, 10'000, "px", ""};
/// Line spacing and trigger distance that follow from camera, altitude and overlaps.
inline constexpr base::Range kSpacing_m{0.1, 100'000, "m", "closer than 10 cm is no survey"};

// Route.
using vehicle::limits::kSpeed_m_s;
inline constexpr base::Range kTurnaround_m{0, 1000, "m", ""};
inline constexpr base::Range kWaypointSpacing_m{0.5, 100'000, "m", ""};
inline constexpr base::Range kCoverageCell_m{0.01, 1000, "m", ""};
inline constexpr base::Range kTerrainTolerance_m{0.1, 1000, "m", "below 0.1 m a DEM's own error"};
inline constexpr base::Range kAngleStep_deg{0.001, 90, "°", "180,000 scan steps at most"};
inline constexpr base::Range kBearing_deg{-360, 360, "°", ""};

// Flight (docs/swath-plan.md).
inline constexpr base::Range kClearance_m{0, 1000, "m", ""};
inline constexpr base::Range kGimbalPitch_deg{-90, 30, "°", "-90 nadir, 0 level"};
inline constexpr base::Range kFenceMargin_m{0, 10'000, "m", ""};
inline constexpr base::Range kLayerSpacing_m{1, 1000, "m", ""};
inline constexpr base::Range kCeiling_m{1, 10'000, "m", "above home"};
inline constexpr base::Range kBank_deg{5, 60, "°", ""};
inline constexpr base::Range kReserve{0, 0.9, "", "a fraction of the endurance"};

// Fleet: the drone's own (vehicle/drone.hpp).
using vehicle::limits::kBatteryLevel;
using vehicle::limits::kDrones;
using vehicle::limits::kEndurance_s;

/// An overlap: in kOverlap, with the hint "did you mean 0.80?" for one given in percent.
void check_overlap(double value, const std::string& where);

}  // namespace swath::planning::limits
