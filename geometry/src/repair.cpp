// The second CGAL translation unit of swath::geometry: arrangements need exact constructions.
#include "swath/geometry/repair.hpp"

#include "swath/geometry/predicates.hpp"

#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <algorithm>
#include <map>

namespace swath::geometry {
namespace {

using ExactKernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Traits = CGAL::Arr_segment_traits_2<ExactKernel>;
using Arrangement = CGAL::Arrangement_2<Traits>;

// Splits a closed walk that may pass a vertex more than once into simple cycles.
std::vector<Ring> simple_cycles(const std::vector<Point2>& walk) {
  std::vector<Ring> cycles;
  std::vector<Point2> stack;
  std::map<std::pair<double, double>, std::size_t> at;  // point -> position in stack
  for (const Point2& p : walk) {
    const auto key = std::make_pair(p.x, p.y);
    if (const auto it = at.find(key); it != at.end()) {
      Ring cycle(stack.begin() + static_cast<std::ptrdiff_t>(it->second), stack.end());
      for (std::size_t k = it->second + 1; k < stack.size(); ++k)
        at.erase({stack[k].x, stack[k].y});
      stack.resize(it->second + 1);
      if (cycle.size() >= 3) cycles.push_back(std::move(cycle));
      continue;
    }
    at[key] = stack.size();
    stack.push_back(p);
  }
  if (stack.size() >= 3) cycles.push_back(stack);
  return cycles;
}

}  // namespace

std::vector<Ring> enclosed_areas(const Ring& ring) {
  std::vector<Traits::X_monotone_curve_2> segments;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point2 a = ring[i], b = ring[(i + 1) % ring.size()];
    if (a == b) continue;
    segments.emplace_back(ExactKernel::Point_2(a.x, a.y), ExactKernel::Point_2(b.x, b.y));
  }
  Arrangement arrangement;
  CGAL::insert(arrangement, segments.begin(), segments.end());

  // Everything bounded is enclosed, so the union's boundary is the unbounded face's inner
  // boundaries; walking one keeps the unbounded face on the left, i.e. goes clockwise around its
  // component.
  std::vector<Ring> pieces;
  const auto unbounded = arrangement.unbounded_face();
  for (auto hole = unbounded->holes_begin(); hole != unbounded->holes_end(); ++hole) {
    std::vector<Point2> walk;
    auto edge = *hole;
    do {
      const auto& p = edge->source()->point();
      walk.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y())});
    } while (++edge != *hole);
    for (Ring& cycle : simple_cycles(walk)) {
      std::reverse(cycle.begin(), cycle.end());
      // Vertices where the arrangement split a straight edge add nothing.
      for (bool removed = true; removed && cycle.size() > 3;) {
        removed = false;
        for (std::size_t i = 0; i < cycle.size() && cycle.size() > 3; ++i) {
          const std::size_t n = cycle.size();
          if (orientation(cycle[(i + n - 1) % n], cycle[i], cycle[(i + 1) % n]) ==
              Orientation::collinear) {
            cycle.erase(cycle.begin() + static_cast<std::ptrdiff_t>(i));
            removed = true;
          }
        }
      }
      if (signed_area(cycle) > 0) pieces.push_back(std::move(cycle));
    }
  }
  std::sort(pieces.begin(), pieces.end(),
            [](const Ring& a, const Ring& b) { return signed_area(a) > signed_area(b); });
  return pieces;
}

}  // namespace swath::geometry
