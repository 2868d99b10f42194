#include "swath/planning/coverage.hpp"

#include <algorithm>
#include <cmath>
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
  for (const Band& b : bands) samples.push_back({b.y, 0.0, &b});
  std::sort(samples.begin(), samples.end(),
            [](const Sample& a, const Sample& b) { return a.y < b.y; });

  CoverageMeasure m;
  std::vector<const Edge*> active_edges;
  std::vector<const Band*> active_bands;
  std::size_t next_edge = 0, next_band = 0;
  std::vector<double> xs;
  std::vector<Interval> inside, swath;
  for (const auto& [y, dy, line] : samples) {
    while (next_edge < edges.size() && edges[next_edge].lo.y <= y)
      active_edges.push_back(&edges[next_edge++]);
    while (next_band < bands.size() && bands[next_band].y0 <= y)
      active_bands.push_back(&bands[next_band++]);
    // A copy: clang 14 cannot capture a structured binding.
    std::erase_if(active_edges, [at = y](const Edge* e) { return e->hi.y <= at; });
    std::erase_if(active_bands, [at = y](const Band* b) { return b->y1 < at; });

    xs.clear();
    for (const Edge* e : active_edges)
      if (e->lo.y <= y && y < e->hi.y)
        xs.push_back(e->lo.x + (e->hi.x - e->lo.x) * (y - e->lo.y) / (e->hi.y - e->lo.y));
    std::sort(xs.begin(), xs.end());
    inside.clear();
    for (std::size_t i = 0; i + 1 < xs.size(); i += 2) inside.push_back({xs[i], xs[i + 1]});
    if (line != nullptr) {
      const double length = line->x1 - line->x0;
      m.line_length_m += length;
      m.line_length_outside_m += length - overlap(inside, {{line->x0, line->x1}});
      continue;
    }
    swath.clear();
    for (const Band* b : active_bands) swath.push_back({b->x0, b->x1});
    merge(swath);

    m.area_m2 += length(inside) * dy;
    m.swath_area_m2 += length(swath) * dy;
    m.covered_area_m2 += overlap(inside, swath) * dy;
  }
  m.covered_fraction = m.area_m2 > 0 ? m.covered_area_m2 / m.area_m2 : 0.0;
  m.outside_fraction =
      m.swath_area_m2 > 0 ? (m.swath_area_m2 - m.covered_area_m2) / m.swath_area_m2 : 0.0;
  return m;
}

}  // namespace swath::planning
