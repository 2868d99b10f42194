// Forecasts and speculation (docs/swath-fleet.md).

#include <chrono>

#include "runtime/runtime_impl.hpp"

namespace swath::fleet::rt {

// Forecasts again when the DTG changed; a `forecast` event when they differ.
void Runtime::update_forecasts() {
  if (!forecaster_ || !dtg_changed_) return;
  dtg_changed_ = false;
  const auto clock0 = std::chrono::steady_clock::now();
  live_ = live_dtg();
  std::vector<ForecastRequest> next = forecaster_->forecast(live_, now_);
  record_.forecast_s_total +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock0).count();
  ++record_.forecasts;
  auto same = [](const std::vector<ForecastRequest>& a, const std::vector<ForecastRequest>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const auto& x, const auto& y) {
      return x.kind == y.kind && x.p == y.p && x.location_m.x == y.location_m.x &&
             x.location_m.y == y.location_m.y;
    });
  };
  const bool changed = !same(next, forecasts_);
  forecasts_ = std::move(next);  // kept even when only the expected times moved
  if (!changed) return;
  json list = json::array();
  for (const ForecastRequest& f : forecasts_)
    list.push_back(at_json(json{{"kind", f.kind}}, f.location_m,
                           json{{"p", round6(f.p)}, {"expected_s", round6(f.expected_s)}}));
  log(json{{"ev", "forecast"}, {"forecasts", list}});
}

// The forecasts inside the fence and not already shown by a visible request, and q between the
// visible requests (avoid-mutual: docs/swath-fleet.md, 'Speculation and avoid-mutual'; pairs below
// 0.01 left out, as the scheduler's neighbour lists).
void Runtime::add_forecasts(Snapshot& s, const std::vector<int>& req_task) const {
  if (!forecaster_) return;
  for (const ForecastRequest& f : forecasts_)
    if (f.p > 0 && settings_.envelope.refusal_xy(f.location_m.x, f.location_m.y).empty() &&
        std::none_of(s.requests.begin(), s.requests.end(), [&](const Request& r) {
          return vehicle::horizontal_distance(r.location_m, f.location_m) <= settings_.hit_within_m;
        })) {
      ForecastRequest g = f;
      g.location_m.z = 0;  // each drone flies at its layer
      s.forecasts.push_back(g);
    }
  for (std::size_t i = 0; i < req_task.size(); ++i)
    for (std::size_t j = 0; j < req_task.size(); ++j) {
      if (i == j) continue;
      const auto ti = static_cast<std::size_t>(req_task[i]),
                 tj = static_cast<std::size_t>(req_task[j]);
      if (ti >= live_.nodes.size() || tj >= live_.nodes.size()) continue;
      const double q = forecaster_->cancel_probability(live_.nodes[ti], live_.nodes[tj]);
      if (q > 0.01) s.mutual.push_back({static_cast<int>(i), static_cast<int>(j), q});
    }
}

// Speculation positions a drone only (docs/swath-fleet.md, 'Speculation and avoid-mutual'): it
// flies to the forecast place at its layer and waits there; it serves what appears only when the
// scheduler gives it that request.
void Runtime::position(Drone& d, const ForecastRequest& f) {
  leave_spot(d);
  d.spot = f.location_m;
  d.spot_hit = false;
  ++record_.speculative_positions;
  Vec3 to = f.location_m;
  to.z = d.layer_m;
  log(at_json(json{{"ev", "position"}, {"drone", d.index}}, to,
              json{{"kind", f.kind}, {"p", round6(f.p)}}));
  start_leg(d, to, Mode::positioning, now_);
}

// The drone leaves its forecast place (another target, home, the run's end): a miss unless a
// request appeared there.
void Runtime::leave_spot(Drone& d) {
  if (!d.spot) return;
  if (!d.spot_hit) ++record_.speculative_misses;
  d.spot.reset();
  d.spot_hit = false;
}

// A request appeared: a hit for each drone sent to within hit_within_m of it.
void Runtime::note_hits(const Vec3& request_at, int task) {
  for (Drone& d : drones_)
    if (d.spot && !d.spot_hit &&
        vehicle::horizontal_distance(*d.spot, request_at) <= settings_.hit_within_m) {
      d.spot_hit = true;
      ++record_.speculative_hits;
      log(json{{"ev", "speculation_hit"}, {"drone", d.index}, {"task", task}});
    }
}

}  // namespace swath::fleet::rt
