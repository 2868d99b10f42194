#pragma once
// A uniform grid over a fixed set of segments (an area's edges): which of them a segment, a box or
// the ray to the right of a point may meet. It only prunes: callers decide on the candidates with
// the same exact predicates as without it, so answers do not change, only the work.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "swath/geometry/point.hpp"

namespace swath::geometry {

struct Segment {
  Point2 a, b;
};

class SegmentIndex {
 public:
  SegmentIndex() = default;
  /// `segments`: finite coordinates, any unit (metres in swath); fewer than 2^31. The grid has
  /// about `cells_per_segment` (> 0) square cells per segment over their bounding box, at most
  /// 4096 a side.
  explicit SegmentIndex(std::vector<Segment> segments, double cells_per_segment = 4);

  const std::vector<Segment>& segments() const { return segments_; }

  /// Calls f(i) for the segments i that may share a point with the closed segment [a, b]: every
  /// segment that does is among them; one may come more than once (a segment across several rows
  /// of cells), so f must not count.
  template <typename F>
  void near_segment(Point2 a, Point2 b, F f) const {
    if (segments_.empty()) return;
    rows_of(a, b, [&](std::size_t r, std::size_t c0, std::size_t c1) {
      for (std::uint32_t k = start_[r * columns_ + c0], end = start_[r * columns_ + c1 + 1];
           k < end; ++k)
        f(items_[k] & kIndex);
    });
  }
  /// The same for the closed box [lo, hi] (lo <= hi componentwise).
  template <typename F>
  void near_box(Point2 lo, Point2 hi, F f) const {
    if (segments_.empty()) return;
    const std::size_t c0 = column(lo.x), c1 = column(hi.x);
    for (std::size_t r = row(lo.y), r1 = row(hi.y); r <= r1; ++r)
      for (std::uint32_t k = start_[r * columns_ + c0], end = start_[r * columns_ + c1 + 1];
           k < end; ++k)
        f(items_[k] & kIndex);
  }
  /// Calls f(i) once each for the segments i that may share a point with the closed horizontal ray
  /// from p towards +x (every one that does among them): point location by counting crossings.
  template <typename F>
  void near_ray_right(Point2 p, F f) const {
    if (segments_.empty()) return;
    // p's row's segments, each once, by descending greatest abscissa, up to the first wholly left
    // of p (it and those after it neither hold p nor cross the ray).
    const std::size_t r = row(p.y);
    for (const RayEntry *k = by_right_.data() + ray_start_[r],
                        *end = by_right_.data() + ray_start_[r + 1];
         k != end && !(k->x < p.x); ++k)
      f(k->index);
  }
  /// The same for the ray towards -x: the row's segments by ascending least abscissa, up to the
  /// first wholly right of p.
  template <typename F>
  void near_ray_left(Point2 p, F f) const {
    if (segments_.empty()) return;
    const std::size_t r = row(p.y);
    for (const RayEntry *k = by_left_.data() + ray_start_[r],
                        *end = by_left_.data() + ray_start_[r + 1];
         k != end && !(k->x > p.x); ++k)
      f(k->index);
  }
  /// Either near_ray_right(p, right) or near_ray_left(p, left), whichever walks fewer segments
  /// about (p left of its row's split abscissa: the ray to the left); true when to the left.
  template <typename Right, typename Left>
  bool near_ray(Point2 p, Right right, Left left) const {
    if (segments_.empty()) return false;
    const std::size_t r = row(p.y);
    if (p.x < ray_split_[r]) {
      for (const RayEntry *k = by_left_.data() + ray_start_[r],
                          *end = by_left_.data() + ray_start_[r + 1];
           k != end && !(k->x > p.x); ++k)
        left(k->index);
      return true;
    }
    for (const RayEntry *k = by_right_.data() + ray_start_[r],
                        *end = by_right_.data() + ray_start_[r + 1];
         k != end && !(k->x < p.x); ++k)
      right(k->index);
    return false;
  }

 private:
  static constexpr std::uint32_t kFirstInRow = 0x80000000u;
  static constexpr std::uint32_t kIndex = 0x7fffffffu;

  // Cell column and row of a coordinate, clamped to the grid. Monotone: floating-point subtraction
  // and multiplication round monotonically, so a point of a segment's bounding box never falls in
  // a column outside the columns of the box's corners.
  std::size_t column(double x) const {
    const double f = (x - x0_) * inv_w_;
    if (!(f > 0)) return 0;  // left of the grid (or NaN)
    if (f >= double(columns_ - 1)) return columns_ - 1;
    return std::size_t(f);
  }
  std::size_t row(double y) const {
    const double f = (y - y0_) * inv_h_;
    if (!(f > 0)) return 0;
    if (f >= double(rows_ - 1)) return rows_ - 1;
    return std::size_t(f);
  }
  // Calls visit(row, first column, last column) for each row the closed segment [a, b] passes
  // through, every cell that holds one of its points among those columns, and those within a
  // thousandth of a cell of it: segments registered and asked for this way are found when they
  // come within rounding of each other, not only when they share a point (a leg a hair beside an
  // edge that lies on a cell boundary; VisibilityRouter cuts a leg where an edge's end is within
  // rounding of it).
  template <typename Visit>
  void rows_of(Point2 a, Point2 b, Visit visit) const {
    const double margin_y = 1e-3 * cell_h_ + 1e-12 * (std::abs(a.y) + std::abs(b.y));
    const double margin_x = 1e-3 * cell_w_ + 1e-12 * (std::abs(a.x) + std::abs(b.x));
    const double x_lo = std::min(a.x, b.x) - margin_x, x_hi = std::max(a.x, b.x) + margin_x;
    const double y_lo = std::min(a.y, b.y) - margin_y, y_hi = std::max(a.y, b.y) + margin_y;
    const std::size_t r0 = row(y_lo), r1 = row(y_hi);
    if (r0 == r1) {
      visit(r0, column(x_lo), column(x_hi));
      return;
    }
    // Rows differ. A row's points have ordinates within its bounds up to rounding (~1e-16 of the
    // coordinates), their abscissae too: the margins are far wider, and cost an extra cell now
    // and then.
    const double dx = b.x - a.x, dy = b.y - a.y;
    if (dy == 0) {  // a horizontal segment across rows only by the margin
      for (std::size_t r = r0; r <= r1; ++r) visit(r, column(x_lo), column(x_hi));
      return;
    }
    for (std::size_t r = r0; r <= r1; ++r) {
      const double bottom = r == r0 ? y_lo : y0_ + double(r) * cell_h_ - margin_y;
      const double top = r == r1 ? y_hi : y0_ + double(r + 1) * cell_h_ + margin_y;
      const double t0 = std::clamp((bottom - a.y) / dy, 0.0, 1.0);
      const double t1 = std::clamp((top - a.y) / dy, 0.0, 1.0);
      const double u = a.x + t0 * dx, v = a.x + t1 * dx;
      const std::size_t c0 = column(std::max(x_lo, std::min(u, v) - margin_x));
      const std::size_t c1 = column(std::min(x_hi, std::max(u, v) + margin_x));
      visit(r, std::min(c0, c1), std::max(c0, c1));
    }
  }

  std::vector<Segment> segments_;
  double x0_ = 0, y0_ = 0;                  ///< the grid's lower left corner
  double cell_w_ = 0, cell_h_ = 0;          ///< cell size (0 along a flat extent)
  double inv_w_ = 0, inv_h_ = 0;            ///< 1 / cell size (0 along a flat extent)
  std::size_t columns_ = 1, rows_ = 1;      ///< >= 1 each
  std::vector<std::uint32_t> start_{0, 0};  ///< per cell (row major), its first item; + the end
  /// Segment indices, ascending within a cell; kFirstInRow marks a segment's first column in a row.
  std::vector<std::uint32_t> items_;
  /// A row's segment for the rays: its greatest abscissa (by_right_) or least (by_left_).
  struct RayEntry {
    double x;
    std::uint32_t index;
  };
  /// Per row, its segments once each: row r's from ray_start_[r] to ray_start_[r + 1] of by_right_
  /// (by descending greatest abscissa) and by_left_ (by ascending least). A ray walks the segments
  /// that reach past p only, not every cell of the row on its side with the segments in it.
  std::vector<std::uint32_t> ray_start_{0, 0};
  std::vector<RayEntry> by_right_, by_left_;
  /// Per row, the abscissa left of which near_ray() walks to the left: about as many segments
  /// reach past it either way (the middle of the middle entries' least and greatest abscissae).
  std::vector<double> ray_split_{0};
};

}  // namespace swath::geometry
