// The forecasters GMF is measured against (docs/swath-fleet.md): none, and constant velocity — each
// kind's newest batch of tasks moved on by the displacement between its two newest batches.

#include <algorithm>
#include <cmath>
#include <map>

#include "swath/fleet/forecaster.hpp"

namespace swath::fleet {

namespace {

using vehicle::Vec3;

class NoForecaster final : public Forecaster {
 public:
  const char* name() const override { return "none"; }
  std::vector<ForecastRequest> forecast(const Dtg&, double) override { return {}; }
};

class ConstantVelocity final : public Forecaster {
 public:
  const char* name() const override { return "constant-velocity"; }

  std::vector<ForecastRequest> forecast(const Dtg& g, double now_s) override {
    // kind → creation time → the located task nodes created then (a batch).
    std::map<std::string, std::map<double, std::vector<const DtgNode*>>> batches;
    for (const DtgNode& n : g.nodes)
      if (n.type == DtgNodeType::task && n.first_loc_m && n.created_s <= now_s)
        batches[n.kind][n.created_s].push_back(&n);
    std::vector<ForecastRequest> out;
    for (const auto& [kind, by_time] : batches) {
      if (by_time.size() < 2) continue;
      const auto last = std::prev(by_time.end());
      const auto before = std::prev(last);
      const bool running = std::any_of(last->second.begin(), last->second.end(),
                                       [](auto* n) { return n->status == DtgStatus::running; });
      if (!running) continue;  // its successors would be here already
      const Vec3 shift = centre(last->second) - centre(before->second);
      const double period_s = last->first - before->first;
      for (const DtgNode* n : last->second)
        out.push_back(
            {kind, *n->first_loc_m + shift, 1.0, std::max(now_s, n->created_s + period_s)});
    }
    return out;
  }

 private:
  static Vec3 centre(const std::vector<const DtgNode*>& batch) {
    Vec3 sum{0, 0, 0};
    for (const DtgNode* n : batch) sum += *n->first_loc_m;
    return sum * (1.0 / static_cast<double>(batch.size()));
  }
};

}  // namespace

std::unique_ptr<Forecaster> constant_velocity_forecaster() {
  return std::make_unique<ConstantVelocity>();
}

std::unique_ptr<Forecaster> no_forecaster() {
  return std::make_unique<NoForecaster>();
}

std::unique_ptr<Forecaster> make_forecaster(const std::string& name, std::vector<Dtg> histories,
                                            const GmfSettings& gmf) {
  if (name == "gmf") return gmf_forecaster(std::move(histories), gmf);
  if (name == "constant-velocity") return constant_velocity_forecaster();
  if (name == "none") return no_forecaster();
  return nullptr;
}

ForecastScore score_forecasts(Forecaster& forecaster, const Dtg& run, double p_min) {
  ForecastScore score;
  std::map<double, std::vector<const DtgNode*>> moments;  // located tasks by creation time
  for (const DtgNode& n : run.nodes)
    if (n.type == DtgNodeType::task && n.first_loc_m) moments[n.created_s].push_back(&n);
  for (auto it = moments.begin(); it != moments.end() && std::next(it) != moments.end(); ++it) {
    const double t_s = it->first;
    const std::vector<ForecastRequest> f = forecaster.forecast(run.as_of(t_s), t_s);
    for (const DtgNode* n : std::next(it)->second) {
      double best = std::numeric_limits<double>::infinity();
      for (const ForecastRequest& r : f)
        if (r.kind == n->kind && r.p >= p_min)
          best = std::min(best, vehicle::horizontal_distance(r.location_m, *n->first_loc_m));
      score.distances_m.push_back(best);
    }
  }
  for (const CancellationPair& p : cancellation_pairs(run)) {
    const double q = forecaster.cancel_probability(run.nodes[static_cast<std::size_t>(p.i)],
                                                   run.nodes[static_cast<std::size_t>(p.j)]);
    score.brier_sum += (q - (p.cancelled ? 1.0 : 0.0)) * (q - (p.cancelled ? 1.0 : 0.0));
    ++score.cancellation_pairs;
  }
  return score;
}

}  // namespace swath::fleet
