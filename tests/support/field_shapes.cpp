#include "field_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "swath/geometry/classification.hpp"
#include "swath/geometry/predicates.hpp"

namespace swath::test {

using geometry::Point2;
using geometry::Polygon;
using geometry::Ring;

namespace {

double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}
int uniform_int(Rng& rng, int lo, int hi) {
  return std::uniform_int_distribution<int>(lo, hi)(rng);
}

// Turned by a random angle about the origin; holes clockwise.
Polygon turned(Rng& rng, Polygon p) {
  const double angle_deg = uniform(rng, 0, 180);
  p.outer = transformed(p.outer, angle_deg, 0, 0);
  for (Ring& h : p.holes) {
    h = transformed(h, angle_deg, 0, 0);
    if (geometry::signed_area(h) > 0) std::reverse(h.begin(), h.end());
  }
  return p;
}

// Moved so that its bounding box is centred on the origin.
Ring centred(Ring ring) {
  double x0 = ring[0].x, x1 = x0, y0 = ring[0].y, y1 = y0;
  for (const Point2& p : ring) {
    x0 = std::min(x0, p.x);
    x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y);
    y1 = std::max(y1, p.y);
  }
  return transformed(ring, 0, -(x0 + x1) / 2, -(y0 + y1) / 2);
}

double boundary_distance(Point2 p, const Ring& ring) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < ring.size(); ++i)
    best = std::min(best, geometry::distance_to_segment(p, ring[i], ring[(i + 1) % ring.size()]));
  return best;
}

// The ring as a GPS track of it looks: every edge resampled about every `spacing_m` metres (its
// corners kept, as a walker turns there) and moved off the edge by an error of `jitter_m` (standard
// deviation) that drifts slowly from one vertex to the next, as a receiver's does (an AR(1) walk),
// so that neighbouring vertices stay nearly collinear. May cross itself where the ring is sharp:
// the caller checks.
Ring gps_trace(Rng& rng, const Ring& ring, double spacing_m, double jitter_m) {
  const double keep = 0.95;  // of the error from one vertex to the next
  std::normal_distribution<double> innovation(0, jitter_m * std::sqrt(1 - keep * keep));
  Point2 error{0, 0};
  Ring out;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point2 a = ring[i], b = ring[(i + 1) % ring.size()];
    const double length = geometry::distance(a, b);
    const int steps = std::max(1, int(std::lround(length / spacing_m)));
    for (int k = 0; k < steps; ++k) {
      error = error * keep + Point2{innovation(rng), innovation(rng)};
      out.push_back(a + (b - a) * (double(k) / steps) + error);
    }
  }
  return out;
}

// A narrow arm (a strip `width_m` wide, `reach_m` long, slightly slanted) jutting out of the
// middle of edge `i` of a counter-clockwise ring.
Ring with_arm(const Ring& ring, std::size_t i, double width_m, double reach_m, double lean_m) {
  const Point2 a = ring[i], b = ring[(i + 1) % ring.size()];
  const double length = geometry::distance(a, b);
  const Point2 u = (b - a) * (1 / length), out{u.y, -u.x};
  const double t = (length - width_m) / 2;
  Ring r(ring.begin(), ring.begin() + std::ptrdiff_t(i) + 1);
  r.push_back(a + u * t);
  r.push_back(a + u * (t + lean_m) + out * reach_m);
  r.push_back(a + u * (t + lean_m + width_m) + out * reach_m);
  r.push_back(a + u * (t + width_m));
  r.insert(r.end(), ring.begin() + std::ptrdiff_t(i) + 1, ring.end());
  return r;
}

bool simple(const Polygon& p) {
  return !geometry::find_crossing(p).has_value();
}

// The coarse outline of a traced field: a concave random walk scaled to `across_m`, centred, with
// 0-2 narrow arms (an arm that would cross the outline is left out).
Ring coarse_outline(Rng& rng, double across_m) {
  Ring ring = random_walk_outline(rng, std::size_t(uniform_int(rng, 12, 40))).outer;
  double x0 = ring[0].x, x1 = x0, y0 = ring[0].y, y1 = y0;
  for (const Point2& p : ring) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  const double scale = across_m / std::max(x1 - x0, y1 - y0);
  for (Point2& p : ring) p = p * scale;
  ring = centred(ring);
  for (int arms = uniform_int(rng, 0, 2); arms > 0; --arms) {
    const std::size_t i = std::size_t(uniform_int(rng, 0, int(ring.size()) - 1));
    const double width = uniform(rng, 20, 70), reach = uniform(rng, 0.1, 0.35) * across_m;
    if (geometry::distance(ring[i], ring[(i + 1) % ring.size()]) < width + 20) continue;
    Ring armed = with_arm(ring, i, width, reach, uniform(rng, -0.3, 0.3) * reach);
    if (simple({armed, {}})) ring = std::move(armed);
  }
  return ring;
}

// 1-4 traced holes (round ponds, rectangular buildings) at least 20 m from the outline and from
// each other, clockwise.
std::vector<Ring> traced_holes(Rng& rng, const Ring& outer, double spacing_m, double jitter_m) {
  double x0 = outer[0].x, x1 = x0, y0 = outer[0].y, y1 = y0;
  for (const Point2& p : outer) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  std::vector<Ring> holes;
  std::vector<std::pair<Point2, double>> placed;  // centre, radius
  const int wanted = uniform_int(rng, 1, 4);
  for (int attempt = 0; attempt < 300 && int(placed.size()) < wanted; ++attempt) {
    const bool pond = uniform_int(rng, 0, 1) == 0;
    const double size = uniform(rng, 15, 60), radius = pond ? size : size * std::sqrt(2.0);
    const Point2 c{uniform(rng, x0, x1), uniform(rng, y0, y1)};
    if (geometry::locate_point(c, outer) != geometry::Containment::inside ||
        boundary_distance(c, outer) < radius + 20)
      continue;
    bool apart = true;
    for (const auto& [other, other_radius] : placed)
      apart &= geometry::distance(c, other) >= radius + other_radius + 20;
    if (!apart) continue;
    Ring hole;
    if (pond) {
      const int n = std::max(12, int(2 * std::numbers::pi * size / spacing_m));
      const double phase = uniform(rng, 0, 2 * std::numbers::pi);
      for (int k = 0; k < n; ++k) {
        const double t = phase + 2 * std::numbers::pi * k / n;
        const double rr = size * (1 + 0.15 * std::sin(2 * t)) + uniform(rng, -jitter_m, jitter_m);
        hole.push_back(c + Point2{rr * std::cos(t), rr * std::sin(t)});
      }
    } else {  // a building, drawn by its corners
      const double a = size, b = size * uniform(rng, 0.4, 1.0), turn = uniform(rng, 0, 90);
      hole = transformed({{-a, -b}, {a, -b}, {a, b}, {-a, b}}, turn, c.x, c.y);
    }
    std::reverse(hole.begin(), hole.end());
    holes.push_back(hole);
    placed.push_back({c, radius});
  }
  return holes;
}

}  // namespace

Polygon traced_outline(Rng& rng) {
  const double across_m = 300 * std::pow(10.0, uniform(rng, 0, 1));  // 0.3-3 km, log-uniform
  const Ring coarse = coarse_outline(rng, across_m);
  const double vertices = uniform(rng, 150, 900);
  const double spacing_m = std::clamp(geometry::perimeter(coarse) / vertices, 2.0, 12.0);
  double jitter_m = std::min(uniform(rng, 0.2, 1.2), 0.15 * spacing_m);
  const bool with_holes = uniform(rng, 0, 1) < 0.4;
  for (int attempt = 1;; ++attempt) {
    Polygon p{gps_trace(rng, coarse, spacing_m, jitter_m), {}};
    if (with_holes) p.holes = traced_holes(rng, p.outer, spacing_m, jitter_m);
    if (simple(p)) return turned(rng, p);
    if (attempt % 5 == 0) jitter_m /= 2;  // a sharp corner the jitter keeps folding
  }
}

Polygon ragged_strip(Rng& rng) {
  const double length = uniform(rng, 250, 1400), width = uniform(rng, 60, 300);
  Ring ring{{0, 0}};
  for (double x = uniform(rng, 20, 60); x < length - 20; x += uniform(rng, 20, 60))
    ring.push_back({x, uniform(rng, -15, 15)});
  ring.push_back({length, 0});
  ring.push_back({length, width});
  for (double x = length - uniform(rng, 20, 60); x > 20; x -= uniform(rng, 20, 60))
    ring.push_back({x, width + uniform(rng, -15, 15)});
  ring.push_back({0, width});
  return turned(rng, {centred(ring), {}});
}

Polygon notched_rectangle(Rng& rng) {
  const double w = uniform(rng, 300, 600), h = uniform(rng, 200, 400);
  const Point2 corners[4] = {{0, 0}, {w, 0}, {w, h}, {0, h}};
  // Each side: nothing, a notch (in its middle 30-70 %, at most a quarter of the other dimension
  // deep, so notches of neighbouring sides never meet) or a sliver jutting out.
  int slivers = uniform_int(rng, 0, 2), notches = uniform_int(rng, 1, 4);
  Ring ring;
  for (int side = 0; side < 4; ++side) {
    const Point2 a = corners[side], b = corners[(side + 1) % 4];
    const double side_length = geometry::distance(a, b), other = side % 2 == 0 ? h : w;
    const Point2 u = (b - a) * (1 / side_length), n{-u.y, u.x};  // n points inwards
    ring.push_back(a);
    const int kind = notches > 0 && (slivers == 0 || uniform_int(rng, 0, 1) == 0) ? 1
                     : slivers > 0                                                ? 2
                                                                                  : 0;
    if (kind == 1) {
      --notches;
      const double width = std::min(uniform(rng, 40, 150), 0.4 * side_length);
      const double t = uniform(rng, 0.3 * side_length, 0.7 * side_length - width);
      const double depth = uniform(rng, 0.3, 1.0) * 0.25 * other;
      if (uniform_int(rng, 0, 1) == 0) {  // rectangular
        ring.push_back(a + u * t);
        ring.push_back(a + u * t + n * depth);
        ring.push_back(a + u * (t + width) + n * depth);
      } else {  // slanted: a triangle with its apex off centre
        ring.push_back(a + u * t);
        ring.push_back(a + u * (t + uniform(rng, 0.2, 0.8) * width) + n * depth);
      }
      ring.push_back(a + u * (t + width));
    } else if (kind == 2) {
      --slivers;
      const double width = uniform(rng, 10, 25), reach = uniform(rng, 60, 160);
      const double t = uniform(rng, 0.1 * side_length, 0.9 * side_length - width);
      const double lean = uniform(rng, -0.5, 0.5) * reach;  // slanted slivers too
      ring.push_back(a + u * t);
      ring.push_back(a + u * (t + lean) - n * reach);
      ring.push_back(a + u * (t + lean + width) - n * reach);
      ring.push_back(a + u * (t + width));
    }
  }
  return turned(rng, {centred(ring), {}});
}

Polygon random_comb(Rng& rng) {
  const int teeth = uniform_int(rng, 2, 6);
  return turned(rng, {centred(comb_polygon(teeth, uniform(rng, 30, 80), uniform(rng, 150, 400),
                                           uniform(rng, 30, 80))),
                      {}});
}

Polygon l_or_t_shape(Rng& rng) {
  const double w1 = uniform(rng, 80, 250), w2 = uniform(rng, 80, 250);
  const double l1 = uniform(rng, std::max(250.0, w2 + 60), 700),
               l2 = uniform(rng, std::max(250.0, w1 + 60), 700);
  Ring ring;
  if (uniform_int(rng, 0, 1) == 0)  // L: an arm along x (w1 wide) and one along y (w2 wide)
    ring = {{0, 0}, {l1, 0}, {l1, w1}, {w2, w1}, {w2, l2}, {0, l2}};
  else  // T: a stem w2 wide and l2 long under a bar w1 wide and l1 long
    ring = {{-w2 / 2, 0},      {w2 / 2, 0},        {w2 / 2, l2},  {l1 / 2, l2},
            {l1 / 2, l2 + w1}, {-l1 / 2, l2 + w1}, {-l1 / 2, l2}, {-w2 / 2, l2}};
  return turned(rng, {centred(ring), {}});
}

Polygon field_with_holes(Rng& rng) {
  const double r = uniform(rng, 200, 400);
  Polygon p{random_field_polygon(rng, std::size_t(uniform_int(rng, 12, 60)), r), {}};
  std::vector<std::pair<Point2, double>> placed;  // centre, radius
  const int wanted = uniform_int(rng, 1, 5);
  for (int attempt = 0; attempt < 200 && int(placed.size()) < wanted; ++attempt) {
    const bool pond = uniform_int(rng, 0, 1) == 0;
    const double size = pond ? uniform(rng, 15, 45) : uniform(rng, 15, 60);
    const double radius = pond ? size : size * std::sqrt(2.0);
    const Point2 c{uniform(rng, -1.3 * r, 1.3 * r), uniform(rng, -1.3 * r, 1.3 * r)};
    if (geometry::locate_point(c, p.outer) != geometry::Containment::inside ||
        boundary_distance(c, p.outer) < radius + 20)
      continue;
    bool apart = true;
    for (const auto& [other, other_radius] : placed)
      apart &= geometry::distance(c, other) >= radius + other_radius + 20;
    if (!apart) continue;
    Ring hole;
    if (pond) {
      const int n = uniform_int(rng, 8, 24);
      for (int k = 0; k < n; ++k) {
        const double t = 2 * std::numbers::pi * k / n;
        const double rr = size * uniform(rng, 0.8, 1.0);
        hole.push_back(c + Point2{rr * std::cos(t), rr * std::sin(t)});
      }
    } else {
      const double a = size, b = size * uniform(rng, 0.4, 1.0), turn = uniform(rng, 0, 90);
      hole = transformed({{-a, -b}, {a, -b}, {a, b}, {-a, b}}, turn, c.x, c.y);
    }
    std::reverse(hole.begin(), hole.end());
    p.holes.push_back(hole);
    placed.push_back({c, radius});
  }
  return turned(rng, p);
}

Polygon random_walk_outline(Rng& rng, std::size_t n) {
  // A closed random walk of the log radius: steps, drift removed so it closes, smoothed by a
  // circular moving average, scaled to a standard deviation of 0.3.
  const int m = 360, smooth = 12;
  std::normal_distribution<double> step(0, 1);
  std::vector<double> walk(m + 1, 0.0);
  for (int i = 1; i <= m; ++i) walk[i] = walk[i - 1] + step(rng);
  std::vector<double> closed(m);
  for (int i = 0; i < m; ++i) closed[i] = walk[i] - walk[m] * i / m;
  std::vector<double> w(m, 0.0);
  for (int i = 0; i < m; ++i) {
    for (int k = -smooth; k <= smooth; ++k) w[i] += closed[((i + k) % m + m) % m];
    w[i] /= 2 * smooth + 1;
  }
  double mean = 0, var = 0;
  for (double x : w) mean += x / m;
  for (double x : w) var += (x - mean) * (x - mean) / m;
  const double scale = var > 0 ? 0.3 / std::sqrt(var) : 0;
  const double r = uniform(rng, 100, 250), squash = uniform(rng, 1, 2);
  Ring ring;
  for (std::size_t j = 0; j < n; ++j) {
    const double t = (double(j) + uniform(rng, -0.3, 0.3)) / double(n);  // fraction of a turn
    const double at = t * m;
    const int i0 = int(std::floor(at));
    const double f = at - i0;
    const double lw = (1 - f) * w[((i0 % m) + m) % m] + f * w[(((i0 + 1) % m) + m) % m];
    const double radius = r * std::exp(scale * (lw - mean));
    const double angle = 2 * std::numbers::pi * t;
    ring.push_back({squash * radius * std::cos(angle), radius * std::sin(angle)});
  }
  return turned(rng, {ring, {}});
}

std::vector<CorpusShape> split_corpus(std::uint64_t seed, int per_family) {
  std::vector<CorpusShape> corpus;
  auto family = [&](const std::string& name, std::uint64_t stream, auto make) {
    Rng rng(seed * 1000003 + stream);
    for (int i = 0; i < per_family; ++i) corpus.push_back({name, i, make(rng, i)});
  };
  family("ragged-strip", 1, [](Rng& rng, int) { return ragged_strip(rng); });
  family("notched", 2, [](Rng& rng, int) { return notched_rectangle(rng); });
  family("comb", 3, [](Rng& rng, int) { return random_comb(rng); });
  family("l-t", 4, [](Rng& rng, int) { return l_or_t_shape(rng); });
  family("holes", 5, [](Rng& rng, int) { return field_with_holes(rng); });
  family("walk", 6, [per_family](Rng& rng, int i) {
    const std::size_t n =
        per_family > 1 ? 5 + std::size_t(std::lround(145.0 * i / (per_family - 1))) : 40;
    return random_walk_outline(rng, n);
  });
  return corpus;
}

}  // namespace swath::test
