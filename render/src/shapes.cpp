#include "shapes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace swath::render::detail {

using geometry::Point2;

Ring positive(Ring ring) {
  double twice_area = 0;
  for (std::size_t i = 0; i < ring.size(); ++i)
    twice_area += geometry::cross(ring[i], ring[(i + 1) % ring.size()]);
  if (twice_area < 0) std::reverse(ring.begin(), ring.end());
  return ring;
}

Ring disc(Point2 centre, double radius_px) {
  // A chord of n sides lies r (1 - cos(pi / n)) ~ r pi^2 / (2 n^2) inside the circle: <= 0.01 px.
  const double r = std::abs(radius_px);
  if (!std::isfinite(r) || !std::isfinite(centre.x) || !std::isfinite(centre.y)) return {};
  // Clamped as a double before the cast (a radius of 1e20 px is still 512 sides).
  const int n =
      static_cast<int>(std::clamp(std::ceil(std::numbers::pi * std::sqrt(r / 0.02)), 8.0, 512.0));
  Ring ring;
  ring.reserve(n);
  for (int k = 0; k < n; ++k) {
    const double t = 2 * std::numbers::pi * k / n;
    ring.push_back({centre.x + r * std::cos(t), centre.y + r * std::sin(t)});
  }
  return ring;  // counter-clockwise in y-down pixels: positive area
}

Ring band(Point2 a, Point2 b, double width_px) {
  const Point2 d = b - a;
  const double length = std::hypot(d.x, d.y);  // no overflow of the square for far points
  if (!(length > 0) || !std::isfinite(length)) return {};
  const Point2 n{-d.y / length * width_px / 2, d.x / length * width_px / 2};
  return positive({a + n, b + n, b - n, a - n});
}

namespace {

// What a round join adds to the two segments' quads at p: the wedge on the outer side of the turn
// from direction u1 to u2 (unit vectors), its arc within 0.05 px of the circle. The inner side is
// already covered where the quads overlap.
Ring join_wedge(Point2 p, Point2 u1, Point2 u2, double radius_px) {
  const double turn = geometry::cross(u1, u2);
  const double angle = std::acos(std::clamp(geometry::dot(u1, u2), -1.0, 1.0));
  if (angle < 1e-9) return {};
  const double side = turn > 0 ? -1 : 1, sweep = turn > 0 ? angle : -angle;
  if (!(angle < 1e9) || !std::isfinite(radius_px)) return {};  // NaN or infinite: no wedge
  const double step = radius_px <= 0.05 ? std::numbers::pi : 2 * std::acos(1 - 0.05 / radius_px);
  // At most 256 pieces a join (as many as a disc's half): a very wide line's joins stay bounded
  // in size, their arc then within radius x (1 - cos(pi / 512)) of the circle.
  const int pieces = static_cast<int>(std::clamp(std::ceil(angle / step), 1.0, 256.0));
  const double start = std::atan2(side * u1.x, side * -u1.y);  // the angle of side * n1
  Ring wedge{p};
  for (int k = 0; k <= pieces; ++k) {
    const double t = start + sweep * k / pieces;
    wedge.push_back({p.x + radius_px * std::cos(t), p.y + radius_px * std::sin(t)});
  }
  return positive(std::move(wedge));
}

Point2 unit(Point2 d) {
  return d * (1 / std::hypot(d.x, d.y));
}

}  // namespace

std::vector<Ring> stroke(const std::vector<Point2>& points, double width_px) {
  // Consecutive repeats dropped: a zero-length segment has no direction.
  std::vector<Point2> line;
  for (const Point2& p : points)
    if (line.empty() || !(p == line.back())) line.push_back(p);
  std::vector<Ring> rings;
  for (std::size_t i = 0; i + 1 < line.size(); ++i)
    rings.push_back(band(line[i], line[i + 1], width_px));
  // Round joins; flat ends, so that a bar is as long as it claims.
  const auto join = [&](Point2 before, Point2 at, Point2 after) {
    Ring wedge = join_wedge(at, unit(at - before), unit(after - at), width_px / 2);
    if (!wedge.empty()) rings.push_back(std::move(wedge));
  };
  for (std::size_t i = 1; i + 1 < line.size(); ++i) join(line[i - 1], line[i], line[i + 1]);
  if (line.size() > 3 && line.front() == line.back())
    join(line[line.size() - 2], line.front(), line[1]);
  return rings;
}

namespace {

// The part [s0, s1] (distances from a) of the segment a + s u, 0 <= s <= length, inside the box
// [lo, hi] (Liang-Barsky); s0 > s1 when it misses the box.
std::pair<double, double> inside_part(Point2 a, Point2 u, double length, Point2 lo, Point2 hi) {
  double s0 = 0, s1 = length;
  const auto limit = [&](double start, double step, double low, double high) {
    if (step == 0) {
      if (start < low || start > high) s0 = 1, s1 = 0;
      return;
    }
    const double ta = (low - start) / step, tb = (high - start) / step;
    s0 = std::max(s0, std::min(ta, tb));
    s1 = std::min(s1, std::max(ta, tb));
  };
  limit(a.x, u.x, lo.x, hi.x);
  limit(a.y, u.y, lo.y, hi.y);
  return {s0, s1};
}

}  // namespace

std::vector<Ring> arrowheads(const std::vector<Point2>& points, double every_px, double size_px,
                             Point2 image_px) {
  std::vector<Ring> rings;
  if (!std::isfinite(every_px) || !std::isfinite(size_px) || every_px <= 0) return rings;
  // No closer than 1 px (nor than 1/64 of their size), and only those that can touch the image:
  // their number is bounded by the length of line inside the image (and their reach round it),
  // whatever the spacing asked or the line's length outside.
  every_px = std::max({every_px, 1.0, std::abs(size_px) / 64});
  const double reach = std::abs(size_px);
  const Point2 lo{-reach, -reach}, hi{image_px.x + reach, image_px.y + reach};
  double walked = 0, next = every_px / 2;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const Point2 a = points[i], b = points[i + 1], d = b - a;
    const double length = std::hypot(d.x, d.y);
    if (!(length > 0) || !std::isfinite(length)) continue;
    const Point2 u = d * (1 / length), n{-u.y, u.x};
    const auto [s0, s1] = inside_part(a, u, length, lo, hi);
    // Arrowheads centred at walked + s0 .. walked + s1 (their tips half a size further on).
    if (s0 <= s1) {
      if (next < walked + s0) next += std::ceil((walked + s0 - next) / every_px) * every_px;
      // Counted, not stepped: far along a long line next + every_px may round back to next.
      const double count = std::floor((walked + s1 - next) / every_px) + 1;
      for (double k = 0; k < std::min(count, s1 - s0 + 2); ++k) {
        const Point2 tip = a + u * (next + k * every_px - walked + size_px / 2);
        const Point2 back = tip - u * size_px;
        rings.push_back(positive({tip, back + n * (size_px / 2), back - n * (size_px / 2)}));
      }
      if (count > 0) next += count * every_px;
    }
    walked += length;
    if (next <= walked) next += (std::floor((walked - next) / every_px) + 1) * every_px;
  }
  return rings;
}

Ring marker(Point2 at, double size_px, MarkerShape shape) {
  const double h = size_px / 2;
  switch (shape) {
    case MarkerShape::disc:
      return disc(at, h);
    case MarkerShape::square:
      return positive(
          {at + Point2{-h, -h}, at + Point2{h, -h}, at + Point2{h, h}, at + Point2{-h, h}});
    case MarkerShape::triangle:
      return positive({at + Point2{0, -h}, at + Point2{h, h}, at + Point2{-h, h}});
  }
  return {};
}

}  // namespace swath::render::detail
