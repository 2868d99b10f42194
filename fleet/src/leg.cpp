#include "swath/fleet/leg.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace swath::fleet {
namespace {

// A bound on v² that is linear in the distance flown s on [from_m, to_m]: v² ≤ a + b·s.
struct Bound {
  double a, b, from_m, to_m;
  double at(double s) const { return a + b * s; }
  bool covers(double s) const { return s >= from_m - 1e-12 && s <= to_m + 1e-12; }
};

std::vector<LegPiece> profile(double length_m, const Kinematics& k, double v0) {
  std::vector<LegPiece> out;
  if (!(length_m > 0)) return out;
  const double inf = std::numeric_limits<double>::infinity();
  const double acc = k.accel_m_s2 > 0 ? k.accel_m_s2 : inf;
  const double approach_from = std::max(0.0, length_m - k.approach_within_m);
  const double vc = k.cruise_m_s;
  const double va = k.approach_within_m > 0 ? std::min(k.approach_m_s, vc) : vc;
  std::vector<Bound> bounds;
  bounds.push_back({vc * vc, 0, 0, approach_from});
  bounds.push_back({va * va, 0, approach_from, length_m});
  if (std::isfinite(acc)) {
    bounds.push_back({v0 * v0, 2 * acc, 0, length_m});              // speeding up
    bounds.push_back({2 * acc * length_m, -2 * acc, 0, length_m});  // stopping at the end
    bounds.push_back({va * va + 2 * acc * approach_from, -2 * acc, 0, approach_from});  // slowing
  }
  // Breakpoints: the ends, the approach point, and where two bounds cross.
  std::vector<double> cuts{0.0, approach_from, length_m};
  for (std::size_t i = 0; i < bounds.size(); ++i)
    for (std::size_t j = i + 1; j < bounds.size(); ++j) {
      const double db = bounds[i].b - bounds[j].b;
      if (db == 0) continue;
      const double s = (bounds[j].a - bounds[i].a) / db;
      if (s > 0 && s < length_m) cuts.push_back(s);
    }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end(),
                         [](double x, double y) { return std::abs(x - y) < 1e-12; }),
             cuts.end());
  double t = 0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double s0 = cuts[i], s1 = cuts[i + 1];
    if (s1 - s0 < 1e-12) continue;
    const double mid = 0.5 * (s0 + s1);
    const Bound* best = nullptr;
    for (const Bound& b : bounds)
      if (b.covers(mid) && (!best || b.at(mid) < best->at(mid))) best = &b;
    const double w0 = std::sqrt(std::max(0.0, best->at(s0)));
    const double w1 = std::sqrt(std::max(0.0, best->at(s1)));
    const double dt = best->b == 0 ? (s1 - s0) / w0 : 2 * (w1 - w0) / best->b;
    out.push_back({s0, s1, best->a, best->b, t, w0, w1});
    t += dt;
  }
  return out;
}

double piece_end_s(const LegPiece& p) {
  return p.beta == 0 ? (p.s1_m - p.s0_m) / p.v0_m_s : 2 * (p.v1_m_s - p.v0_m_s) / p.beta;
}

}  // namespace

Leg::Leg(const Vec3& from, const Vec3& to, const Kinematics& k, double initial_speed_m_s)
    : from_(from), to_(to) {
  const double dz = to.z - from.z;
  vertical_s_ = dz > 0 ? dz / k.climb_m_s : -dz / k.descent_m_s;
  length_m_ = std::hypot(to.x - from.x, to.y - from.y);
  if (length_m_ > 0) unit_ = {(to.x - from.x) / length_m_, (to.y - from.y) / length_m_, 0};
  // A vertical part first means the drone stops before it: it enters level flight at rest.
  const double v0 = vertical_s_ > 0 ? 0.0 : std::max(0.0, initial_speed_m_s);
  pieces_ = profile(length_m_, k, v0);
  horizontal_s_ = pieces_.empty() ? 0.0 : pieces_.back().t0_s + piece_end_s(pieces_.back());
}

double Leg::distance_at(double ht) const {
  if (pieces_.empty() || ht <= 0) return 0;
  if (ht >= horizontal_s_) return length_m_;
  auto it = std::upper_bound(pieces_.begin(), pieces_.end(), ht,
                             [](double x, const LegPiece& p) { return x < p.t0_s; });
  const LegPiece& p = *(it - 1);
  const double tau = ht - p.t0_s;
  if (p.beta == 0) return std::min(p.s1_m, p.s0_m + p.v0_m_s * tau);
  const double v = p.v0_m_s + 0.5 * p.beta * tau;
  return std::clamp(p.s0_m + (v * v - p.v0_m_s * p.v0_m_s) / p.beta, p.s0_m, p.s1_m);
}

Vec3 Leg::position_at(double t) const {
  if (t <= 0) return from_;
  if (t < vertical_s_) {
    const double f = t / vertical_s_;
    return {from_.x, from_.y, from_.z + f * (to_.z - from_.z)};
  }
  if (t >= duration_s()) return to_;
  const double s = distance_at(t - vertical_s_);
  return {from_.x + unit_.x * s, from_.y + unit_.y * s, to_.z};
}

double Leg::speed_at(double t) const {
  if (t < vertical_s_ || t >= duration_s() || pieces_.empty()) return 0;
  const double ht = t - vertical_s_;
  auto it = std::upper_bound(pieces_.begin(), pieces_.end(), ht,
                             [](double x, const LegPiece& p) { return x < p.t0_s; });
  const LegPiece& p = *(it - 1);
  return p.beta == 0 ? p.v0_m_s : p.v0_m_s + 0.5 * p.beta * (ht - p.t0_s);
}

Leg next_leg(const Leg* current, double t_on_s, const Vec3& from, const Vec3& to,
             const Kinematics& k) {
  const Vec3 new_dir = to - from;
  const bool there = std::hypot(new_dir.x, new_dir.y) < 1e-9 && std::abs(new_dir.z) < 1e-9;
  double v0 = 0;
  if (current && !there) {
    const double along = current->speed_at(t_on_s);
    const Vec3 old_dir = current->to() - current->from();
    const double n0 = std::hypot(old_dir.x, old_dir.y), n1 = std::hypot(new_dir.x, new_dir.y);
    if (n0 > 0 && n1 > 0)
      v0 = along * std::max(0.0, (old_dir.x * new_dir.x + old_dir.y * new_dir.y) / (n0 * n1));
  }
  return Leg(from, to, k, v0);
}

double horizontal_time_s(double length_m, const Kinematics& k) {
  return Leg({0, 0, 0}, {length_m, 0, 0}, k).duration_s();
}

}  // namespace swath::fleet
