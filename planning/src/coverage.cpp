#include "swath/planning/coverage.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>

namespace swath::planning {
namespace {

using geometry::Point2;
using Interval = std::pair<double, double>;

// Union of intervals, sorted and merged in place.
void merge(std::vector<Interval>& v) {
  std::sort(v.begin(), v.end());
  std::size_t k = 0;
  for (const Interval& i : v) {
    if (k > 0 && i.first <= v[k - 1].second) {
      v[k - 1].second = std::max(v[k - 1].second, i.second);
    } else {
      v[k++] = i;
    }
  }
  v.resize(k);
}

double length(const std::vector<Interval>& v) {
  double s = 0;
  for (const Interval& i : v) s += i.second - i.first;
  return s;
}

// Length of the intersection of two merged interval lists.
double overlap(const std::vector<Interval>& a, const std::vector<Interval>& b) {
  double s = 0;
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    s += std::max(0.0, std::min(a[i].second, b[j].second) - std::max(a[i].first, b[j].first));
    if (a[i].second < b[j].second) {
      ++i;
    } else {
      ++j;
    }
  }
  return s;
}

struct Edge {
  Point2 lo, hi;  // lo.y <= hi.y
};

// One scanline's strip of height dy: the area inside, the swath, and their overlap.
void add_strip(CoverageMeasure& m, const std::vector<Interval>& inside,
               const std::vector<Interval>& swath, double dy) {
  m.area_m2 += length(inside) * dy;
  m.swath_area_m2 += length(swath) * dy;
  m.covered_area_m2 += overlap(inside, swath) * dy;
}

// The fractions from the sums.
CoverageMeasure finished(CoverageMeasure m) {
  m.covered_fraction = m.area_m2 > 0 ? m.covered_area_m2 / m.area_m2 : 0.0;
  m.outside_fraction =
      m.swath_area_m2 > 0 ? (m.swath_area_m2 - m.covered_area_m2) / m.swath_area_m2 : 0.0;
  return m;
}

}  // namespace

CoverageMeasure measure_coverage(const geometry::Polygon& area, const std::vector<SweepLine>& lines,
                                 double angle_deg, double footprint_width_m, int rows) {
  // Rotate so that the lines run along x; scanlines are then rows of constant y.
  std::vector<Edge> edges;
  double y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
  for (std::size_t r = 0; r < geometry::ring_count(area); ++r) {
    const geometry::Ring& ring = geometry::ring_at(area, r);
    for (std::size_t i = 0; i < ring.size(); ++i) {
      Point2 a = rotate(ring[i], -angle_deg), b = rotate(ring[(i + 1) % ring.size()], -angle_deg);
      if (a.y > b.y) std::swap(a, b);
      if (a.y == b.y) continue;  // horizontal edges never cross a scanline's interior
      edges.push_back({a, b});
      y_min = std::min(y_min, a.y);
      y_max = std::max(y_max, b.y);
    }
  }
  struct Band {
    double y0, y1, x0, x1;
    double y;  // the line itself
  };
  std::vector<Band> bands;
  for (const SweepLine& l : lines) {
    const Point2 a = rotate(l.start, -angle_deg), b = rotate(l.end, -angle_deg);
    const double y = (a.y + b.y) / 2;
    bands.push_back({y - footprint_width_m / 2, y + footprint_width_m / 2, std::min(a.x, b.x),
                     std::max(a.x, b.x), y});
    y_min = std::min(y_min, y - footprint_width_m / 2);
    y_max = std::max(y_max, y + footprint_width_m / 2);
  }
  std::sort(edges.begin(), edges.end(),
            [](const Edge& a, const Edge& b) { return a.lo.y < b.lo.y; });
  std::sort(bands.begin(), bands.end(), [](const Band& a, const Band& b) { return a.y0 < b.y0; });

  // Sample ordinates: between consecutive events (vertex ordinates, footprint band edges) the
  // active edges and bands do not change, so the lengths vary linearly in y (except where an edge
  // crosses a band's end) and the midpoint rule is exact; slabs get rows in proportion to height.
  std::vector<double> events;
  for (const Edge& e : edges) {
    events.push_back(e.lo.y);
    events.push_back(e.hi.y);
  }
  for (const Band& b : bands) {
    events.push_back(b.y0);
    events.push_back(b.y1);
  }
  std::sort(events.begin(), events.end());
  events.erase(std::unique(events.begin(), events.end()), events.end());
  struct Sample {
    double y, weight;
    const Band* line;  // a line's own ordinate (weight 0): measures its length outside the area
  };
  std::vector<Sample> samples;
  const double total = y_max - y_min;
  for (std::size_t k = 0; k + 1 < events.size(); ++k) {
    const double h = events[k + 1] - events[k];
    if (h <= 0) continue;
    const int n = std::max(1, static_cast<int>(std::ceil(rows * h / total)));
    for (int i = 0; i < n; ++i) samples.push_back({events[k] + (i + 0.5) * h / n, h / n, nullptr});
  }
  const auto slab_samples = static_cast<std::ptrdiff_t>(samples.size());
  for (const Band& b : bands) samples.push_back({b.y, 0.0, &b});
  // The slabs' samples come out increasing, the lines' nearly so. Where both runs increase
  // strictly and share no ordinate, the order by y is total: merging the runs gives the order
  // std::sort gives. Otherwise (equal ordinates, whose order std::sort alone decides) std::sort.
  const auto by_y = [](const Sample& a, const Sample& b) { return a.y < b.y; };
  const auto strictly_increasing = [](auto first, auto last) {
    return std::adjacent_find(
               first, last, [](const Sample& a, const Sample& b) { return !(a.y < b.y); }) == last;
  };
  const auto middle = samples.begin() + slab_samples;
  bool merged = false;
  if (strictly_increasing(samples.begin(), middle) && strictly_increasing(middle, samples.end())) {
    std::vector<Sample> runs;
    runs.reserve(samples.size());
    std::merge(samples.begin(), middle, middle, samples.end(), std::back_inserter(runs), by_y);
    if (strictly_increasing(runs.begin(), runs.end())) {
      samples = std::move(runs);
      merged = true;
    }
  }
  if (!merged) std::sort(samples.begin(), samples.end(), by_y);

  CoverageMeasure m;
  // The active edges are kept in the order of their abscissae at the last sample: between events
  // no edge starts or ends and (in a simple ring) none crosses another, so the next sample's
  // abscissae come out sorted but for the edges that joined. Sorted, they are the same sequence
  // as std::sort made of them (the one ascending order of the same values; equal values are
  // equal doubles but for 0 and -0, whose order changes no sum below: x + 0 == x + -0 for x != 0,
  // and the sums start at +0).
  std::vector<const Edge*> active_edges;
  std::vector<const Band*> active_bands;
  std::size_t next_edge = 0, next_band = 0;
  std::vector<double> xs;
  std::vector<Interval> inside, swath;
  // The merged swath depends only on the set of active bands: merged again only when it changed.
  bool bands_changed = true;
  for (const auto& [y, dy, line] : samples) {
    while (next_edge < edges.size() && edges[next_edge].lo.y <= y)
      active_edges.push_back(&edges[next_edge++]);
    const std::size_t bands_joined = next_band;
    while (next_band < bands.size() && bands[next_band].y0 <= y)
      active_bands.push_back(&bands[next_band++]);
    const std::size_t bands_before = active_bands.size();
    // A copy: clang 14 cannot capture a structured binding.
    std::erase_if(active_edges, [at = y](const Edge* e) { return e->hi.y <= at; });
    std::erase_if(active_bands, [at = y](const Band* b) { return b->y1 < at; });
    bands_changed =
        bands_changed || next_band != bands_joined || active_bands.size() != bands_before;

    xs.clear();
    for (const Edge* e : active_edges)  // every one has lo.y <= y < hi.y
      xs.push_back(e->lo.x + (e->hi.x - e->lo.x) * (y - e->lo.y) / (e->hi.y - e->lo.y));
    // Insertion sort, the edges moved with their abscissae: a new edge or a crossing costs only
    // the places it moves.
    for (std::size_t i = 1; i < xs.size(); ++i) {
      const double x = xs[i];
      const Edge* e = active_edges[i];
      std::size_t j = i;
      for (; j > 0 && x < xs[j - 1]; --j) {
        xs[j] = xs[j - 1];
        active_edges[j] = active_edges[j - 1];
      }
      xs[j] = x;
      active_edges[j] = e;
    }
    inside.clear();
    for (std::size_t i = 0; i + 1 < xs.size(); i += 2) inside.push_back({xs[i], xs[i + 1]});
    if (line != nullptr) {
      const double length = line->x1 - line->x0;
      m.line_length_m += length;
      m.line_length_outside_m += length - overlap(inside, {{line->x0, line->x1}});
      continue;
    }
    if (bands_changed) {
      swath.clear();
      for (const Band* b : active_bands) swath.push_back({b->x0, b->x1});
      merge(swath);
      bands_changed = false;
    }

    add_strip(m, inside, swath, dy);
  }
  return finished(m);
}

CoverageMeasure measure_coverage_any_direction(const geometry::Polygon& area,
                                               const std::vector<SweepLine>& lines,
                                               double footprint_width_m, int rows) {
  std::vector<Edge> edges;
  std::vector<Edge> all_edges;  // every ring edge as given, horizontal ones too: clipping lines
  double y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
  for (std::size_t r = 0; r < geometry::ring_count(area); ++r) {
    const geometry::Ring& ring = geometry::ring_at(area, r);
    for (std::size_t i = 0; i < ring.size(); ++i) {
      Point2 a = ring[i], b = ring[(i + 1) % ring.size()];
      all_edges.push_back({a, b});
      if (a.y > b.y) std::swap(a, b);
      if (a.y == b.y) continue;
      edges.push_back({a, b});
      y_min = std::min(y_min, a.y);
      y_max = std::max(y_max, b.y);
    }
  }
  // Each footprint a convex quadrilateral: its four edges, and the ordinates it spans.
  struct Quad {
    std::array<Edge, 4> sides;
    double y0, y1;
  };
  std::vector<Quad> quads;
  std::vector<double> events;
  CoverageMeasure m;
  for (const SweepLine& l : lines) {
    const double length = geometry::distance(l.start, l.end);
    m.line_length_m += length;
    if (!(length > 0)) continue;  // no rectangle along a point
    const Point2 across =
        Point2{-(l.end.y - l.start.y), l.end.x - l.start.x} * (footprint_width_m / 2 / length);
    const std::array<Point2, 4> c{l.start - across, l.end - across, l.end + across,
                                  l.start + across};
    Quad q{};
    q.y0 = std::numeric_limits<double>::infinity();
    q.y1 = -q.y0;
    for (std::size_t i = 0; i < 4; ++i) {
      Point2 a = c[i], b = c[(i + 1) % 4];
      if (a.y > b.y) std::swap(a, b);
      q.sides[i] = {a, b};
      q.y0 = std::min(q.y0, a.y);
      q.y1 = std::max(q.y1, b.y);
      events.push_back(c[i].y);
    }
    y_min = std::min(y_min, q.y0);
    y_max = std::max(y_max, q.y1);
    quads.push_back(q);
    // The length outside: the line cut where it crosses a ring edge, each piece inside or out by
    // its middle (crossing parity over every ring: holes count as outside).
    std::vector<double> ts{0.0, 1.0};
    const Point2 d = l.end - l.start;
    for (const Edge& e : all_edges) {
      const Point2 f = e.hi - e.lo;
      const double denominator = geometry::cross(d, f);
      if (denominator == 0) continue;
      const double t = geometry::cross(e.lo - l.start, f) / denominator;
      const double u = geometry::cross(e.lo - l.start, d) / denominator;
      if (t > 0 && t < 1 && u >= 0 && u <= 1) ts.push_back(t);
    }
    std::sort(ts.begin(), ts.end());
    for (std::size_t k = 0; k + 1 < ts.size(); ++k) {
      if (ts[k + 1] <= ts[k]) continue;
      const Point2 mid = l.start + d * ((ts[k] + ts[k + 1]) / 2);
      bool in = false;
      for (const Edge& e : edges)
        if ((e.lo.y <= mid.y) != (e.hi.y <= mid.y) &&
            e.lo.x + (e.hi.x - e.lo.x) * (mid.y - e.lo.y) / (e.hi.y - e.lo.y) > mid.x)
          in = !in;
      if (!in) m.line_length_outside_m += (ts[k + 1] - ts[k]) * length;
    }
  }
  for (const Edge& e : edges) {
    events.push_back(e.lo.y);
    events.push_back(e.hi.y);
  }
  std::sort(edges.begin(), edges.end(),
            [](const Edge& a, const Edge& b) { return a.lo.y < b.lo.y; });
  std::sort(quads.begin(), quads.end(), [](const Quad& a, const Quad& b) { return a.y0 < b.y0; });
  std::sort(events.begin(), events.end());
  events.erase(std::unique(events.begin(), events.end()), events.end());
  std::vector<std::pair<double, double>> samples;  // ordinate, weight
  const double total = y_max - y_min;
  for (std::size_t k = 0; k + 1 < events.size(); ++k) {
    const double h = events[k + 1] - events[k];
    if (h <= 0) continue;
    const int n = std::max(1, static_cast<int>(std::ceil(rows * h / total)));
    for (int i = 0; i < n; ++i) samples.push_back({events[k] + (i + 0.5) * h / n, h / n});
  }

  std::vector<const Edge*> active_edges;
  std::vector<const Quad*> active_quads;
  std::size_t next_edge = 0, next_quad = 0;
  std::vector<double> xs;
  std::vector<Interval> inside, swath;
  for (const auto& [y, dy] : samples) {
    while (next_edge < edges.size() && edges[next_edge].lo.y <= y)
      active_edges.push_back(&edges[next_edge++]);
    while (next_quad < quads.size() && quads[next_quad].y0 <= y)
      active_quads.push_back(&quads[next_quad++]);
    std::erase_if(active_edges, [at = y](const Edge* e) { return e->hi.y <= at; });
    std::erase_if(active_quads, [at = y](const Quad* q) { return q->y1 <= at; });
    xs.clear();
    for (const Edge* e : active_edges)
      if (e->lo.y <= y && y < e->hi.y)
        xs.push_back(e->lo.x + (e->hi.x - e->lo.x) * (y - e->lo.y) / (e->hi.y - e->lo.y));
    std::sort(xs.begin(), xs.end());
    inside.clear();
    for (std::size_t i = 0; i + 1 < xs.size(); i += 2) inside.push_back({xs[i], xs[i + 1]});
    swath.clear();
    for (const Quad* q : active_quads) {
      double x0 = std::numeric_limits<double>::infinity(), x1 = -x0;
      for (const Edge& e : q->sides)
        if (e.lo.y <= y && y <= e.hi.y && e.hi.y > e.lo.y) {
          const double x = e.lo.x + (e.hi.x - e.lo.x) * (y - e.lo.y) / (e.hi.y - e.lo.y);
          x0 = std::min(x0, x);
          x1 = std::max(x1, x);
        }
      if (x1 > x0) swath.push_back({x0, x1});
    }
    merge(swath);
    add_strip(m, inside, swath, dy);
  }
  return finished(m);
}

}  // namespace swath::planning
