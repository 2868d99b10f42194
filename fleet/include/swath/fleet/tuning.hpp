#pragma once
// Tuning the scheduler's weights by replay (docs/swath-fleet.md): the search itself — the trials'
// weights, successive halving over the tuning seeds, the files it writes — apart from how a
// trial is run (swath-fleet tune runs the app again, or a trace of it; tune ask / tell hands the
// runs to an engine: docs/swath-fleet.md, 'Trace replay') and from the command line.

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "swath/fleet/scheduler.hpp"

namespace swath::fleet {

/// A weight a trial may change, with its key in a weights file. Coverage stays (it keeps "serve
/// what is visible" above the rest) and closest is fixed at 1 (the argmax ignores scale).
struct FreeWeight {
  const char* name;
  double Weights::*member;
};
/// fairness, avoid_zigzag, commitment, speculative, avoid_mutual.
const std::array<FreeWeight, 5>& free_weights();

/// `count` (≥ 2) weight sets: `start`, reactive's (start without the forecast terms), then
/// draws from `seed`'s "tune" stream: each free weight 0 with probability 1/5, else log-uniform
/// in [1e-3, 1e3] to 4 significant digits (so a weights file holds exactly what was scored).
std::vector<Weights> draw_trials(const Weights& start, int count, std::uint64_t seed);

/// A weights file: the comment line, coverage and the free weights (shortest round-trip text).
std::string weights_yaml(const Weights& w, const std::string& comment);

/// One trial: its weights and its completion times, one per tuning seed it ran, in order.
struct Trial {
  Weights weights;
  std::vector<double> times_s;
  double mean_s() const;
};

/// The halving's order: the lower mean time first, ties to the lower trial index.
bool better_trial(const std::vector<Trial>& trials, std::size_t a, std::size_t b);
/// The better half (rounded up) of the trials `alive` (indices), best first.
std::vector<std::size_t> better_half(const std::vector<Trial>& trials,
                                     std::vector<std::size_t> alive);
/// The best of `alive` (non-empty).
std::size_t best_trial(const std::vector<Trial>& trials, const std::vector<std::size_t>& alive);

/// Successive halving over `rungs` tuning seeds: every trial runs rung 0, the better half rung 1,
/// and so on; `time_s(trial, rung)` is a trial's completion time on a rung's seed (a run that
/// does not complete: twice the time limit). Returns the winner: the best of the last rung.
std::size_t successive_halving(std::vector<Trial>& trials, int rungs,
                               const std::function<double(std::size_t, int)>& time_s);

/// tune.csv: one row per trial (its weights, how many tuning seeds it ran, its mean time).
std::string tune_csv(const std::vector<Trial>& trials);

}  // namespace swath::fleet
