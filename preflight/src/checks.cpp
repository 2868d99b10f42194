// The per-file checks of a flown path: zones, fences, ceiling and ground, photos (issue 45).
#include "checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "swath/base/number_text.hpp"
#include "swath/geometry/autopilot_track.hpp"
#include "swath/geometry/predicates.hpp"

namespace swath::preflight {
namespace {

using base::fixed_text;
using geometry::Point2;

constexpr double kInf = std::numeric_limits<double>::infinity();
// Positions are written to 1e-9 degrees (0.1 mm) and altitudes to 1 mm: closer calls are rounding.
constexpr double kTolerance_m = 1e-3;

Point2 closest_on_segment(Point2 p, Point2 a, Point2 b) {
  const Point2 d = b - a;
  const double len2 = geometry::dot(d, d);
  if (len2 <= 0) return a;
  const double t = std::clamp(geometry::dot(p - a, d) / len2, 0.0, 1.0);
  return a + d * t;
}

}  // namespace

std::string on_track(double bow_m) {
  if (bow_m <= 0) return "";
  return "; on the track ArduPilot flies, which strays up to " + fixed_text(bow_m, 2) +
         " m from the straight leg (it steers legs straight in latitude and longitude): split the "
         "leg with waypoints";
}

SegmentDistance segment_distance(Point2 p, Point2 q, Point2 a, Point2 b) {
  if (geometry::segments_intersect(p, q, a, b))
    return {0.0, geometry::segments_common_point(p, q, a, b)};
  SegmentDistance best{kInf, p};
  auto consider = [&](Point2 on_pq, Point2 other) {
    const double d = geometry::distance(on_pq, other);
    if (d < best.distance_m) best = {d, on_pq};
  };
  consider(p, closest_on_segment(p, a, b));
  consider(q, closest_on_segment(q, a, b));
  consider(closest_on_segment(a, p, q), a);
  consider(closest_on_segment(b, p, q), b);
  return best;
}

// The edges are taken in order and the first nearest kept, as by measuring every edge; an edge is
// measured only if its bounding box comes near enough the segment's to hold a point as near as
// the nearest so far, or as the nearest vertex (a distance segment_distance itself measures for
// the vertex's edges, so the result is at most that). The boxes' gap along x or y is a lower bound
// of the distance of any two points of them; the slack covers the rounding of the measured
// distance (a few ulps of the coordinates: below 1e-8 m up to 10^7 m from the frame's origin), so
// that an edge skipped could not have been taken.
SegmentDistance ring_distance(Point2 p, Point2 q, const geometry::Ring& ring) {
  constexpr double kBoxSlack_m = 1e-6;
  const double lo_x = std::min(p.x, q.x), hi_x = std::max(p.x, q.x);
  const double lo_y = std::min(p.y, q.y), hi_y = std::max(p.y, q.y);
  double nearest_vertex_m = kInf;
  for (const Point2 a : ring)
    nearest_vertex_m =
        std::min(nearest_vertex_m, geometry::distance(closest_on_segment(a, p, q), a));
  SegmentDistance best{kInf, p};
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point2 a = ring[i], b = ring[i + 1 < ring.size() ? i + 1 : 0];
    const double gap_x = std::max(std::min(a.x, b.x) - hi_x, lo_x - std::max(a.x, b.x));
    const double gap_y = std::max(std::min(a.y, b.y) - hi_y, lo_y - std::max(a.y, b.y));
    if (std::max(gap_x, gap_y) - kBoxSlack_m > std::min(best.distance_m, nearest_vertex_m))
      continue;
    const SegmentDistance d = segment_distance(p, q, a, b);
    if (d.distance_m < best.distance_m) best = d;
  }
  return best;
}

SegmentDistance zone_distance(Point2 p, Point2 q, const geometry::Ring& ring) {
  if (geometry::locate_point(p, ring) != geometry::Containment::outside) return {0.0, p};
  return ring_distance(p, q, ring);
}

std::vector<PathPiece> pieces(const FlownPath& path) {
  std::vector<PathPiece> out;
  for (const Leg& l : path.legs)
    if (l.kind != LegKind::hold) out.push_back({l.from, l.to, l.place, false});
  for (const Overrun& o : path.overruns) out.push_back({o.from, o.to, o.place, true});
  if (out.empty()) out.push_back({path.home, path.home, path.source + ": home", false});
  return out;
}

std::string piece_name(const PathPiece& piece) {
  return piece.place + (piece.overrun ? " (its stopping margin)" : "");
}

namespace {

// A ring's bounding box.
struct Box {
  double lo_x = kInf, lo_y = kInf, hi_x = -kInf, hi_y = -kInf;
};

Box box_of(const geometry::Ring& ring) {
  Box b;
  for (const Point2 v : ring) {
    b.lo_x = std::min(b.lo_x, v.x), b.hi_x = std::max(b.hi_x, v.x);
    b.lo_y = std::min(b.lo_y, v.y), b.hi_y = std::max(b.hi_y, v.y);
  }
  return b;
}

// A lower bound of the distance between any point of [p, q] and any of the box: their gap along
// x or y (0 or less when they overlap).
double box_gap(Point2 p, Point2 q, const Box& b) {
  const double gap_x = std::max(b.lo_x - std::max(p.x, q.x), std::min(p.x, q.x) - b.hi_x);
  const double gap_y = std::max(b.lo_y - std::max(p.y, q.y), std::min(p.y, q.y) - b.hi_y);
  return std::max(gap_x, gap_y);
}

// The least of `measure` (a SegmentDistance of a straight piece [p, q]) over the tracks the
// vehicle flies for `piece` (geometry::AutopilotTrack): each track in as many pieces as keep its
// chords within 0.1 mm of it. `chord`: the measure of the straight piece, returned where the tracks
// cannot stray far enough to matter: by at most the cheap bound, then the bow measured, short of
// `worth_m` less the measure.
struct TrackDistance {
  SegmentDistance least;
  double bow_m = 0;  ///< > 0: `least` is the track's, which strays this far from the leg
};
template <class Measure>
TrackDistance least_along_track(const geometry::AutopilotTrack& track, const PathPiece& piece,
                                SegmentDistance chord, double worth_m, Measure measure) {
  const Point2 a = piece.from.xy(), b = piece.to.xy();
  if (chord.distance_m - track.bow_bound_m(a, b) > worth_m) return {chord};
  const double bow = track.bow_m(a, b);
  if (chord.distance_m - bow > worth_m || bow < geometry::AutopilotTrack::kNegligibleBow_m)
    return {chord};
  TrackDistance out{chord};
  for (const std::vector<Point2>& points :
       track.tracks(a, b, geometry::AutopilotTrack::pieces_for(bow)))
    for (std::size_t k = 0; k + 1 < points.size(); ++k) {
      const SegmentDistance d = measure(points[k], points[k + 1]);
      if (d.distance_m < out.least.distance_m) out = {d, bow};
    }
  return out;
}

}  // namespace

// A ring zone whose bounding box is farther from a piece than both the least clearance so far and
// the clearance asked is not measured: it could neither be the nearest (only a strictly nearer
// one replaces it) nor a violation. The slack is ring_distance's (rounding of the measure).
void check_zones(const FileContext& f, const std::vector<LocalZone>& zones, double clearance_m,
                 Checked& out) {
  constexpr double kBoxSlack_m = 1e-6;
  std::vector<Box> boxes;
  for (const LocalZone& zone : zones) boxes.push_back(box_of(zone.ring));
  const geometry::AutopilotTrack track(*f.frame, f.path->home.xy());
  for (const PathPiece& piece : pieces(*f.path))
    for (std::size_t z = 0; z < zones.size(); ++z) {
      const LocalZone& zone = zones[z];
      const double asked = zone.own_fence ? 0.0 : clearance_m;
      const double bound = track.bow_bound_m(piece.from.xy(), piece.to.xy());
      if (zone.radius_m <= 0 &&
          box_gap(piece.from.xy(), piece.to.xy(), boxes[z]) - kBoxSlack_m - bound >
              std::max(out.least_clearance_m, asked))
        continue;
      const auto measure = [&](Point2 p, Point2 q) -> SegmentDistance {
        if (zone.radius_m <= 0) return zone_distance(p, q, zone.ring);
        const Point2 c = zone.ring.front();
        const Point2 at = closest_on_segment(c, p, q);
        return {std::max(0.0, geometry::distance(at, c) - zone.radius_m), at};
      };
      // Measured along the vehicle's track where it may come nearer than asked, or than the
      // least clearance so far.
      const TrackDistance t =
          least_along_track(track, piece, measure(piece.from.xy(), piece.to.xy()),
                            std::max(out.least_clearance_m, asked), measure);
      const SegmentDistance& d = t.least;
      if (d.distance_m < out.least_clearance_m) {
        out.least_clearance_m = d.distance_m;
        out.least_clearance_where = zone.name;
      }
      // Touching a zone counts as entering it, whatever the clearance asked.
      if (d.distance_m <= 0 || d.distance_m < asked - kTolerance_m - zone.slack_m)
        out.violations.push_back(
            {"no-fly zone", piece_name(piece), f.frame->to_geo(d.at), asked - d.distance_m,
             d.distance_m <= 0
                 ? piece_name(piece) + " enters " + zone.name + " (" + fixed_text(asked, 2) +
                       " m clearance asked)" + on_track(t.bow_m)
                 : piece_name(piece) + " comes within " + fixed_text(d.distance_m, 2) + " m of " +
                       zone.name + " (" + fixed_text(asked, 2) + " m asked: " +
                       fixed_text(asked - d.distance_m, 2) + " m short)" + on_track(t.bow_m)});
    }
}

namespace {

// A piece whose ends are inside a fence but which touches or crosses its boundary: how far out it
// goes (sampled every 1/64 of its length; 0 when it only touches).
SegmentDistance notch_depth(const PathPiece& piece, const geometry::Ring& ring) {
  SegmentDistance worst{0.0, piece.from.xy()};
  for (int k = 1; k < 64; ++k) {
    const Point2 p = piece.from.xy() + (piece.to.xy() - piece.from.xy()) * (k / 64.0);
    if (geometry::locate_point(p, ring) != geometry::Containment::outside) continue;
    const double out_m = ring_distance(p, p, ring).distance_m;
    if (-out_m < worst.distance_m) worst = {-out_m, p};
  }
  return worst;
}

// How far inside one inclusion fence a piece stays (negative: outside by that much), and where.
SegmentDistance fence_margin(const PathPiece& piece, const LocalZone& fence) {
  SegmentDistance margin{kInf, piece.from.xy()};
  if (fence.radius_m > 0) {  // a circle: a segment is farthest from its centre at an end
    for (Point2 p : {piece.from.xy(), piece.to.xy()}) {
      const double m = fence.radius_m - geometry::distance(p, fence.ring.front());
      if (m < margin.distance_m) margin = {m, p};
    }
    return margin;
  }
  const SegmentDistance edge = ring_distance(piece.from.xy(), piece.to.xy(), fence.ring);
  bool inside = true;
  for (Point2 p : {piece.from.xy(), piece.to.xy()})
    if (geometry::locate_point(p, fence.ring) == geometry::Containment::outside) {
      inside = false;
      const double out_m = ring_distance(p, p, fence.ring).distance_m;
      if (-out_m < margin.distance_m) margin = {-out_m, p};
    }
  if (inside) margin = edge.distance_m > 0 ? edge : notch_depth(piece, fence.ring);
  return margin;
}

// The piece's margin against the fences together, and the fence that decides it: the least over
// all of them (the vehicle must stay inside every one), or with `any_one` the greatest (inside
// one is enough).
std::pair<SegmentDistance, std::size_t> fences_margin(const PathPiece& piece,
                                                      const std::vector<LocalZone>& fences,
                                                      bool any_one) {
  std::pair<SegmentDistance, std::size_t> decided{{any_one ? -kInf : kInf, piece.from.xy()}, 0};
  for (std::size_t i = 0; i < fences.size(); ++i) {
    const SegmentDistance m = fence_margin(piece, fences[i]);
    if (any_one ? m.distance_m > decided.first.distance_m : m.distance_m < decided.first.distance_m)
      decided = {m, i};
  }
  return decided;
}

}  // namespace

void check_fences(const FileContext& f, const std::vector<LocalZone>& fences, bool any_one,
                  Checked& out) {
  if (fences.empty()) return;
  out.fence_checked = true;
  out.most_inclusion_fences = std::max(out.most_inclusion_fences, fences.size());
  std::vector<PathPiece> all = pieces(*f.path);
  for (Point2 r : f.rally_points)
    all.push_back({{r.x, r.y, 0}, {r.x, r.y, 0}, f.source + ": rally point", false});
  all.push_back({f.path->home, f.path->home, f.source + ": home", false});
  const geometry::AutopilotTrack track(*f.frame, f.path->home.xy());
  for (const PathPiece& piece : all) {
    // Measured along the vehicle's track where it may stray outside.
    const auto [chord, chord_fence] = fences_margin(piece, fences, any_one);
    const auto margin = [&](Point2 p, Point2 q) {
      return fences_margin({{p.x, p.y, 0}, {q.x, q.y, 0}, piece.place, piece.overrun}, fences,
                           any_one);
    };
    const TrackDistance t = least_along_track(
        track, piece, chord, 0.0, [&](Point2 p, Point2 q) { return margin(p, q).first; });
    const SegmentDistance& m = t.least;
    // The fence left: the straight leg's, or the one the track is farthest out of where it is.
    const std::size_t fence = t.bow_m > 0 ? margin(m.at, m.at).second : chord_fence;
    out.least_fence_margin_m = std::min(out.least_fence_margin_m, m.distance_m);
    if (m.distance_m < -kTolerance_m - fences[fence].slack_m)
      out.violations.push_back(
          {"fence", piece_name(piece), f.frame->to_geo(m.at), -m.distance_m,
           piece_name(piece) + " is " + fixed_text(-m.distance_m, 2) + " m outside " +
               (any_one && fences.size() > 1 ? "every inclusion fence" : fences[fence].name) +
               on_track(t.bow_m)});
  }
}

namespace {

// The least and the most height of a leg above the ground (a DEM), or above home without one (a
// straight leg is highest and lowest at an end), and where.
struct LegHeights {
  double least_m = 0, most_m = 0;
  Point2 least_at, most_at;
};

LegHeights leg_heights(const FileContext& f, const geometry::Ground* ground, const Leg& l) {
  const auto xy = [&](double t) { return l.from.xy() + (l.to.xy() - l.from.xy()) * t; };
  if (!ground) {
    return {std::min(l.from.z_m, l.to.z_m), std::max(l.from.z_m, l.to.z_m),
            l.to.z_m < l.from.z_m ? l.to.xy() : l.from.xy(),
            l.to.z_m > l.from.z_m ? l.to.xy() : l.from.xy()};
  }
  // Sampled where the ground's worst point under the straight leg lies (every half pixel, every
  // row and column of pixel centres it crosses, and the extremes between): a cliff between two
  // samples a half pixel apart hid a leg 3 m into the ground.
  const geometry::GroundProfile p = geometry::ground_profile(
      *ground, [&](double t) { return f.frame->to_geo(xy(t)); },
      geometry::distance(l.from.xy(), l.to.xy()));
  for (const double g : p.ground_m)
    if (!std::isfinite(g) || !std::isfinite(f.home_ground_amsl_m))  // no ground: as flat at home
      return leg_heights(f, nullptr, l);
  const double home = f.home_ground_amsl_m;
  const geometry::HeightAboveGround h =
      geometry::height_above_ground(p, 0, p.t.size() - 1, l.from.z_m + home, l.to.z_m + home);
  return {h.least_m, h.most_m, xy(h.t_least), xy(h.t_most)};
}

}  // namespace

void check_heights(const FileContext& f, const CheckOptions& options, Checked& out) {
  const geometry::Ground* ground = options.ground.get();
  for (const Leg& l : f.path->legs) {
    if (l.kind == LegKind::hold) continue;
    const LegHeights h = leg_heights(f, ground, l);
    const double worst_high = h.most_m, worst_low = h.least_m;
    if (worst_high > out.max_height_m) out.max_height_m = worst_high;
    if (worst_high > options.ceiling_m + kTolerance_m)
      out.violations.push_back(
          {"ceiling", l.place, f.frame->to_geo(h.most_at), worst_high - options.ceiling_m,
           l.place + " flies at " + fixed_text(worst_high, 1) + " m above " +
               (ground ? "the ground" : "home") + ", " +
               fixed_text(worst_high - options.ceiling_m, 1) + " m above the " +
               fixed_text(options.ceiling_m, 1) + " m ceiling"});
    // Without a DEM the ground is taken as flat at home's height: below home is below it.
    if (!ground && worst_low < -kTolerance_m)
      out.violations.push_back({"ground", l.place, f.frame->to_geo(h.least_at), -worst_low,
                                l.place + " flies " + fixed_text(-worst_low, 1) +
                                    " m below home, under the ground (without a DEM, --terrain, "
                                    "taken as flat at home's height)"});
    if (ground && (l.kind == LegKind::cruise || l.kind == LegKind::rtl)) {
      out.min_height_m = std::min(out.min_height_m, worst_low);
      if (worst_low < options.min_height_m - kTolerance_m)
        out.violations.push_back(
            {"ground", l.place, f.frame->to_geo(h.least_at), options.min_height_m - worst_low,
             l.place +
                 (worst_low < 0 ? " goes " + fixed_text(-worst_low, 1) + " m into the ground, "
                                : " passes " + fixed_text(worst_low, 1) + " m above the ground, ") +
                 fixed_text(options.min_height_m - worst_low, 1) + " m below the least " +
                 fixed_text(options.min_height_m, 1) + " m"});
    }
  }
}

namespace {

bool meets_area(const Leg& l, const std::vector<geometry::Ring>& area) {
  for (const geometry::Ring& ring : area)
    if (zone_distance(l.from.xy(), l.to.xy(), ring).distance_m <= 0) return true;
  return false;
}

// Per leg: whether the straight run it belongs to (legs flown through without a stop, as a survey
// line split into several waypoints is) meets the area. A line reaching beyond the boundary is
// still a line; a run that never meets the area is a transit.
std::vector<bool> runs_meeting_area(const std::vector<Leg>& legs,
                                    const std::vector<geometry::Ring>& area) {
  std::vector<bool> out(legs.size(), true);
  if (area.empty()) return out;
  std::size_t start = 0;
  for (std::size_t i = 0; i < legs.size(); ++i) {
    const bool run_ends = legs[i].kind != LegKind::cruise || legs[i].stops_at_end ||
                          i + 1 == legs.size() || legs[i + 1].kind != LegKind::cruise;
    if (!run_ends) continue;
    bool meets = false;
    for (std::size_t k = start; k <= i && !meets; ++k) meets = meets_area(legs[k], area);
    for (std::size_t k = start; k <= i; ++k) out[k] = meets;
    start = i + 1;
  }
  return out;
}

const char* transit_kind(const Leg& l, bool run_meets_area) {
  switch (l.kind) {
    case LegKind::climb:
      return "the take-off climb";
    case LegKind::rtl:
      return "the return to launch";
    case LegKind::descent:
      return "the landing";
    case LegKind::hold:
      return nullptr;
    case LegKind::cruise:
      break;
  }
  // A cruise leg is a transit only where the area says so: a survey line may start or end at home.
  if (!run_meets_area) return "a transit outside the area";
  return nullptr;
}

// Photos triggered on each leg: a photo each time the distance (or time) since the last one
// reaches the trigger's, counted on across legs while the trigger stays on (a line split by
// waypoints is one run of photos, as ArduPilot triggers it), anew from a trigger item (with its
// photo at once where it asks for one).
class PhotoCounter {
 public:
  double photos_on(const Leg& l) {
    const bool distance = l.trigger_distance_m > 0;
    const double every = distance ? l.trigger_distance_m : l.trigger_interval_s;
    if (l.trigger_started || every != every_ || distance != distance_) since_ = 0;
    every_ = every, distance_ = distance;
    since_ += distance ? geometry::distance(l.from.xy(), l.to.xy()) : l.t_end_s - l.t_start_s;
    const double n = std::floor(since_ / every + 1e-9);
    since_ = std::max(since_ - n * every, 0.0);
    return n + (l.photo_at_start ? 1 : 0);
  }
  void off() { every_ = 0; }

 private:
  double since_ = 0, every_ = 0;
  bool distance_ = true;
};

}  // namespace

void check_photos(const FileContext& f, const std::vector<geometry::Ring>& area, Checked& out) {
  const std::vector<bool> meets = runs_meeting_area(f.path->legs, area);
  PhotoCounter counter;
  for (std::size_t i = 0; i < f.path->legs.size(); ++i) {
    const Leg& l = f.path->legs[i];
    if (l.trigger_distance_m <= 0 && l.trigger_interval_s <= 0) {
      counter.off();
      continue;
    }
    const double photos = counter.photos_on(l);
    const char* transit = transit_kind(l, meets[i]);
    if (transit == nullptr) {
      out.photos += photos;
      ++out.photo_legs;
      continue;
    }
    out.transit_photos += photos;
    out.violations.push_back(
        {"photos", l.place, f.frame->to_geo(l.from.xy()), photos,
         l.place + " leaves the camera triggering (" +
             (l.trigger_distance_m > 0 ? "every " + fixed_text(l.trigger_distance_m, 2) + " m"
                                       : "every " + fixed_text(l.trigger_interval_s, 2) + " s") +
             ") on in " + transit + ": " + fixed_text(photos, 0) + " photos"});
  }
}

}  // namespace swath::preflight
