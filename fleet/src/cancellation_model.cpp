// q(i→j): how likely finishing task i cancels task j (docs/swath-fleet.md).

#include <algorithm>
#include <cmath>

#include "dtg_index.hpp"
#include "swath/fleet/forecaster.hpp"

namespace swath::fleet {

namespace {

using detail::at;
// Bins beyond this are one bin: 10 km of 1 m bins is more than any fenced field.
constexpr double kMaxBinM = 10'000;

std::size_t bin_of(double distance_m) {
  return static_cast<std::size_t>(std::clamp(distance_m, 0.0, kMaxBinM));
}

}  // namespace

std::vector<CancellationPair> cancellation_pairs(const Dtg& g) {
  const detail::DtgIndex ix(g);
  std::vector<int> tasks;
  for (std::size_t n = 0; n < g.nodes.size(); ++n)
    if (g.nodes[n].type == DtgNodeType::task && g.nodes[n].first_loc_m)
      tasks.push_back(static_cast<int>(n));
  std::vector<CancellationPair> out;
  std::vector<char> by_i(g.nodes.size(), 0);
  for (int i : tasks) {
    const DtgNode& a = g.nodes[at(i)];
    if (a.status != DtgStatus::done) continue;
    // Cancels issued from i's node or from a sync node awaiting i.
    std::vector<int> sources = ix.awaited_by[at(i)];
    sources.push_back(i);
    for (int s : sources)
      for (int c : ix.cancelled[at(s)]) by_i[at(c)] = 1;
    for (int j : tasks) {
      const DtgNode& b = g.nodes[at(j)];
      if (j == i || !(b.created_s <= a.ended_s) || !(b.ended_s >= a.ended_s)) continue;
      out.push_back(
          {i, j, vehicle::horizontal_distance(*a.first_loc_m, *b.first_loc_m), by_i[at(j)] != 0});
    }
    for (int s : sources)
      for (int c : ix.cancelled[at(s)]) by_i[at(c)] = 0;
  }
  return out;
}

void CancellationModel::learn(const Dtg& history) {
  for (const CancellationPair& p : cancellation_pairs(history)) {
    Counts& c = pairs_[{history.nodes[at(p.i)].kind, history.nodes[at(p.j)].kind}];
    const std::size_t b = bin_of(p.distance_m);
    if (c.trials.size() <= b) c.trials.resize(b + 1, 0), c.cancelled.resize(b + 1, 0);
    ++c.trials[b];
    ++c.trials_total;
    if (p.cancelled) ++c.cancelled[b], ++c.cancelled_total;
  }
}

double CancellationModel::q(const std::string& kind_i, const std::string& kind_j,
                            double distance_m) const {
  const auto it = pairs_.find({kind_i, kind_j});
  if (it == pairs_.end()) return 0;
  const Counts& c = it->second;
  const double rate =
      (static_cast<double>(c.cancelled_total) + 1.0) / (static_cast<double>(c.trials_total) + 2.0);
  const std::size_t b = bin_of(distance_m);
  if (b >= c.trials.size()) return rate;
  return (static_cast<double>(c.cancelled[b]) + rate) / (static_cast<double>(c.trials[b]) + 1.0);
}

double Forecaster::cancel_probability(const DtgNode&, const DtgNode&) const {
  return 0;
}

}  // namespace swath::fleet
