#include "swath/fleet/scheduler.hpp"

#include "swath/fleet/leg.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

namespace swath::fleet {
namespace {

constexpr int kNone = -1;

std::size_t draw(vehicle::SplitMix64& rng, std::size_t n) {
  return std::min(n - 1, static_cast<std::size_t>(rng.uniform() * static_cast<double>(n)));
}

// Busy drones keep their targets: fixed first, their requests taken.
Assignment fixed_part(const Snapshot& s, std::vector<char>& taken) {
  Assignment a(s.drones.size());
  taken.assign(s.requests.size() + s.forecasts.size(), 0);
  for (std::size_t d = 0; d < s.drones.size(); ++d)
    if (s.drones[d].busy && s.drones[d].target && *s.drones[d].target >= 0 &&
        static_cast<std::size_t>(*s.drones[d].target) < s.requests.size()) {
      a[d] = s.drones[d].target;
      taken[static_cast<std::size_t>(*s.drones[d].target)] = 1;
    }
  return a;
}

Assignment greedy(const Utility& u) {
  const Snapshot& s = u.snapshot();
  std::vector<char> taken;
  Assignment a = fixed_part(s, taken);
  struct Pair {
    double eta;
    std::size_t d, r;
  };
  std::vector<Pair> pairs;
  pairs.reserve(u.drones() * u.requests());
  for (std::size_t d = 0; d < u.drones(); ++d) {
    if (s.drones[d].busy) continue;
    for (std::size_t r = 0; r < u.requests(); ++r)
      if (u.feasible(d, r) && !taken[r]) pairs.push_back({u.eta_s(d, r), d, r});
  }
  // Ties broken by drone, then request: the same order on every standard library.
  std::sort(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) {
    return x.eta != y.eta ? x.eta < y.eta : x.d != y.d ? x.d < y.d : x.r < y.r;
  });
  for (const Pair& p : pairs)
    if (!a[p.d] && !taken[p.r]) {
      a[p.d] = static_cast<int>(p.r);
      taken[p.r] = 1;
    }
  return a;
}

class Greedy final : public Scheduler {
 public:
  const char* name() const override { return "greedy"; }
  Assignment assign(const Snapshot& s, vehicle::SplitMix64&) override { return greedy(Utility(s)); }
};

class RoundRobin final : public Scheduler {
 public:
  const char* name() const override { return "round-robin"; }
  Assignment assign(const Snapshot& s, vehicle::SplitMix64&) override {
    const Utility u(s);
    std::vector<char> taken;
    Assignment a = fixed_part(s, taken);
    std::size_t next = 0;
    for (std::size_t r = 0; r < u.requests() && u.drones() > 0; ++r) {
      if (taken[r]) continue;
      for (std::size_t k = 0; k < u.drones(); ++k) {
        const std::size_t d = (next + k) % u.drones();
        if (s.drones[d].busy || a[d] || !u.feasible(d, r)) continue;
        a[d] = static_cast<int>(r);
        next = d + 1;
        break;
      }
    }
    return a;
  }
};

// Hungarian algorithm (shortest augmenting paths with potentials) minimising cost over an
// n × m matrix with n ≤ m; returns each row's column.
std::vector<std::size_t> hungarian(const std::vector<double>& cost, std::size_t n, std::size_t m) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(n + 1, 0), v(m + 1, 0), way_min(m + 1);
  std::vector<std::size_t> p(m + 1, 0), way(m + 1, 0);
  for (std::size_t i = 1; i <= n; ++i) {
    p[0] = i;
    std::size_t j0 = 0;
    std::fill(way_min.begin(), way_min.end(), inf);
    std::vector<char> used(m + 1, 0);
    do {
      used[j0] = 1;
      const std::size_t i0 = p[j0];
      double delta = inf;
      std::size_t j1 = 0;
      for (std::size_t j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double cur = cost[(i0 - 1) * m + (j - 1)] - u[i0] - v[j];
        if (cur < way_min[j]) {
          way_min[j] = cur;
          way[j] = j0;
        }
        if (way_min[j] < delta) {
          delta = way_min[j];
          j1 = j;
        }
      }
      for (std::size_t j = 0; j <= m; ++j) {
        if (used[j]) {
          u[p[j]] += delta;
          v[j] -= delta;
        } else {
          way_min[j] -= delta;
        }
      }
      j0 = j1;
    } while (p[j0] != 0);
    do {
      const std::size_t j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<std::size_t> row_to_col(n, 0);
  for (std::size_t j = 1; j <= m; ++j)
    if (p[j] != 0) row_to_col[p[j] - 1] = j - 1;
  return row_to_col;
}

class Hungarian final : public Scheduler {
 public:
  const char* name() const override { return "hungarian"; }
  Assignment assign(const Snapshot& s, vehicle::SplitMix64&) override {
    const Utility u(s);
    std::vector<char> taken;
    Assignment a = fixed_part(s, taken);
    std::vector<std::size_t> rows, cols;
    for (std::size_t d = 0; d < u.drones(); ++d)
      if (!s.drones[d].busy) rows.push_back(d);
    for (std::size_t r = 0; r < u.targets(); ++r)
      if (!taken[r]) cols.push_back(r);
    if (rows.empty()) return a;
    // Columns: the free requests, then one "none" per drone (value 0). Infeasible pairs get a
    // cost no optimum would take.
    const std::size_t n = rows.size(), m = cols.size() + n;
    double big = 1;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j : cols)
        if (u.feasible(rows[i], j)) big = std::max(big, std::abs(u.value(rows[i], j)));
    big *= 4.0 * static_cast<double>(n + 1);
    std::vector<double> cost(n * m, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < cols.size(); ++k)
        cost[i * m + k] = u.feasible(rows[i], cols[k]) ? -u.value(rows[i], cols[k]) : big;
    const std::vector<std::size_t> chosen = hungarian(cost, n, m);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t k = chosen[i];
      if (k < cols.size() && u.feasible(rows[i], cols[k]) && u.value(rows[i], cols[k]) > 0)
        a[rows[i]] = static_cast<int>(cols[k]);
    }
    return a;
  }
};

class Annealing final : public Scheduler {
 public:
  explicit Annealing(const AnnealingSettings& settings) : settings_(settings) {}
  const char* name() const override { return "sa"; }
  Assignment assign(const Snapshot& s, vehicle::SplitMix64& rng) override;

 private:
  AnnealingSettings settings_;
};

// One annealing search (docs/swath-fleet.md): the state (each drone's target, each target's
// holder), the candidates, the moves with their incremental ΔU, the temperature and the cooling
// loop.
class AnnealingRun {
 public:
  AnnealingRun(const Snapshot& s, const AnnealingSettings& settings, vehicle::SplitMix64& rng)
      : s_(s), u_(s), settings_(settings), rng_(rng) {}

  Assignment run() {
    const Assignment start = starting_assignment();
    find_candidates();
    if (free_drones_.empty()) return start;
    return anneal(u_.total(start), initial_temperature());
  }

 private:
  static constexpr int kRetarget = 0, kSwap = 1, kClear = 2;
  struct Move {
    int kind = kRetarget;
    std::size_t d1 = 0, d2 = 0;
    int r = kNone;
    double delta = 0;
    bool valid = false;
  };

  // The better of greedy and the current targets (when they are a valid assignment).
  Assignment starting_assignment() {
    const std::size_t nd = u_.drones();
    Assignment start = greedy(u_);
    Assignment current(nd);
    for (std::size_t d = 0; d < nd; ++d) current[d] = s_.drones[d].target;
    if (u_.valid(current) && u_.total(current) > u_.total(start)) start = current;
    target_.assign(nd, kNone);
    holder_.assign(u_.targets(), kNone);
    for (std::size_t d = 0; d < nd; ++d)
      if (start[d]) {
        target_[d] = *start[d];
        holder_[static_cast<std::size_t>(*start[d])] = static_cast<int>(d);
      }
    return start;
  }

  // Per free drone: its nearest feasible visible and forecast requests, its current target.
  void find_candidates() {
    const std::size_t nd = u_.drones();
    candidates_.assign(nd, {});
    for (std::size_t d = 0; d < nd; ++d) {
      if (s_.drones[d].busy) continue;
      free_drones_.push_back(d);
      auto nearest = [&](std::size_t from, std::size_t to, int count) {
        std::vector<std::pair<double, int>> near;
        for (std::size_t r = from; r < to; ++r)
          if (u_.feasible(d, r)) near.push_back({u_.eta_s(d, r), static_cast<int>(r)});
        const auto k = std::min<std::size_t>(near.size(), static_cast<std::size_t>(count));
        std::partial_sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(k), near.end());
        for (std::size_t i = 0; i < k; ++i) candidates_[d].push_back(near[i].second);
      };
      nearest(0, u_.requests(), settings_.candidates);
      nearest(u_.requests(), u_.targets(), settings_.forecast_candidates);
      if (target_[d] != kNone && std::find(candidates_[d].begin(), candidates_[d].end(),
                                           target_[d]) == candidates_[d].end())
        candidates_[d].push_back(target_[d]);
    }
  }

  double value(std::size_t d, int r) const {
    return r == kNone ? 0.0 : u_.value(d, static_cast<std::size_t>(r));
  }

  // avoid-mutual's penalty around the moved drones' requests (each pair once), as they stand.
  double local_pairs(const std::array<int, 4>& moved) const {
    double cost = 0;
    for (std::size_t k = 0; k < moved.size(); ++k) {
      const int i = moved[k];
      if (i == kNone || static_cast<std::size_t>(i) >= u_.requests() ||
          std::find(moved.begin(), moved.begin() + static_cast<std::ptrdiff_t>(k), i) !=
              moved.begin() + static_cast<std::ptrdiff_t>(k))
        continue;
      const int di = holder_[static_cast<std::size_t>(i)];
      if (di == kNone) continue;
      for (const Utility::Link& l : u_.links(static_cast<std::size_t>(i))) {
        const int dj = holder_[l.other];
        if (dj == kNone) continue;
        const bool also_moved =
            std::find(moved.begin(), moved.end(), static_cast<int>(l.other)) != moved.end();
        if (also_moved && static_cast<int>(l.other) < i) continue;  // counted from its side
        cost += u_.pair_cost(static_cast<std::size_t>(i), static_cast<std::size_t>(di), l,
                             static_cast<std::size_t>(dj));
      }
    }
    return cost;
  }

  void apply(const Move& m) {
    if (m.kind == kRetarget) {
      if (m.d2 != m.d1) target_[m.d2] = kNone;
      if (target_[m.d1] != kNone) holder_[static_cast<std::size_t>(target_[m.d1])] = kNone;
      target_[m.d1] = m.r;
      holder_[static_cast<std::size_t>(m.r)] = static_cast<int>(m.d1);
    } else if (m.kind == kSwap) {
      std::swap(target_[m.d1], target_[m.d2]);
      if (target_[m.d1] != kNone)
        holder_[static_cast<std::size_t>(target_[m.d1])] = static_cast<int>(m.d1);
      if (target_[m.d2] != kNone)
        holder_[static_cast<std::size_t>(target_[m.d2])] = static_cast<int>(m.d2);
    } else {
      holder_[static_cast<std::size_t>(target_[m.d1])] = kNone;
      target_[m.d1] = kNone;
    }
  }

  // A random move with the pair part of its ΔU (from the values).
  Move propose_pair() {
    Move m;
    const double pick = rng_.uniform();
    m.d1 = free_drones_[draw(rng_, free_drones_.size())];
    if (pick < 0.6 && !candidates_[m.d1].empty()) {
      m.kind = kRetarget;
      m.r = candidates_[m.d1][draw(rng_, candidates_[m.d1].size())];
      if (m.r == target_[m.d1]) return m;
      const int other = holder_[static_cast<std::size_t>(m.r)];
      if (other != kNone && s_.drones[static_cast<std::size_t>(other)].busy) return m;
      m.d2 = other == kNone ? m.d1 : static_cast<std::size_t>(other);
      m.delta =
          value(m.d1, m.r) - value(m.d1, target_[m.d1]) - (other == kNone ? 0.0 : value(m.d2, m.r));
      m.valid = true;
    } else if (pick < 0.85 && free_drones_.size() > 1) {
      m.kind = kSwap;
      m.d2 = free_drones_[draw(rng_, free_drones_.size())];
      const int t1 = target_[m.d1], t2 = target_[m.d2];
      if (m.d1 == m.d2 || t1 == t2) return m;
      if ((t2 != kNone && !u_.feasible(m.d1, static_cast<std::size_t>(t2))) ||
          (t1 != kNone && !u_.feasible(m.d2, static_cast<std::size_t>(t1))))
        return m;
      m.delta = value(m.d1, t2) + value(m.d2, t1) - value(m.d1, t1) - value(m.d2, t2);
      m.valid = true;
    } else {
      m.kind = kClear;
      if (target_[m.d1] == kNone) return m;
      m.delta = -value(m.d1, target_[m.d1]);
      m.valid = true;
    }
    return m;
  }

  // The whole ΔU: the pairwise part by making the move on the moved drones' entries, measuring,
  // and putting them back.
  Move propose() {
    Move m = propose_pair();
    if (!m.valid || !u_.has_pairwise()) return m;
    const std::array<int, 4> moved{target_[m.d1], target_[m.d2], m.r,
                                   m.kind == kSwap ? target_[m.d1] : kNone};
    const double before = local_pairs(moved);
    const std::array<int, 2> old_target{target_[m.d1], target_[m.d2]};
    std::array<int, 4> old_holder{};
    for (std::size_t k = 0; k < 4; ++k)
      old_holder[k] = moved[k] == kNone ? kNone : holder_[static_cast<std::size_t>(moved[k])];
    apply(m);
    m.delta -= local_pairs(moved) - before;
    target_[m.d1] = old_target[0];
    target_[m.d2] = old_target[1];
    for (std::size_t k = 4; k-- > 0;)
      if (moved[k] != kNone) holder_[static_cast<std::size_t>(moved[k])] = old_holder[k];
    return m;
  }

  // T₀ from the median |ΔU| of random moves (not made), / ln 2.
  double initial_temperature() {
    std::vector<double> probes;
    for (int k = 0; k < settings_.probe_moves; ++k)
      if (const Move m = propose(); m.valid && m.delta != 0) probes.push_back(std::abs(m.delta));
    if (probes.empty()) return 1e-9;
    std::nth_element(probes.begin(),
                     probes.begin() + static_cast<std::ptrdiff_t>(probes.size() / 2), probes.end());
    return std::max(probes[probes.size() / 2] / std::log(2.0), 1e-9);
  }

  // Geometric cooling to T₀·10⁻³; the best assignment seen.
  Assignment anneal(double now, double t0) {
    double best_value = now;
    std::vector<int> best = target_;
    const double cooling = std::pow(1e-3, 1.0 / std::max(settings_.moves, 1));
    double temperature = t0;
    for (int k = 0; k < settings_.moves; ++k, temperature *= cooling) {
      const Move m = propose();
      if (!m.valid) continue;
      if (m.delta < 0 && metropolis_rejects(rng_.uniform(), m.delta / temperature)) continue;
      apply(m);
      now += m.delta;
      if (now > best_value + 1e-12) {
        best_value = now;
        best = target_;
      }
    }
    Assignment out(best.size());
    for (std::size_t d = 0; d < best.size(); ++d)
      if (best[d] != kNone) out[d] = best[d];
    return out;
  }

  const Snapshot& s_;
  const Utility u_;
  const AnnealingSettings& settings_;
  vehicle::SplitMix64& rng_;
  std::vector<int> target_, holder_;  // drone -> target, target -> drone (kNone: none)
  std::vector<std::size_t> free_drones_;
  std::vector<std::vector<int>> candidates_;
};

Assignment Annealing::assign(const Snapshot& s, vehicle::SplitMix64& rng) {
  return AnnealingRun(s, settings_, rng).run();
}

bool inside_fence(const std::vector<std::array<double, 2>>& ring, const Vec3& p) {
  if (ring.size() < 3) return true;
  bool in = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const auto& a = ring[i];
    const auto& b = ring[j];
    if ((a[1] > p.y) != (b[1] > p.y) && p.x < (b[0] - a[0]) * (p.y - a[1]) / (b[1] - a[1]) + a[0])
      in = !in;
  }
  return in;
}

}  // namespace

double landing_soc(const EnergyFeasibility& e, const EtaModel& eta, const DroneState& d,
                   const Request& r) {
  double soc =
      energy::soc_after(e.battery, d.soc, e.cruise_power_w, eta.eta_s(d.position_m, r.location_m));
  soc = energy::soc_after(e.battery, soc, e.hover_power_w, r.service_s);
  return energy::soc_after(e.battery, soc, e.cruise_power_w, eta.eta_s(r.location_m, d.home_m));
}

double EtaModel::eta_s(const Vec3& from, const Vec3& to) const {
  if (!routes || !routes->routes()) return leg_s(from, to);
  const std::vector<Vec3> way = routes->route(from, to);
  if (way.size() < 2) return leg_s(from, to);  // straight, or no way (then not feasible)
  double s = 0;
  Vec3 at = from;
  for (const Vec3& stop : way) {
    s += leg_s(at, stop);
    at = stop;
  }
  return s;
}

double EtaModel::leg_s(const Vec3& from, const Vec3& to) const {
  // Level flight: drones fly at their altitude layers, so only the horizontal distance counts.
  const double length = std::hypot(to.x - from.x, to.y - from.y);
  if (!(length > 0)) return 0.0;
  if (approach_within_m > 0)
    return rest_to_rest_s(length, cruise_m_s, approach_m_s, approach_within_m, accel_m_s2);
  // Triangle when too short to reach cruise: v_peak = √(L a).
  if (length < cruise_m_s * cruise_m_s / accel_m_s2) return 2 * std::sqrt(length / accel_m_s2);
  return length / cruise_m_s + cruise_m_s / accel_m_s2;
}

// Binding, sensing, fence (the legs there and home too), flight time and charge (there, serve, home
// above the reserve). A forecast is a place only: no binding, no sensor, no service.
bool Utility::pair_feasible(std::size_t d, std::size_t r) const {
  const Snapshot& s = snapshot_;
  const DroneState& dr = s.drones[d];
  Request q;
  if (is_forecast(r)) {
    if (dr.only_request) return false;  // reserved for its non-interruptible task
    q.location_m = s.forecasts[r - requests_].location_m;
  } else {
    q = s.requests[r];
  }
  bool ok = (!q.bound_drone || *q.bound_drone == static_cast<int>(d)) &&
            (!dr.only_request || *dr.only_request == static_cast<int>(r)) &&
            (dr.can_sense || !q.needs_sensor) && inside_fence(s.fence, q.location_m);
  // Not the target it has: given before that drone took off, it was checked against its climb.
  const bool keeps = dr.target && *dr.target == static_cast<int>(r);
  for (const LandingColumn& c : s.landing_columns)
    if (ok && !keeps && c.drone != static_cast<int>(d) && c.home_m.z > dr.home_m.z)
      ok =
          std::hypot(q.location_m.x - c.home_m.x, q.location_m.y - c.home_m.y) >= s.column_radius_m;
  if (ok && s.envelope) ok = s.envelope->reachable(dr.position_m, q.location_m, dr.home_m);
  if (ok && std::isfinite(dr.remaining_flight_s))
    ok = s.eta.eta_s(dr.position_m, q.location_m) + q.service_s +
             s.eta.eta_s(q.location_m, dr.home_m) <=
         dr.remaining_flight_s;
  if (ok && s.energy) ok = landing_soc(*s.energy, s.eta, dr, q) >= s.energy->battery.reserve_soc;
  return ok;
}

Utility::Utility(const Snapshot& s)
    : snapshot_(s),
      drones_(s.drones.size()),
      requests_(s.requests.size()),
      targets_(s.requests.size() + s.forecasts.size()) {
  value_.assign(drones_ * targets_, 0.0);
  feasible_.assign(drones_ * targets_, 0);
  eta_.assign(drones_ * targets_, 0.0);
  auto place = [&](std::size_t r) -> const Vec3& {
    return is_forecast(r) ? s.forecasts[r - requests_].location_m : s.requests[r].location_m;
  };
  // avoid-zigzag's centre: visible requests weigh 1, forecasts their p.
  Vec3 centre;
  double weight = 0;
  for (std::size_t r = 0; r < targets_; ++r) {
    const double w = is_forecast(r) ? s.forecasts[r - requests_].p : 1.0;
    centre = centre + place(r) * w;
    weight += w;
  }
  if (weight > 0) centre = centre / weight;
  for (std::size_t d = 0; d < drones_; ++d)
    for (std::size_t r = 0; r < targets_; ++r) {
      const bool ok = pair_feasible(d, r);
      feasible_[d * targets_ + r] = ok ? 1 : 0;
      eta_[d * targets_ + r] =
          s.drones[d].takeoff_s + s.eta.eta_s(s.drones[d].position_m, place(r));
      if (ok) horizon_s_ = std::max(horizon_s_, 1.0 + eta_[d * targets_ + r]);
    }
  const Weights& w = s.weights;
  // avoid-mutual: each request's links, and the gain of serving it first.
  links_.assign(requests_, {});
  std::vector<double> mutual_gain(requests_, 0.0);
  for (const MutualPair& m : s.mutual) {
    if (m.i < 0 || m.j < 0 || m.i == m.j || static_cast<std::size_t>(m.i) >= requests_ ||
        static_cast<std::size_t>(m.j) >= requests_ || !(m.q > 0) || w.avoid_mutual == 0)
      continue;
    const auto i = static_cast<std::size_t>(m.i), j = static_cast<std::size_t>(m.j);
    mutual_gain[i] += m.q * s.requests[j].service_s;
    auto add = [&](std::size_t a, std::size_t b, double out, double in) {
      for (Link& l : links_[a])
        if (l.other == b) {
          l.q_out += out;
          l.q_in += in;
          return;
        }
      links_[a].push_back({b, out, in});
    };
    add(i, j, m.q, 0);
    add(j, i, 0, m.q);
    has_pairwise_ = true;
  }
  // Forecasts first: the largest forecast value is what coverage must add to each visible
  // request so that no drone waits at a forecast place while a request it could serve waits
  // (speculation is for idle drones: a forecast of the next iteration cannot appear before this
  // one's requests are served).
  double best_forecast = 0;
  for (std::size_t d = 0; d < drones_; ++d)
    for (std::size_t r = 0; r < targets_; ++r) {
      const bool keeps = s.drones[d].target && *s.drones[d].target == static_cast<int>(r);
      double v = w.avoid_zigzag * norm(place(r) - centre) + (keeps ? w.commitment : 0.0);
      if (is_forecast(r)) {
        v += w.speculative * s.forecasts[r - requests_].p * (horizon_s_ - eta_[d * targets_ + r]);
        if (feasible(d, r)) best_forecast = std::max(best_forecast, v);
      }
      value_[d * targets_ + r] = v;
    }
  for (std::size_t d = 0; d < drones_; ++d)
    for (std::size_t r = 0; r < requests_; ++r) {
      const Request& q = s.requests[r];
      value_[d * targets_ + r] += w.coverage * horizon_s_ + best_forecast - eta_[d * targets_ + r] +
                                  w.fairness * q.waiting_s + w.avoid_mutual * mutual_gain[r];
    }
}

double Utility::pair_cost(std::size_t i, std::size_t di, const Link& l, std::size_t dj) const {
  const double si = snapshot_.requests[i].service_s, sj = snapshot_.requests[l.other].service_s;
  return snapshot_.weights.avoid_mutual *
         (l.q_out * (eta_s(dj, l.other) + sj) + l.q_in * (eta_s(di, i) + si));
}

double Utility::total(const Assignment& a) const {
  double sum = 0;
  std::vector<int> holder(has_pairwise_ ? requests_ : 0, -1);
  for (std::size_t d = 0; d < a.size() && d < drones_; ++d)
    if (a[d]) {
      const auto r = static_cast<std::size_t>(*a[d]);
      sum += value(d, r);
      if (has_pairwise_ && r < requests_) holder[r] = static_cast<int>(d);
    }
  if (has_pairwise_)
    for (std::size_t i = 0; i < requests_; ++i)
      if (holder[i] >= 0)
        for (const Link& l : links_[i])
          if (l.other > i && holder[l.other] >= 0)
            sum -= pair_cost(i, static_cast<std::size_t>(holder[i]), l,
                             static_cast<std::size_t>(holder[l.other]));
  return sum;
}

bool Utility::valid(const Assignment& a) const {
  if (a.size() != drones_) return false;
  std::vector<char> seen(targets_, 0);
  for (std::size_t d = 0; d < drones_; ++d) {
    const DroneState& drone = snapshot_.drones[d];
    if (drone.busy && a[d] != drone.target) return false;
    if (!a[d]) continue;
    const int r = *a[d];
    if (r < 0 || static_cast<std::size_t>(r) >= targets_ || seen[static_cast<std::size_t>(r)] ||
        !feasible(d, static_cast<std::size_t>(r)))
      return false;
    seen[static_cast<std::size_t>(r)] = 1;
  }
  return true;
}

std::unique_ptr<Scheduler> greedy_scheduler() {
  return std::make_unique<Greedy>();
}
std::unique_ptr<Scheduler> round_robin_scheduler() {
  return std::make_unique<RoundRobin>();
}
std::unique_ptr<Scheduler> hungarian_scheduler() {
  return std::make_unique<Hungarian>();
}
std::unique_ptr<Scheduler> annealing_scheduler(const AnnealingSettings& settings) {
  return std::make_unique<Annealing>(settings);
}

std::unique_ptr<Scheduler> make_scheduler(const std::string& name) {
  if (name == "greedy") return greedy_scheduler();
  if (name == "round-robin") return round_robin_scheduler();
  if (name == "hungarian") return hungarian_scheduler();
  if (name == "sa") return annealing_scheduler();
  return nullptr;
}

}  // namespace swath::fleet
