#include "swath/fleet/tuning.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "swath/base/number_text.hpp"
#include "swath/vehicle/random.hpp"

namespace swath::fleet {

const std::array<FreeWeight, 5>& free_weights() {
  static const std::array<FreeWeight, 5> free{{{"fairness", &Weights::fairness},
                                               {"avoid_zigzag", &Weights::avoid_zigzag},
                                               {"commitment", &Weights::commitment},
                                               {"speculative", &Weights::speculative},
                                               {"avoid_mutual", &Weights::avoid_mutual}}};
  return free;
}

namespace {

// 0 with probability 1/5, else log-uniform in [1e-3, 1e3], kept to 4 significant digits so that
// weights.yaml holds exactly the weights that were scored.
double draw_weight(vehicle::SplitMix64& rng) {
  if (rng.uniform() < 0.2) return 0.0;
  const double v = std::pow(10.0, rng.uniform(-3.0, 3.0));
  // Rounded through its text: 43.41, not 43.410000000000004.
  const int decimals = std::max(0, 3 - static_cast<int>(std::floor(std::log10(v))));
  double rounded = 0;
  base::parse_number(base::fixed_text(v, decimals), rounded);
  return std::min(1000.0, rounded);
}

}  // namespace

std::vector<Weights> draw_trials(const Weights& start, int count, std::uint64_t seed) {
  std::vector<Weights> out{start};
  Weights reactive = start;  // the paper's baseline weights: no forecast terms
  reactive.speculative = reactive.avoid_mutual = 0;
  out.push_back(reactive);
  auto rng = vehicle::SplitMix64::stream(seed, "tune");
  while (static_cast<int>(out.size()) < count) {
    Weights w = start;
    for (const FreeWeight& f : free_weights()) w.*f.member = draw_weight(rng);
    out.push_back(w);
  }
  return out;
}

std::string weights_yaml(const Weights& w, const std::string& comment) {
  std::ostringstream out;
  out << "# " << comment << "\n";
  out << "coverage: " << base::shortest_text(w.coverage) << "\n";
  for (const FreeWeight& f : free_weights())
    out << f.name << ": " << base::shortest_text(w.*f.member) << "\n";
  return out.str();
}

double Trial::mean_s() const {
  double sum = 0;
  for (double t : times_s) sum += t;
  return sum / static_cast<double>(times_s.size());
}

bool better_trial(const std::vector<Trial>& trials, std::size_t a, std::size_t b) {
  const double ma = trials[a].mean_s(), mb = trials[b].mean_s();
  return ma != mb ? ma < mb : a < b;
}

std::vector<std::size_t> better_half(const std::vector<Trial>& trials,
                                     std::vector<std::size_t> alive) {
  std::sort(alive.begin(), alive.end(),
            [&](std::size_t a, std::size_t b) { return better_trial(trials, a, b); });
  alive.resize((alive.size() + 1) / 2);
  return alive;
}

std::size_t best_trial(const std::vector<Trial>& trials, const std::vector<std::size_t>& alive) {
  return *std::min_element(alive.begin(), alive.end(), [&](std::size_t a, std::size_t b) {
    return better_trial(trials, a, b);
  });
}

std::size_t successive_halving(std::vector<Trial>& trials, int rungs,
                               const std::function<double(std::size_t, int)>& time_s) {
  std::vector<std::size_t> alive(trials.size());
  for (std::size_t i = 0; i < alive.size(); ++i) alive[i] = i;
  for (int k = 0; k < rungs; ++k) {
    if (k > 0) alive = better_half(trials, std::move(alive));
    for (std::size_t i : alive) trials[i].times_s.push_back(time_s(i, k));
  }
  return best_trial(trials, alive);
}

std::string tune_csv(const std::vector<Trial>& trials) {
  std::string csv = "trial,coverage";
  for (const FreeWeight& f : free_weights()) csv += std::string(",") + f.name;
  csv += ",tuning_seeds,mean_completion_time_s\n";
  for (std::size_t i = 0; i < trials.size(); ++i) {
    csv += std::to_string(i) + "," + base::shortest_text(trials[i].weights.coverage);
    for (const FreeWeight& f : free_weights())
      csv += "," + base::shortest_text(trials[i].weights.*f.member);
    csv += "," + std::to_string(trials[i].times_s.size()) + "," +
           base::fixed_text(trials[i].mean_s(), 3) + "\n";
  }
  return csv;
}

}  // namespace swath::fleet
