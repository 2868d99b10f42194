#pragma once
// Forecasting an application's next requests and cancellations from its task graph
// (paper 000 §3.2.2; docs/swath-fleet.md). A `Forecaster` looks at the DTG as it stands now — its
// frontier being the task nodes still running — and says where requests will appear next and how
// likely; the scheduler may send drones ahead there (docs/swath-fleet.md, 'Speculation and
// avoid-mutual') and weighs against serving requests that are about to be cancelled (q,
// avoid-mutual). Three strategies behind one interface:
//   gmf               graph matching against past runs (the paper's GMF),
//   constant-velocity each kind's latest batch of tasks moved on by its last displacement (the
//                     baseline GMF must beat),
//   none              no forecasts (the reactive scheduler's view).

#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "swath/fleet/dtg.hpp"

namespace swath::fleet {

/// A request expected to appear.
struct ForecastRequest {
  std::string kind;          ///< the kind of the task expected to show it
  vehicle::Vec3 location_m;  ///< local metres, as first_loc
  double p = 0;              ///< probability it appears, (0, 1]
  double expected_s = 0;  ///< when it is expected, s since the run began (≥ the forecast's now)
};

/// q(i→j) (the paper gives no algorithm; docs/swath-fleet.md, 'Forecasting the next requests'): the
/// probability that task j is cancelled by a cancel issued from task i or from the await on i,
/// given that i ended done while j was running. Empirical, by kind pair and distance between first
/// locations in 1 m bins; a bin is smoothed toward its kind pair's rate (Laplace: (c + r) / (n +
/// 1), r = (C + 1) / (N + 2) over the pair's bins), so an unseen distance is not a coin toss. Kind
/// pairs never seen: 0.
class CancellationModel {
 public:
  /// Adds every (i done, j running then) pair of a finished run.
  void learn(const Dtg& history);
  double q(const std::string& kind_i, const std::string& kind_j, double distance_m) const;
  bool empty() const { return pairs_.empty(); }

  struct Counts {
    std::vector<long> cancelled, trials;  ///< per 1 m bin
    long cancelled_total = 0, trials_total = 0;
  };

 private:
  std::map<std::pair<std::string, std::string>, Counts> pairs_;
};

/// One observed (i done → j running) pair of a run: the unit q is learned from and scored on.
struct CancellationPair {
  int i = 0, j = 0;        ///< task node indices
  double distance_m = 0;   ///< between their first locations (horizontal)
  bool cancelled = false;  ///< j was cancelled from i's node or from the sync node awaiting i
};
/// Every such pair of `g` (both tasks located; j created by i's end and not ended before it).
std::vector<CancellationPair> cancellation_pairs(const Dtg& g);

class Forecaster {
 public:
  virtual ~Forecaster() = default;
  virtual const char* name() const = 0;
  /// The requests expected next, from `current` (the DTG as it stands at `now_s`). Deterministic.
  virtual std::vector<ForecastRequest> forecast(const Dtg& current, double now_s) = 0;
  /// q(i→j) for two task nodes; 0 for a forecaster without a cancellation model.
  virtual double cancel_probability(const DtgNode& i, const DtgNode& j) const;
};

struct GmfSettings {
  int frontier = 32;        ///< newest running task nodes forecast from
  int max_depth = 10;       ///< deepest signature compared (WL iterations)
  int min_candidates = 10;  ///< stop deepening below this many candidates
  int top_k = 10;           ///< candidates kept after ranking by the rigid-fit residual
  /// Candidates ranked at most (a deterministic even spread of the matches beyond it): the
  /// ranking is the cost; above a few hundred equal matches more add nothing.
  int max_ranked = 256;
  double cluster_m = 2.0;  ///< forecast points within this are one request, m
  /// Matches whose neighbourhood fits f's worse than this RMS residual are dropped, m (ours: the
  /// paper ranks by "total distance" without a cut; a poor match only spreads the forecast).
  double max_residual_m = 2.0;
};

/// GMF over `histories` (finished runs' DTGs; the current run's own finished nodes are used too).
std::unique_ptr<Forecaster> gmf_forecaster(std::vector<Dtg> histories, GmfSettings settings = {});
/// Repeats each kind's last displacement between its two newest batches (tasks of a kind created
/// at the same instant), p = 1, when the newest batch is still running.
std::unique_ptr<Forecaster> constant_velocity_forecaster();
std::unique_ptr<Forecaster> no_forecaster();
/// gmf, constant-velocity or none; nullptr for another name.
std::unique_ptr<Forecaster> make_forecaster(const std::string& name, std::vector<Dtg> histories,
                                            const GmfSettings& gmf = {});

/// How good the forecasts of one held-out run were (docs/swath-fleet.md).
struct ForecastScore {
  /// Per task spawned after the first batch (located): horizontal distance from its first
  /// location to the nearest forecast of its kind with p ≥ p_min made when the batch before it
  /// appeared; infinity when there was none.
  std::vector<double> distances_m;
  double brier_sum = 0;  ///< Σ (q − cancelled)² over the run's cancellation pairs
  std::size_t cancellation_pairs = 0;
};
/// Replays `run` (a finished DTG) batch by batch through `forecaster`.
ForecastScore score_forecasts(Forecaster& forecaster, const Dtg& run, double p_min = 0.5);

}  // namespace swath::fleet
