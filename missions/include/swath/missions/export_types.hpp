#pragma once
// Values the mission writers (writers.hpp) share with the planner that fills them: how the camera
// is triggered, and which aircraft and payload a DJI camera is.

namespace swath::missions {

/// How photos are taken on the lines.
enum class TriggerMode {
  distance,  ///< the autopilot triggers every trigger distance (DO_SET_CAM_TRIGG_DIST)
  time,      ///< every trigger distance / speed seconds (IMAGE_START_CAPTURE / STOP)
  hover,     ///< stop at each photo point and shoot (a waypoint with a hold, then one shot)
};

/// The aircraft and payload a DJI camera is, as DJI WPML names them (`wpml:droneInfo`,
/// `wpml:payloadInfo`): the `type` / `sub_type` numbers of DJI Cloud API's product table, e.g.
/// Mavic 3 Enterprise: drone 77, sub-type 0, payload 66. Integers in [0, 65535].
struct DjiEnums {
  int drone = 0;      ///< droneEnumValue: 60 M300 RTK, 89 M350 RTK, 67 M30, 77 Mavic 3E/T/M, 91 M3D
  int drone_sub = 0;  ///< droneSubEnumValue: e.g. 0 M3E, 1 M3T, 2 M3M
  int payload = 0;    ///< payloadEnumValue: e.g. 66 Mavic 3E camera, 50 Zenmuse P1
};

}  // namespace swath::missions
