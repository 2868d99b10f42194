#pragma once
// Internal: the drawing module's anti-aliasing. A shape (closed rings of straight edges, in image
// pixels: x right, y down, pixel (i, j) is the square [i, i+1] x [j, j+1]) becomes, for every
// pixel, the exact fraction of that square the shape covers under a fill rule.
//
// Accuracy: exact up to double rounding (about 1e-12 of a pixel for coordinates below 1e4 px),
// for any rings: self-intersecting, overlapping, with holes, partly or wholly outside the image.
// How: each pixel row is cut into sub-strips at every vertex and every edge crossing inside it;
// in a sub-strip no two edges cross, so the shape is a union of trapezoids between consecutive
// boundary edges (found by walking the edges left to right with the fill rule), and the area of
// a trapezoid within each pixel column is the area right of its left edge minus the area right of
// its right edge, accumulated in a difference array and prefix-summed. No supersampled buffer:
// memory is one row of doubles and the edges.
//
// One exception keeps the time linear: where, within one row, a run of edges that overlap in x
// has more than 128 vertices and crossings (a long series squeezed into a few pixels, whose
// crossings grow as the square of its edges), that run is measured on 64 horizontal lines through
// the row instead, each exact along its length: there a pixel's coverage is within 1.5/64 per
// edge through it (the error of 64 x 64 point samples), elsewhere in the row it stays exact.

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "swath/geometry/point.hpp"

namespace swath::render::detail {

enum class FillRule {
  even_odd,  ///< inside where an odd number of rings wind round the point (holes)
  nonzero,   ///< inside where the winding number is not zero (unions of overlapping pieces)
};

class CoverageRasterizer {
 public:
  /// Coverage is computed for the pixels [0, width_px) x [0, height_px).
  CoverageRasterizer(int width_px, int height_px);

  /// Adds a closed ring (the last point joins the first; fewer than 3 points are ignored).
  /// Points that are not finite are left out; a ring reaching beyond 1e7 px of the image is
  /// clipped to that box first: the same coverage inside the image up to rounding of the crossings
  /// (each computed from the point inside the box, to ~1e-16 of the far point's coordinate: exact
  /// to a pixel's 1e-6 while the points lie within ~1e10 px). A ring whose clipping overflows
  /// (coordinates of opposite sign near 1e308) is left out whole.
  void add_ring(std::span<const geometry::Point2> ring);
  void clear() { edges_.clear(); }

  /// One row's coverage: pixels [x_begin, x_begin + coverage.size()) of row y, each in [0, 1].
  /// Rows and pixels not reported are not covered at all.
  using RowSink = std::function<void(int y, int x_begin, std::span<const float> coverage)>;

  /// Reports the coverage of the rings added so far, row by row, top to bottom.
  void rasterize(FillRule rule, const RowSink& sink) const;

 private:
  struct Edge {
    double x_top, y_top, x_bottom, y_bottom;  ///< y_top < y_bottom
    int dir;  ///< +1 if the ring runs downwards along it, -1 upwards
    double x_at(double y) const {
      return x_top + (x_bottom - x_top) * ((y - y_top) / (y_bottom - y_top));
    }
  };
  // An edge's part inside one row.
  struct Piece {
    double y0, y1, x0, x1;  ///< x0 at y0, x1 at y1; y0 < y1
    int dir;
    double x_at(double y) const { return y == y1 ? x1 : x0 + (x1 - x0) * ((y - y0) / (y1 - y0)); }
    double x_min() const { return x0 < x1 ? x0 : x1; }
    double x_max() const { return x0 < x1 ? x1 : x0; }
  };

  void rasterize_row(int y, const std::vector<Piece>& pieces, FillRule rule,
                     const RowSink& sink) const;
  // Accumulates pieces that overlap in x with no gap; returns the winding right of them, given
  // `winding_left` on their left.
  int accumulate_cluster(std::span<const Piece> cluster, int winding_left, FillRule rule,
                         double row_top) const;
  // A cluster's cut heights (row top and bottom, vertices, crossings), sorted; empty when the
  // cluster is dense.
  std::vector<double> exact_cuts(std::span<const Piece> cluster, double row_top) const;
  void accumulate_area_right(double xa, double xb, double height) const;

  int width_px_, height_px_;
  std::vector<Edge> edges_;
  mutable std::vector<double> accumulator_;  ///< width + 2: a difference array of one row
  mutable std::vector<float> row_;
};

}  // namespace swath::render::detail
