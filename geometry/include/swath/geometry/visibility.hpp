#pragma once
// Shortest paths that stay inside an area (closed: running along the boundary is allowed).

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "swath/geometry/polygon.hpp"
#include "swath/geometry/segment_index.hpp"

namespace swath::geometry {

/// Whether a VisibilityRouter finds paths or only measures legs (length_outside, visible): a
/// router that only measures skips the graph's set-up.
enum class Routing : bool { measure_only, routed };

/// Routes between points of an area given as rings (outer counter-clockwise, holes clockwise;
/// several outer rings allowed): a point is inside when an odd number of rings contain it, or it
/// lies within 1e-9 of the area's size of the boundary (rounding of computed boundary points). The
/// shortest path inside a polygonal area bends only at reflex vertices, so the graph holds those;
/// visibility is decided with exact predicates, on the edges a grid over them (SegmentIndex) finds
/// near each leg. The graph's edges and which nodes a path's ends see are tested lazily, only as
/// far as an A* search from the start towards the end needs to prove the path shortest. There is
/// no limit on the number of reflex vertices. Without a corner allowance, on rings that neither
/// cross nor touch, the search continues a path round a corner only the way a shortest path can
/// (the corner's obstacle on the inner side of both legs; exact orientation tests, with the
/// boundary's rounding tolerance), looking at the nodes in that cone of directions only (a grid of
/// nodes): at the nearly flat corners of a traced outline a narrow cone. Between paths of equal
/// length (up to rounding) it may then pick another than the full search.
///
/// `corner_allowance_m` (>= 0, metres) moves each bend this far away from its corner, along the
/// corner's bisector, where the moved point still sees both neighbours of the corner: an autopilot
/// flying through a bend cuts it (ArduCopter by up to ~1.7 m in SITL), and the allowance keeps the
/// cut path as far from the corner as the unmoved bend was. Paths stay inside the area; they are
/// then no longer exactly the shortest (longer by at most ~2 x allowance per bend). The moved bends
/// are no corners, so with an allowance the search is the full A* (the path the full Dijkstra
/// search over the moved bends picks, ties included), at O(r) per node it settles.
class VisibilityRouter {
 public:
  explicit VisibilityRouter(std::vector<Ring> rings, Routing routing = Routing::routed,
                            double corner_allowance_m = 0.0);

  /// True when the closed segment [a, b] lies inside the closed area.
  bool visible(Point2 a, Point2 b) const;
  /// True when p lies inside the closed area (its boundary within rounding included). Not
  /// visible(p, p): a segment of length 0 has no length outside, wherever it is.
  bool contains(Point2 p) const { return inside_closed(p); }
  /// The shortest path from a to b inside the area, a and b included; the straight segment when
  /// it is inside, when no inside path exists (a or b outside, separate pieces) or the router only
  /// measures (Routing::measure_only).
  std::vector<Point2> path(Point2 a, Point2 b) const;
  /// Length of [a, b] outside the closed area, metres (exact up to rounding).
  double length_outside(Point2 a, Point2 b) const;
  bool routes() const { return routing_; }
  /// A router for the same area (same nodes, same answers) for another thread: a router serves
  /// one thread at a time, its tables of the points asked about filling as it answers; the copy's
  /// are its own, empty. Which graph nodes see each other (the same for every path) is one table
  /// that this router and its copies share, each answer kept by whichever asks first.
  std::unique_ptr<VisibilityRouter> fresh_copy() const;
  ~VisibilityRouter();

 private:
  VisibilityRouter() = default;
  bool inside_closed(Point2 p) const;
  /// inside_closed()'s ray cast: whether p lies on an edge, and whether the edges cross its ray an
  /// odd number of times (without the boundary's rounding tolerance).
  struct RayCount {
    bool on_edge, odd;
  };
  RayCount ray_count(Point2 p) const;
  /// The area's edges by their direction from one point, in bins of angle: a visibility test from
  /// a point asked about often looks only at the edges in the leg's direction (about a bin's
  /// worth), not at every grid cell along the leg. Every edge that may share a point with a leg
  /// from the point is among them (the margins below), so the exact tests decide as before.
  struct Fan {
    std::vector<std::uint32_t> start;  ///< per bin, its first item; + the end
    /// Edge indices, start.back() of them: made without zeroing (fan_of() places every one; a
    /// vector's zeroing resize took 1.2 % more instructions over every 10th traced outline).
    std::unique_ptr<std::uint32_t[]> items;
    std::vector<std::uint32_t> near;  ///< edges within near_m of the point: asked every time
    double near_m = 0;  ///< 1e-6 of the larger of the area's and the point's extent, metres
    /// The point's ray crosses the edges an odd number of times and it lies on none: a leg from it
    /// that no edge meets lies inside (outside_fraction()).
    bool inside = false;
  };
  Fan fan_of(Point2 a) const;
  friend struct VisibilityRouterTestProbe;  ///< tests/geometry/visibility_fan_test.cpp
  long fan_bin(double diamond_angle) const;
  /// The part of [a, b] outside the closed area, as a fraction of its length; once that part
  /// exceeds `stop_m` metres, a partial sum (still above stop_m). `fan`: the fan of a, or null.
  double outside_fraction(Point2 a, Point2 b, double stop_m, const Fan* fan = nullptr) const;
  bool visible_with(Point2 a, Point2 b, const Fan* fan) const;
  Point2 moved_out(Point2 before, Point2 corner, Point2 after, double allowance_m) const;
  /// Which sides of the directed line p -> c (c: node v) the edges of v's corner lie on, each
  /// side with the line itself.
  struct Sides {
    bool left, right;
  };
  Sides corner_sides(Point2 p, Point2 c, std::size_t v) const;
  /// Whether a path from p bending at node v on to q turns round v's corner (`in`: the sides of
  /// p -> v; see visibility.cpp).
  bool taut(Sides in, Point2 p, std::size_t v, Point2 q) const;
  struct Box {
    double x0, y0, x1, y1;
  };
  std::vector<Ring> rings_;
  SegmentIndex edges_;           ///< every ring's edges, ring after ring, in ring order
  std::vector<Box> edge_boxes_;  ///< per edge of edges_
  std::vector<Point2> nodes_;    ///< the reflex corners (moved by the corner allowance)
  std::vector<Point2> before_;   ///< per node, the corner's ring neighbour before it
  std::vector<Point2> after_;    ///< per node, the corner's ring neighbour after it
  /// The directions a shortest path can leave a node in (taut()) lie within a double cone about a
  /// line through its corner: at angles up to (pi - the obstacle's angle) / 2 from `axis`. Nodes by
  /// cell of a grid let a search look at the cells that cone meets only (onward()).
  struct Bowtie {
    Point2 axis;     ///< unit vector along the cone's middle
    Point2 across;   ///< unit vector at right angles to it
    double spread;   ///< tan of the half angle, widened for rounding; infinity: every direction
    bool axis_left;  ///< the corner's edges lie left of +axis
  };
  std::vector<Bowtie> bowties_;
  struct NodeGrid {
    double x0 = 0, y0 = 0, cell_m = 1;
    long nx = 0, ny = 0;
    std::vector<std::uint32_t> start;  ///< per cell (row after row), its first item; + the end
    std::vector<std::uint32_t> items;  ///< node indices
  };
  NodeGrid grid_;
  void build_node_grid();
  /// Calls f(u) for every node u that a path bending at node v may go on to (and a few more),
  /// among those in cells meeting the box [lo, hi]; `in`: the sides of the leg into v.
  template <class F>
  void onward(std::size_t v, Sides in, Point2 lo, Point2 hi, F&& f) const;
  std::vector<std::uint32_t> nodes_by_x_;  ///< node indices by ascending x
  // Everything below is filled lazily, as paths are asked: a plan asks for ~10^4 paths between
  // run ends, and testing every run end against every reflex vertex (and every pair of reflex
  // vertices) up front was most of the routing time. Each answer is the one the eager
  // computation gave, bit for bit: the same visibility tests decide, and the A* search settles
  // the nodes it settles with the distances and predecessors Dijkstra's gave them (path()).
  static constexpr signed char kUnknown = -1;
  /// Which graph nodes a point sees (kUnknown: not asked yet), per point asked about (routing
  /// asks about the same entry and exit points many times), and its fan once it has been asked
  /// kFanAfter times. A fan costs some tens of tests along the grid, but a point asked about twice
  /// (a run end, a corner near the paths) is mostly asked about many more times: on traced field
  /// outlines 2 took the fewest instructions of 0 to 48 (12: 2 % more, 48: 7 % more).
  struct Row {
    std::vector<signed char> seen;
    int asked = 0;
    std::size_t known = 0, visible = 0;  ///< nodes of `seen` tested, and of them seen
    std::unique_ptr<Fan> fan;
    /// For a point searched from (path()'s a): the nodes its searches settled, each once, with
    /// its distance from the point. Every search from the point settles a node at Dijkstra's
    /// distance (up to rounding: see path()), so a later search bounds its answer by them from
    /// the start. As many entries as nodes settled, not one per node of the graph.
    std::vector<std::pair<std::uint32_t, double>> reached;
  };
  static constexpr int kFanAfter = 2;
  /// The fans of asked points a router keeps, in items (4 bytes each): 64 MB.
  static constexpr std::size_t kRowFanItemBudget = std::size_t{16} << 20;
  mutable std::size_t row_fan_items_ = 0;  ///< kept in sees_'s rows so far
  Row& seen_row(Point2 p) const;
  bool sees(Point2 p, Row& row, std::size_t node) const;
  /// One run of path()'s search, its state and its steps (visibility.cpp).
  struct Search;
  friend struct VisibilityRouterSearchProbe;  ///< tests/geometry/visibility_search_test.cpp
  /// For tests: one run of path()'s search from a to b under `limit` (no first bound), with its
  /// groups' bounds or without (visibility_search_test.cpp: the same run either way).
  struct SearchRun {
    bool answered;     ///< a way to b found under the limit
    std::size_t last;  ///< the node it ends at
    double beyond;     ///< without an answer: the least f left out
    bool left_out;
  };
  SearchRun search_run(Point2 a, Point2 b, double limit, bool groups) const;
  /// A first bound on the answer's f of a search from a to b, from the nodes earlier searches
  /// from a settled (path()); infinity: none.
  double first_bound(const Row& from_a, Row& to_b, Point2 b, double limit) const;
  /// The nodes a's searches settled (`settled`, with their g), added to a's row.
  static void remember_reached(Row& from_a, const std::vector<std::uint32_t>& settled,
                               const std::vector<double>& g_of);
  mutable std::map<std::pair<double, double>, Row> sees_;
  /// Whether nodes i < j see each other, tested from i (as the eager graph did: the test is not
  /// symmetric in rounding) and kept in both rows; through i's fan, made when a pair is first
  /// tested from i (a corner's fan serves every copy, and most corners a search reaches are tested
  /// against tens of others: on traced outlines making it at once took fewer instructions than
  /// after 1, 2 or more pairs; traced-157 1,503.7 -> 1,499.1 M, traced-067 354.6 -> 352.6 M).
  bool nodes_see(std::size_t i, std::size_t j) const;
  /// What is known of whether nodes i and j (either order: row i is read) see each other (asked
  /// before, by any copy): 1 yes, 0 no, kUnknown not asked yet.
  signed char nodes_known(std::size_t i, std::size_t j) const;
  /// Whether node j's bit in row i of the known-hidden bits is set (tests: it must be set exactly
  /// where nodes_known(i, j) is 0).
  bool hidden_bit(std::size_t i, std::size_t j) const;
  /// Which nodes see each other (in chunks of rows, made as they are first asked) and the nodes'
  /// fans, shared with copies (atomics).
  struct NodeTables;
  std::shared_ptr<NodeTables> node_tables_;
  std::size_t fan_bins_ = 0;
  double bins_per_unit_ = 0;  ///< fan bins per unit of diamond angle (4 a turn)
  double extent_m_ = 0;       ///< the largest absolute coordinate of the area, metres
  bool routing_ = true;
  bool prune_ = true;       ///< the rings neither cross nor touch: taut() prunes the search
  double tolerance_ = 0.0;  ///< distance from the boundary that still counts as on it, metres
};

/// Sum of the lengths of a polyline.
double polyline_length(const std::vector<Point2>& points);

}  // namespace swath::geometry
