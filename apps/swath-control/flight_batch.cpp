#include "flight_batch.hpp"

#include <algorithm>
#include <mutex>

#include "progress_bar.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/parallel.hpp"
#include "swath/control/experiment.hpp"

namespace swath::apps {

using base::fixed_text;

std::string paper_mission(const std::string& environment) {
  if (environment == "rugby") return "random:8@100x70";
  if (environment == "arch") return "random:8@170x170";
  return "random:8@20x20";
}

// Flies every run on `jobs` threads; results land at their own index, so the output does not
// depend on the number of threads.
void fly_all(std::vector<BatchFlight>& runs, unsigned jobs, bool progress) {
  std::size_t done = 0;
  std::mutex lock;
  ProgressBar bar(progress, "flying");
  base::parallel_for(runs.size(), jobs, [&](std::size_t i) {
    runs[i].summary = control::simulate(runs[i].settings, nullptr);
    const std::lock_guard<std::mutex> guard(lock);
    bar.update(static_cast<double>(++done) / static_cast<double>(runs.size()));
  });
}

std::string runs_csv(const std::vector<BatchFlight>& runs, const std::string& value_column) {
  std::string out =
      "environment,vehicle,mode," + (value_column.empty() ? "" : value_column + ",") +
      "seed,status,flight_time_s,attitude_rms_deg,"
      "attitude_estimated_rms_deg,cross_track_rms_m,executions_per_s,unchanged_fraction,"
      "cpu_utilisation,cpu_j,motors_j,total_j,mean_power_w,final_soc,roll_rms_deg,roll_max_deg,"
      "pitch_rms_deg,pitch_max_deg,yaw_rms_deg,yaw_max_deg,roll_disturbance_rms_deg,"
      "roll_disturbance_max_deg,pitch_disturbance_rms_deg,pitch_disturbance_max_deg,"
      "yaw_disturbance_rms_deg,yaw_disturbance_max_deg,disturbance_share\n";
  for (const BatchFlight& r : runs) {
    const control::FlightFigures f = control::figures_of(r.summary);
    const control::SimulationSummary& s = r.summary;
    out += r.environment + ',' + r.vehicle + ',' + r.mode + ',' +
           (value_column.empty() ? "" : r.value + ',') + std::to_string(r.seed) + ',' +
           control::to_string(s.status) + ',' + fixed_text(f.flight_time_s, 3) + ',' +
           fixed_text(f.attitude_rms_deg, 4) + ',' + fixed_text(f.attitude_estimated_rms_deg, 4) +
           ',' + fixed_text(f.cross_track_rms_m, 4) + ',' + fixed_text(f.executions_per_s, 2) +
           ',' + fixed_text(f.unchanged_fraction, 6) + ',' + fixed_text(s.cpu_utilisation, 6) +
           ',' + fixed_text(s.cpu_j, 3) + ',' + fixed_text(s.motors_j, 1) + ',' +
           fixed_text(s.total_j, 1) + ',' + fixed_text(s.mean_power_w, 3) + ',' +
           fixed_text(s.final_soc, 6);
    for (const auto& axes : {f.axis_error_deg, f.axis_disturbance_error_deg})
      for (const control::ErrorStat& e : axes)
        out += ',' + fixed_text(e.rms, 4) + ',' + fixed_text(e.max, 4);
    out += ',' + fixed_text(f.disturbance_share, 4) + '\n';
  }
  return out;
}

}  // namespace swath::apps
