#pragma once
// Internal to the file writers: a plan's points in WGS84 as the files write them, converted once
// per point within a set of files.

#include "swath/geometry/point.hpp"
#include "swath/planning/survey.hpp"

namespace swath::planning::files {

/// A local point in WGS84, rounded to 1e-9 degrees as every file writes it. Within a GeoMemo of
/// the plan, each point (by its exact coordinates) is converted once.
geometry::GeoPoint geo(const SurveyPlan& plan, geometry::Point2 p);
/// A WGS84 position rounded to 1e-9 degrees, as every file writes it.
geometry::GeoPoint rounded(const geometry::GeoPoint& g);
/// geo() for a point no other writer converts (a photo's position): never remembered, which would
/// only cost the memo's lookup.
geometry::GeoPoint geo_unshared(const SurveyPlan& plan, geometry::Point2 p);

/// While alive, geo() remembers the positions of `plan`'s points on this thread: the writers of
/// one file set convert the same waypoints, cell corners and fence vertices many times over
/// (LocalFrame::to_geo iterates GeographicLib's Reverse, ~2,000 instructions a point). The answer
/// is the same function's of the same point, so the files are the same bytes. A memo opened while
/// another is alive on the thread leaves that one in charge.
class GeoMemo {
 public:
  explicit GeoMemo(const SurveyPlan& plan);
  ~GeoMemo();
  GeoMemo(const GeoMemo&) = delete;
  GeoMemo& operator=(const GeoMemo&) = delete;

 private:
  bool owner_ = false;
};

}  // namespace swath::planning::files
