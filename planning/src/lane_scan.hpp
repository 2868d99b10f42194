#pragma once
// Internal to lane_runs.cpp (and its tests): which intervals of a horizontal line lie inside an
// area turned so that lanes run along x.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "swath/geometry/polygon.hpp"

namespace swath::planning::detail {

using geometry::Point2;
using geometry::Ring;

struct Span {
  double x0, x1;
};

// The area in the frame turned by -angle: lanes run along x. Which intervals of a horizontal
// line lie inside, by crossings (a vertex on the line counts for the edge above it only).
class LaneScan {
 public:
  LaneScan(const std::vector<Ring>& rings, double angle_deg) {
    // rotate()'s arithmetic with its sine and cosine taken once: 10,000-vertex outlines are
    // turned for every candidate direction.
    const double t = -angle_deg * std::numbers::pi / 180.0;
    const double c = std::cos(t), sn = std::sin(t);
    for (const Ring& ring : rings) {
      Ring turned;
      for (const Point2& p : ring) turned.push_back({c * p.x - sn * p.y, sn * p.x + c * p.y});
      for (std::size_t i = 0; i < turned.size(); ++i) {
        const Point2 a = turned[i], b = turned[(i + 1) % turned.size()];
        edges_.push_back({a, b});
        y_min = std::min(y_min, a.y);
        y_max = std::max(y_max, a.y);
      }
    }
  }

  std::vector<Span> at(double y) const {
    // Only the edges of y's bucket can span y (coverage lanes ask this for every corner the grid
    // misses: O(n) each made 10,000-vertex outlines slow). The crossings are sorted, so the
    // spans do not depend on the order the edges come in.
    if (buckets_ == 0) fill_buckets();
    std::vector<double> xs;
    const std::size_t k = bucket(y);
    for (std::uint32_t e = start_[k]; e < start_[k + 1]; ++e) {
      const auto& [a, b] = edges_[items_[e]];
      if ((a.y <= y) != (b.y <= y)) xs.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
    }
    return pairs(xs);
  }

  /// at() for many increasing ordinates: each edge finds its first by search.
  std::vector<std::vector<Span>> at(const std::vector<double>& ys) const {
    std::vector<std::vector<double>> xs(ys.size());
    for (const auto& [a, b] : edges_) {
      const double lo = std::min(a.y, b.y), hi = std::max(a.y, b.y);
      auto k = std::lower_bound(ys.begin(), ys.end(), lo);
      for (; k != ys.end() && *k < hi; ++k)
        xs[std::size_t(k - ys.begin())].push_back(a.x + (*k - a.y) * (b.x - a.x) / (b.y - a.y));
    }
    std::vector<std::vector<Span>> out;
    for (auto& x : xs) out.push_back(pairs(x));
    return out;
  }

  const std::vector<std::pair<Point2, Point2>>& edges() const { return edges_; }
  double y_min = std::numeric_limits<double>::infinity();
  double y_max = -std::numeric_limits<double>::infinity();

 private:
  static std::vector<Span> pairs(std::vector<double>& xs) {
    std::sort(xs.begin(), xs.end());
    std::vector<Span> out;
    for (std::size_t i = 0; i + 1 < xs.size(); i += 2)
      if (xs[i + 1] - xs[i] > 1e-6) out.push_back({xs[i], xs[i + 1]});
    return out;
  }
  // Buckets of equal height over [y_min, y_max], each listing the edges whose ordinate range
  // meets it. bucket() is monotone (rounding included), so an edge spanning y (min <= y < max)
  // is listed in y's bucket: it is in every bucket from bucket(min) to bucket(max).
  std::size_t bucket(double y) const {
    const double f = (y - y_min) * inv_height_;
    if (!(f > 0)) return 0;
    if (f >= double(buckets_ - 1)) return buckets_ - 1;
    return std::size_t(f);
  }
  void fill_buckets() const {
    buckets_ = std::clamp<std::size_t>(edges_.size(), 1, 4096);
    inv_height_ = y_max > y_min ? double(buckets_) / (y_max - y_min) : 0.0;
    std::vector<std::uint32_t> counts(buckets_ + 1, 0);
    auto each = [&](auto f) {
      for (std::size_t e = 0; e < edges_.size(); ++e) {
        const auto& [a, b] = edges_[e];
        for (std::size_t k = bucket(std::min(a.y, b.y)), last = bucket(std::max(a.y, b.y));
             k <= last; ++k)
          f(k, std::uint32_t(e));
      }
    };
    each([&](std::size_t k, std::uint32_t) { ++counts[k + 1]; });
    for (std::size_t k = 0; k < buckets_; ++k) counts[k + 1] += counts[k];
    start_ = counts;
    items_.resize(counts.back());
    each([&](std::size_t k, std::uint32_t e) { items_[counts[k]++] = e; });
  }

  std::vector<std::pair<Point2, Point2>> edges_;
  mutable std::size_t buckets_ = 0;  ///< 0 until at(y) is first asked
  mutable double inv_height_ = 0;
  mutable std::vector<std::uint32_t> start_, items_;
};

}  // namespace swath::planning::detail
