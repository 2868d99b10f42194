#pragma once
// Which drone serves which request, moment by moment (paper 000 §3.3.1; docs/swath-fleet.md): a
// snapshot of drones and visible requests in, at most one target per drone out, maximising
// U(A) = Σ_k w_k u_k(A) in seconds. Pair terms (coverage, closest, fairness, avoid-zigzag,
// commitment, speculative, avoid-mutual's per-request gain) depend on one drone and one target;
// avoid-mutual's penalty depends on two assigned requests. Targets are the visible requests,
// then the forecast ones (speculation positions drones there, docs/swath-fleet.md).
// Schedulers are interchangeable behind `Scheduler`:
// simulated annealing (the paper's), and the baselines greedy, round-robin and Hungarian (exact
// for pair terms, so also a test oracle).

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "swath/energy/battery.hpp"
#include "swath/fleet/envelope.hpp"
#include "swath/fleet/forecaster.hpp"
#include "swath/vehicle/random.hpp"
#include "swath/vehicle/vec3.hpp"

namespace swath::fleet {

using vehicle::Vec3;

/// A drone as the scheduler sees it.
struct DroneState {
  Vec3 position_m;            ///< local metres (x east, y north, altitude above home)
  std::optional<int> target;  ///< the request it flies to now (index into the snapshot)
  bool busy = false;          ///< mid-action: keeps its target, not reassigned
  double soc = 1.0;           ///< state of charge, [0, 1]
  Vec3 home_m;                ///< where it lands, local metres
  bool can_sense = true;      ///< false while its sensor has failed (docs/swath-fleet.md)
  /// Flight time it has left before it must be home, s (max_flight_time_s; infinity: no limit):
  /// a request it cannot reach, serve and return from in time is infeasible for it.
  double remaining_flight_s = std::numeric_limits<double>::infinity();
  /// Reserved for a non-interruptible task (docs/swath-fleet.md): only this request (index) may be
  /// given to it; -1 when that task shows none now.
  std::optional<int> only_request;
  /// Time before it can fly its first leg, s: the climb to its layer when it is on the ground
  /// (0 airborne). Part of every eta it is given, so that a landed drone is not preferred to an
  /// airborne one that reaches the request first.
  double takeoff_s = 0;
};

/// What a pair costs in charge (paper 004 eq. 12 via energy::Battery): fly there at cruise
/// power, serve at hover power, fly home; a pair that would land below the reserve is infeasible.
struct EnergyFeasibility {
  energy::Battery battery;      ///< capacity, voltages, reserve_soc
  double cruise_power_w = 200;  ///< > 0
  double hover_power_w = 190;   ///< > 0
};

/// A visible request: a task's head segment.
struct Request {
  Vec3 location_m;
  double service_s = 0;            ///< the actions after the flight, s, ≥ 0
  double waiting_s = 0;            ///< since it became visible, s, ≥ 0
  std::optional<int> bound_drone;  ///< `same_drone`: only this drone may serve it
  bool needs_sensor = false;       ///< its segment senses: drones with a failed sensor cannot
};

/// Straight-line flight time: accelerate at `accel_m_s2` to `cruise_m_s`, brake to a stop
/// (docs/swath-fleet.md kinematics without the approach phase).
/// With `approach_within_m` > 0, also the paper's approach rule (`approach_m_s` within that
/// distance of the target), as the simulated drones fly (leg.hpp; equal to Leg's level time).
struct EtaModel {
  double cruise_m_s = 10.0;      ///< > 0
  double accel_m_s2 = 2.0;       ///< > 0
  double approach_m_s = 2.0;     ///< (0, cruise_m_s]
  double approach_within_m = 0;  ///< ≥ 0; 0: no approach phase
  /// A fence that routes (LocalEnvelope::route; null: none): the time is the way round it, each
  /// leg from rest to rest.
  const LocalEnvelope* routes = nullptr;
  double eta_s(const Vec3& from, const Vec3& to) const;
  /// The time of one straight leg.
  double leg_s(const Vec3& from, const Vec3& to) const;
};

/// The weights of the sub-utilities (the weights YAML; w_closest ≡ 1).
struct Weights {
  /// H per assigned visible request; with forecasts, plus the snapshot's largest forecast value,
  /// so that a visible request a drone could serve always beats a forecast place (ours).
  double coverage = 1.0;
  double fairness = 0.5;      ///< per second of the request's waiting
  double avoid_zigzag = 0.0;  ///< s per metre from the requests' centre
  double commitment = 5.0;    ///< s when a drone keeps its target
  /// Per forecast given to a drone: p (H − eta), s per s (paper 000 §3.3.1's speculative term).
  double speculative = 1.0;
  /// Per assigned request i: + Σ_j q(i→j) service_j (serving i may make j's service moot);
  /// per pair of assigned requests: − q(i→j)(eta_j + service_j) (j's drone may fly for
  /// nothing). Paper 000 §3.3.1 and Fig. 13; docs/swath-fleet.md for why both terms.
  double avoid_mutual = 1.0;
};

/// q(i→j) between two visible requests (indices into Snapshot::requests): the probability that
/// j is cancelled once i is done (fleet::CancellationModel).
struct MutualPair {
  int i = 0, j = 0;
  double q = 0;  ///< (0, 1]
};

/// The column an airborne drone lands through: the vertical above its home up to its layer. A drone
/// of a lower layer staying within separation of it would hold that landing (docs/swath-fleet.md,
/// 'Safety envelope'), for as long as it works there, whatever the charge left.
struct LandingColumn {
  Vec3 home_m;     ///< x, y: its home; z: its layer (local metres)
  int drone = -1;  ///< the drone landing there (index into Snapshot::drones); -1: not offered now
};

struct Snapshot {
  std::vector<DroneState> drones;
  std::vector<Request> requests;
  /// Requests expected to appear: targets requests.size() + k of an Assignment. A drone given
  /// one only flies there and hovers (nothing is served); only `speculative` values it.
  std::vector<ForecastRequest> forecasts;
  std::vector<MutualPair> mutual;  ///< q between visible requests; pairs absent: 0
  EtaModel eta;
  Weights weights;
  std::optional<EnergyFeasibility> energy;  ///< none: charge is not checked
  /// The fence (local metres, x/y; empty: none): requests outside it are infeasible.
  std::vector<std::array<double, 2>> fence;
  /// The safety envelope's fence (none: not fenced): a pair is feasible only when the target is
  /// reachable from the drone's position and its home from the target
  /// (LocalEnvelope::reachable), so every leg it flies for the target, and the way home from
  /// anywhere on them, stays inside.
  std::shared_ptr<const LocalEnvelope> envelope;
  /// Homes of the airborne drones: a target within `column_radius_m` (horizontally) of one is
  /// infeasible for a drone of a lower layer (its home_m.z), so no drone is sent to work where it
  /// would keep another from landing.
  std::vector<LandingColumn> landing_columns;
  double column_radius_m = 0;  ///< the envelope's separation_m
};

/// The state of charge a drone lands with after serving `r` and flying home (eq. 12 per leg).
double landing_soc(const EnergyFeasibility& e, const EtaModel& eta, const DroneState& d,
                   const Request& r);

/// drone → target index (a visible request, or requests.size() + k for forecast k), or nullopt
/// for none. Each target at most once.
using Assignment = std::vector<std::optional<int>>;

/// The terms of one snapshot, precomputed: value(d, r) is what assigning target r to d adds to U
/// on its own; pair_cost(...) what two assigned requests take away together (avoid-mutual);
/// infeasible pairs (binding, fence, charge) have no value.
class Utility {
 public:
  explicit Utility(const Snapshot& snapshot);
  std::size_t drones() const { return drones_; }
  /// Visible requests: targets 0 .. requests() − 1.
  std::size_t requests() const { return requests_; }
  /// Visible and forecast requests.
  std::size_t targets() const { return targets_; }
  bool is_forecast(std::size_t r) const { return r >= requests_; }
  bool feasible(std::size_t d, std::size_t r) const { return feasible_[d * targets_ + r] != 0; }
  double value(std::size_t d, std::size_t r) const { return value_[d * targets_ + r]; }
  double eta_s(std::size_t d, std::size_t r) const { return eta_[d * targets_ + r]; }
  /// A visible request's avoid-mutual partners: (j, q(i→j), q(j→i)).
  struct Link {
    std::size_t other;
    double q_out, q_in;
  };
  const std::vector<Link>& links(std::size_t r) const { return links_[r]; }
  bool has_pairwise() const { return has_pairwise_; }
  /// What requests i (served by drone di) and j (by dj) cost together, s (≥ 0), given their
  /// link: w (q(i→j)(eta(dj, j) + service_j) + q(j→i)(eta(di, i) + service_i)).
  double pair_cost(std::size_t i, std::size_t di, const Link& l, std::size_t dj) const;
  /// U(A); A must be valid (checked by valid()).
  double total(const Assignment& a) const;
  /// Each target at most once, every pair feasible, busy drones keep their target.
  bool valid(const Assignment& a) const;
  /// H: 1 + the largest feasible ETA (coverage's unit).
  double horizon_s() const { return horizon_s_; }
  const Snapshot& snapshot() const { return snapshot_; }

 private:
  bool pair_feasible(std::size_t d, std::size_t r) const;

  const Snapshot& snapshot_;
  std::size_t drones_, requests_, targets_;
  std::vector<double> value_, eta_;
  std::vector<char> feasible_;
  std::vector<std::vector<Link>> links_;
  bool has_pairwise_ = false;
  double horizon_s_ = 1.0;
};

class Scheduler {
 public:
  virtual ~Scheduler() = default;
  virtual const char* name() const = 0;
  /// At most one target per drone; busy drones keep theirs. Deterministic for the RNG's state.
  virtual Assignment assign(const Snapshot& snapshot, vehicle::SplitMix64& rng) = 0;
};

/// Smallest ETA first over all feasible pairs of visible requests (forecasts ignored).
std::unique_ptr<Scheduler> greedy_scheduler();
/// Visible requests in order to drones in turn (FIFO), nearest-free-drone ignored.
std::unique_ptr<Scheduler> round_robin_scheduler();
/// The exact optimum of the pair terms, forecasts included (Hungarian algorithm, O(n²m) with a
/// "none" per drone); avoid-mutual's pairwise penalty is not seen.
std::unique_ptr<Scheduler> hungarian_scheduler();

struct AnnealingSettings {
  int candidates = 16;  ///< nearest feasible visible requests per drone (plus its target and none)
  int forecast_candidates = 8;  ///< nearest feasible forecast requests per drone
  int moves = 20'000;           ///< geometric cooling from T₀ to T₀·10⁻³ over these
  int probe_moves = 64;         ///< T₀ = median |ΔU| of this many random moves / ln 2
};
/// Metropolis' test for a worse move, x = ΔU / T < 0, with u uniform in [0, 1) (a multiple of
/// 2⁻⁵³, vehicle::SplitMix64::uniform): rejected when u ≥ eˣ. Below x = −38, eˣ < 2⁻⁵³ ≤ any u > 0,
/// so the answer is known without exp(): the cold part of a search, most of its moves, skips the
/// call (the same decisions, so the same assignments and draws).
inline bool metropolis_rejects(double u, double x) {
  if (x < -38.0 && u > 0) return true;
  return u >= std::exp(x);
}

/// Simulated annealing (paper 000 §3.3.1): starts from the better of greedy and the current
/// targets; moves retarget one drone (the previous holder drops to none), swap two, clear one;
/// ΔU incremental (pairwise terms over the moved requests' links only).
std::unique_ptr<Scheduler> annealing_scheduler(const AnnealingSettings& settings = {});

/// The scheduler named greedy, round-robin, hungarian or sa; nullptr for another name.
std::unique_ptr<Scheduler> make_scheduler(const std::string& name);

}  // namespace swath::fleet
