#include "coverage_rasterizer.hpp"

#include <algorithm>
#include <cmath>

namespace swath::render::detail {

using geometry::Point2;

CoverageRasterizer::CoverageRasterizer(int width_px, int height_px)
    : width_px_(std::max(0, width_px)),
      height_px_(std::max(0, height_px)),
      accumulator_(static_cast<std::size_t>(width_px_) + 2, 0.0),
      row_(static_cast<std::size_t>(width_px_), 0.0f) {}

namespace {

// Beyond this many pixels from the image a coordinate is moved onto this bound (see the header):
// differences of coordinates then stay finite and exact enough, and no row or column index
// computed from them overflows an int.
constexpr double kFarPx = 1e7;

// Where `p` meets the line x = bound (axis 0) or y = bound (axis 1) on the way to `q`.
Point2 meet(Point2 p, Point2 q, int axis, double bound) {
  const double pa = axis == 0 ? p.x : p.y, qa = axis == 0 ? q.x : q.y;
  const double t = (bound - pa) / (qa - pa);
  return axis == 0 ? Point2{bound, p.y + (q.y - p.y) * t} : Point2{p.x + (q.x - p.x) * t, bound};
}

// The ring clipped to one side of a bound (Sutherland-Hodgman): keeps the part with
// coordinate >= bound (keep_above) or <= bound. Clipping to a convex box leaves the area inside
// the box as it was.
std::vector<Point2> clip_side(const std::vector<Point2>& ring, int axis, double bound,
                              bool keep_above) {
  std::vector<Point2> out;
  const auto in = [&](Point2 p) {
    const double v = axis == 0 ? p.x : p.y;
    return keep_above ? v >= bound : v <= bound;
  };
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point2 p = ring[i], q = ring[(i + 1) % ring.size()];
    if (in(p)) out.push_back(p);
    // From the point inside: its coordinates are the small ones, so the crossing keeps their
    // precision (from a point at 1e300 px it could land 1e7 px off the line).
    if (in(p) != in(q)) out.push_back(in(p) ? meet(p, q, axis, bound) : meet(q, p, axis, bound));
  }
  return out;
}

}  // namespace

void CoverageRasterizer::add_ring(std::span<const Point2> input) {
  // Points that are not finite numbers are left out (the ring stays closed through the others).
  std::vector<Point2> ring;
  ring.reserve(input.size());
  bool far = false;
  for (const Point2& p : input) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
    far = far || std::abs(p.x) > kFarPx || std::abs(p.y) > kFarPx;
    ring.push_back(p);
  }
  if (ring.size() < 3) return;
  if (far) {  // clipped to a box kFarPx round the image: the same coverage inside the image
    ring = clip_side(ring, 0, -kFarPx, true);
    ring = clip_side(ring, 0, width_px_ + kFarPx, false);
    ring = clip_side(ring, 1, -kFarPx, true);
    ring = clip_side(ring, 1, height_px_ + kFarPx, false);
    if (ring.size() < 3) return;
    // Points beyond ~1e307 px whose differences overflow give no crossing: the ring is left out
    // whole (dropping its edges one by one would leave it open, filling to the image's edge).
    for (const Point2& p : ring)
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) return;
  }
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point2 a = ring[i], b = ring[(i + 1) % ring.size()];
    if (!std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(b.x) || !std::isfinite(b.y))
      continue;
    // Horizontal edges are kept (dir 0): they cover nothing but join the edges at their ends.
    if (a.y <= b.y)
      edges_.push_back({a.x, a.y, b.x, b.y, a.y < b.y ? 1 : 0});
    else
      edges_.push_back({b.x, b.y, a.x, a.y, -1});
  }
}

void CoverageRasterizer::rasterize(FillRule rule, const RowSink& sink) const {
  if (edges_.empty() || width_px_ == 0 || height_px_ == 0) return;
  std::vector<std::size_t> order(edges_.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return edges_[a].y_top < edges_[b].y_top; });
  double y_max = edges_[order.front()].y_bottom;
  for (const Edge& e : edges_) y_max = std::max(y_max, e.y_bottom);
  // Clamped as doubles before the cast: a shape far below or above the image has no row in it.
  const double h = height_px_;
  const int first_row =
      static_cast<int>(std::clamp(std::floor(edges_[order.front()].y_top), 0.0, h));
  const int end_row = static_cast<int>(std::clamp(std::ceil(y_max), 0.0, h));

  std::vector<std::size_t> active;
  std::vector<Piece> pieces;
  std::size_t next = 0;
  for (int y = first_row; y < end_row; ++y) {
    const double top = y, bottom = y + 1.0;
    while (next < order.size() && edges_[order[next]].y_top < bottom)
      active.push_back(order[next++]);
    std::erase_if(active, [&](std::size_t i) {
      const Edge& e = edges_[i];
      return e.dir == 0 ? e.y_top < top : e.y_bottom <= top;
    });
    pieces.clear();
    for (std::size_t i : active) {
      const Edge& e = edges_[i];
      if (e.dir == 0) {
        // Only a horizontal edge strictly inside the row joins pieces of this row.
        if (e.y_top > top && e.y_top < bottom)
          pieces.push_back({e.y_top, e.y_top, e.x_top, e.x_bottom, 0});
        continue;
      }
      const double y0 = std::max(e.y_top, top), y1 = std::min(e.y_bottom, bottom);
      if (y1 <= y0) continue;
      const double x0 = y0 == e.y_top ? e.x_top : e.x_at(y0);
      const double x1 = y1 == e.y_bottom ? e.x_bottom : e.x_at(y1);
      pieces.push_back({y0, y1, x0, x1, e.dir});
    }
    if (!pieces.empty()) rasterize_row(y, pieces, rule, sink);
  }
}

void CoverageRasterizer::rasterize_row(int y, const std::vector<Piece>& unsorted, FillRule rule,
                                       const RowSink& sink) const {
  std::vector<Piece> pieces = unsorted;
  std::sort(pieces.begin(), pieces.end(),
            [](const Piece& a, const Piece& b) { return a.x_min() < b.x_min(); });
  double x_max = pieces.front().x_max();
  for (const Piece& p : pieces) x_max = std::max(x_max, p.x_max());
  const double w = width_px_;
  const int lo = static_cast<int>(std::clamp(std::floor(pieces.front().x_min()), 0.0, w - 1));
  const int hi = static_cast<int>(std::clamp(std::floor(x_max) + 1, 0.0, w - 1));
  std::fill(accumulator_.begin() + lo, accumulator_.begin() + hi + 2, 0.0);

  // Clusters: pieces that overlap or touch in x. Between clusters no edge passes, so the winding
  // there is the same at every height of the row and carries from one cluster to the next.
  int winding = 0;
  for (std::size_t i = 0; i < pieces.size();) {
    std::size_t j = i + 1;
    double reach = pieces[i].x_max();
    while (j < pieces.size() && pieces[j].x_min() <= reach)
      reach = std::max(reach, pieces[j++].x_max());
    winding = accumulate_cluster(std::span(pieces).subspan(i, j - i), winding, rule, y);
    i = j;
  }

  double coverage = 0;
  int first = -1, last = -1;
  for (int x = lo; x <= hi; ++x) {
    coverage += accumulator_[x];
    const double c = std::clamp(coverage, 0.0, 1.0);
    row_[x] = c < 1e-9 ? 0.0f : static_cast<float>(c);
    if (row_[x] > 0) {
      if (first < 0) first = x;
      last = x;
    }
  }
  if (first >= 0) sink(y, first, std::span<const float>(row_).subspan(first, last - first + 1));
}

namespace {

// Beyond these a cluster is dense (a long series squeezed into a few pixels: its crossings grow
// as the square of its pieces) and is sampled on kSampleLines lines instead (see the header).
constexpr std::size_t kMaxCuts = 128;
constexpr int kSampleLines = 64;

}  // namespace

std::vector<double> CoverageRasterizer::exact_cuts(std::span<const Piece> cluster,
                                                   double row_top) const {
  std::vector<double> cuts{row_top, row_top + 1};
  for (const Piece& p : cluster)
    if (p.dir != 0) cuts.insert(cuts.end(), {p.y0, p.y1});
  if (cuts.size() > kMaxCuts) return {};
  // Crossings: where two pieces swap their left-right order.
  std::size_t pairs = 0;
  const std::size_t max_pairs = 32 * cluster.size() + 1024;
  for (std::size_t a = 0; a < cluster.size(); ++a) {
    const Piece& pa = cluster[a];
    if (pa.dir == 0) continue;
    for (std::size_t b = a + 1; b < cluster.size() && cluster[b].x_min() <= pa.x_max(); ++b) {
      const Piece& pb = cluster[b];
      if (pb.dir == 0) continue;
      if (++pairs > max_pairs) return {};
      const double lo = std::max(pa.y0, pb.y0), hi = std::min(pa.y1, pb.y1);
      if (hi <= lo) continue;
      const double d_lo = pa.x_at(lo) - pb.x_at(lo), d_hi = pa.x_at(hi) - pb.x_at(hi);
      if ((d_lo < 0 && d_hi > 0) || (d_lo > 0 && d_hi < 0)) {
        const double cut = lo + (hi - lo) * (d_lo / (d_lo - d_hi));
        if (cut > lo && cut < hi) cuts.push_back(cut);
        if (cuts.size() > kMaxCuts) return {};
      }
    }
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  return cuts;
}

int CoverageRasterizer::accumulate_cluster(std::span<const Piece> cluster, int winding_left,
                                           FillRule rule, double row_top) const {
  const auto inside = [rule](int winding) {
    return rule == FillRule::even_odd ? (winding & 1) != 0 : winding != 0;
  };
  struct AtLine {
    double x;
    const Piece* piece;
  };
  std::vector<AtLine> crossing;
  // The pieces that span [s0, s1], by their x at `at`, walked with the fill rule; each piece where
  // the inside turns on or off adds the area right of its part from x(s0) to x(s1), height s1 - s0.
  // Returns the winding right of them (that of `winding_left` when no piece spans the strip).
  const auto walk = [&](double s0, double s1, double at, bool sampled) {
    crossing.clear();
    for (const Piece& p : cluster) {
      if (p.dir == 0) continue;
      if (sampled ? p.y0 <= at && at < p.y1 : p.y0 <= s0 && p.y1 >= s1)
        crossing.push_back({p.x_at(at), &p});
    }
    std::sort(crossing.begin(), crossing.end(),
              [](const AtLine& a, const AtLine& b) { return a.x < b.x; });
    int winding = winding_left;
    for (const AtLine& c : crossing) {
      const bool was_inside = inside(winding);
      winding += c.piece->dir;
      if (inside(winding) == was_inside) continue;
      const double height = was_inside ? -(s1 - s0) : s1 - s0;
      if (sampled)  // the strip's width along its sample line
        accumulate_area_right(c.x, c.x, height);
      else
        accumulate_area_right(c.piece->x_at(s0), c.piece->x_at(s1), height);
    }
    return winding;
  };

  int winding_right = winding_left;
  const std::vector<double> cuts = exact_cuts(cluster, row_top);
  if (cuts.empty()) {
    for (int k = 0; k < kSampleLines; ++k) {
      const double s0 = row_top + static_cast<double>(k) / kSampleLines;
      const double s1 = row_top + static_cast<double>(k + 1) / kSampleLines;
      const int w = walk(s0, s1, (s0 + s1) / 2, true);
      if (!crossing.empty()) winding_right = w;
    }
    return winding_right;
  }
  // Between consecutive cuts no two pieces cross: the shape is the trapezoids between the pieces
  // where the fill rule turns on and off.
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const int w = walk(cuts[k], cuts[k + 1], (cuts[k] + cuts[k + 1]) / 2, false);
    if (!crossing.empty()) winding_right = w;
  }
  return winding_right;
}

// Adds, to every pixel column of the row, the area (times the sign of `height`) that lies right
// of the straight segment from xa to xb spanning |height| of the row: a column wholly right of
// it gains |height|, the columns it crosses the trapezoid right of their part of it.
void CoverageRasterizer::accumulate_area_right(double xa, double xb, double height) const {
  const double w = width_px_;
  const auto add = [&](double p0, double p1, double h) {
    if (p1 <= 0) {  // left of the image: every column is right of it
      accumulator_[0] += h;
      return;
    }
    if (p0 >= w) return;  // right of the image
    const double middle = (p0 + p1) / 2;
    const int column = std::min(static_cast<int>(std::floor(middle)), width_px_ - 1);
    const double in_column = h * ((column + 1) - middle);
    accumulator_[column] += in_column;
    accumulator_[column + 1] += h - in_column;
  };
  const double lo = std::min(xa, xb), hi = std::max(xa, xb);
  if (hi - lo <= 0) {
    add(lo, lo, height);
    return;
  }
  const double height_per_x = height / (hi - lo);
  for (double x = lo; x < hi;) {
    const double next = x < 0 ? std::min(hi, 0.0) : x >= w ? hi : std::min(hi, std::floor(x) + 1);
    add(x, next, (next - x) * height_per_x);
    x = next;
  }
}

}  // namespace swath::render::detail
