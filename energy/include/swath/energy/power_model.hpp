#pragma once
// The "measured" power of the flight simulation: mechanical flight power, on-board computation
// power g(c) from profiled points (paper 004 §II-C), payload, and fixed-seed noise.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "swath/vehicle/random.hpp"

namespace swath::energy {

/// Level-flight and turning power of the airframe. Not a physics truth: a smooth, plausible model
/// whose shape (speed, banking, wind through airspeed) the estimator has to learn.
struct MechanicalPower {
  double cruise_w = 150.0;            ///< level flight at the reference airspeed, W (> 0)
  double cruise_airspeed_m_s = 12.0;  ///< the reference airspeed, m/s (> 0)
  double parasitic_share = 0.4;       ///< share of cruise power that grows with airspeed^3, [0, 1]
  double max_bank_deg = 35.0;         ///< bank limit (so turn-rate limit), degrees in (0, 80]
};

/// Level-flight power at `airspeed_m_s` (>= 0): cruise_w * ((1 - s) + s * (v / v_ref)^3), W.
double level_flight_power_w(const MechanicalPower& m, double airspeed_m_s);

/// Power while the ground track curves with lateral acceleration `lateral_accel_m_s2`: a
/// coordinated turn needs load factor n = sqrt(1 + (a/g)^2) and power grows as n^1.5, W.
double mechanical_power_w(const MechanicalPower& m, double airspeed_m_s, double lateral_accel_m_s2);

/// Power of one on-board computation against its parameter (paper 004 g(c)), piecewise linear
/// through profiled points (c, W) sorted by c, extended linearly beyond the end points, and 0 for
/// c == 0 (the computation switched off: g(∅) = 0). Never negative.
struct PowerCurve {
  std::string name;                               ///< e.g. "detection (fps)"
  std::vector<std::pair<double, double>> points;  ///< (parameter, W), >= 1 point, increasing c
};

double computation_power_w(const PowerCurve& curve, double parameter);

/// Everything that draws power, for the simulation and for mission budgets.
struct PowerProfile {
  MechanicalPower mechanical;
  double payload_w = 0.0;                ///< camera, radio, avionics: always on, W (>= 0)
  double climb_w = 0.0;                  ///< power while climbing (budget), W; 0: 1.3 x cruise
  double descent_w = 0.0;                ///< power while descending (budget), W; 0: 0.8 x cruise
  std::vector<PowerCurve> computations;  ///< one per computation parameter of the plan
  double noise_w = 0.0;                  ///< standard deviation of the measurement noise, W
  std::uint64_t seed = 1;                ///< noise seed: same seed, same signal
};

/// Power while climbing and while descending, without the payload, W: climb_w and descent_w, or
/// when not given 1.3 and 0.8 x the cruise power (defined here only: swath-energy budget and
/// swath-fleet's drones use these).
inline constexpr double kClimbPowerFactor = 1.3;
inline constexpr double kDescentPowerFactor = 0.8;
double climbing_power_w(const PowerProfile& p);
double descending_power_w(const PowerProfile& p);

/// Sum of g_j(c_j) over the computations, W. `parameters.size()` must equal curves' count.
double computations_power_w(const std::vector<PowerCurve>& curves,
                            const std::vector<double>& parameters);

/// Gaussian noise from a fixed seed, the same numbers on every platform (vehicle::SplitMix64,
/// swath's one generator, + Box-Muller; std::normal_distribution is implementation-defined).
class GaussianNoise {
 public:
  GaussianNoise(std::uint64_t seed, double sigma) : bits_(seed), sigma_(sigma) {}
  double next();

 private:
  double uniform();
  vehicle::SplitMix64 bits_;
  double sigma_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace swath::energy
