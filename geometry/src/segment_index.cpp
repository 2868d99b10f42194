#include "swath/geometry/segment_index.hpp"

#include <algorithm>
#include <cmath>

namespace swath::geometry {

SegmentIndex::SegmentIndex(std::vector<Segment> segments, double cells_per_segment)
    : segments_(std::move(segments)) {
  if (segments_.empty()) return;
  double x1 = segments_[0].a.x, y1 = segments_[0].a.y;
  x0_ = x1;
  y0_ = y1;
  for (const Segment& s : segments_)
    for (const Point2& p : {s.a, s.b}) {
      x0_ = std::min(x0_, p.x);
      y0_ = std::min(y0_, p.y);
      x1 = std::max(x1, p.x);
      y1 = std::max(y1, p.y);
    }
  const double width = x1 - x0_, height = y1 - y0_;
  // Square cells, about cells_per_segment per segment; at most 4096 a side (the rows and columns
  // a long segment passes through stay few).
  const double target = std::max(1.0, cells_per_segment * double(segments_.size()));
  constexpr double kMaxSide = 4096;
  auto count = [&](double extent, double side) {
    return extent > 0 ? std::clamp(std::ceil(extent / side), 1.0, kMaxSide) : 1.0;
  };
  double side = std::max(width, height) / target;  // one flat extent: a strip of cells
  if (width > 0 && height > 0) side = std::sqrt(width * height / target);
  if (side > 0) {
    columns_ = std::size_t(count(width, side));
    rows_ = std::size_t(count(height, side));
  }
  if (width > 0) {
    cell_w_ = width / double(columns_);
    inv_w_ = double(columns_) / width;
  }
  if (height > 0) {
    cell_h_ = height / double(rows_);
    inv_h_ = double(rows_) / height;
  }
  // Compressed rows: count per cell, then fill (segments in index order: ascending per cell).
  std::vector<std::uint32_t> counts(columns_ * rows_, 0);
  for (const Segment& s : segments_)
    rows_of(s.a, s.b, [&](std::size_t r, std::size_t c0, std::size_t c1) {
      for (std::size_t c = c0; c <= c1; ++c) ++counts[r * columns_ + c];
    });
  start_.assign(columns_ * rows_ + 1, 0);
  for (std::size_t k = 0; k < counts.size(); ++k) start_[k + 1] = start_[k] + counts[k];
  items_.resize(start_.back());
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < segments_.size(); ++i)
    rows_of(segments_[i].a, segments_[i].b, [&](std::size_t r, std::size_t c0, std::size_t c1) {
      for (std::size_t c = c0; c <= c1; ++c)
        items_[fill[r * columns_ + c]++] = std::uint32_t(i) | (c == c0 ? kFirstInRow : 0);
    });
  // The rays' rows: each segment once (at the first column of its run in the row), sorted by the
  // abscissa a ray stops at (ties by index: the same order on every build).
  ray_start_.assign(rows_ + 1, 0);
  ray_split_.assign(rows_, 0);
  by_right_.clear();
  by_left_.clear();
  for (std::size_t r = 0; r < rows_; ++r) {
    for (std::uint32_t k = start_[r * columns_], end = start_[(r + 1) * columns_]; k < end; ++k) {
      if (!(items_[k] & kFirstInRow)) continue;
      const std::uint32_t i = items_[k] & kIndex;
      const Segment& s = segments_[i];
      by_right_.push_back({std::max(s.a.x, s.b.x), i});
      by_left_.push_back({std::min(s.a.x, s.b.x), i});
    }
    ray_start_[r + 1] = std::uint32_t(by_right_.size());
    const auto first = std::ptrdiff_t(ray_start_[r]);
    std::sort(by_right_.begin() + first, by_right_.end(), [](RayEntry u, RayEntry v) {
      return u.x > v.x || (u.x == v.x && u.index < v.index);
    });
    std::sort(by_left_.begin() + first, by_left_.end(), [](RayEntry u, RayEntry v) {
      return u.x < v.x || (u.x == v.x && u.index < v.index);
    });
    const std::size_t middle = std::size_t(first) + (by_left_.size() - std::size_t(first)) / 2;
    ray_split_[r] = middle < by_left_.size() ? by_left_[middle].x / 2 + by_right_[middle].x / 2 : 0;
  }
}

}  // namespace swath::geometry
