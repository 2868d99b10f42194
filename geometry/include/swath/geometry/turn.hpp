#pragma once
// A turn of the plane about the origin, its cosine and sine taken once for all the points it
// turns (libm's sincos per point was a sixth of a 10,000-vertex plan's instructions).

#include <cmath>
#include <numbers>

#include "swath/geometry/point.hpp"

namespace swath::geometry {

/// Turns points by `angle_deg` (degrees, counter-clockwise). The same bits as planning::rotate()
/// and as taking the cosine and sine anew per point: the same values and arithmetic, without fused
/// multiply-adds (the project builds with -ffp-contract=off).
class Turn {
 public:
  explicit Turn(double angle_deg) {
    const double t = angle_deg * std::numbers::pi / 180.0;
    c_ = std::cos(t);
    s_ = std::sin(t);
  }
  Point2 operator()(Point2 p) const { return {c_ * p.x - s_ * p.y, s_ * p.x + c_ * p.y}; }
  /// The turned point's ordinate alone.
  double y(Point2 p) const { return s_ * p.x + c_ * p.y; }

 private:
  double c_, s_;
};

}  // namespace swath::geometry
