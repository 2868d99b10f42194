#pragma once
// The multirotor of docs/swath-control.md: a 6-DoF rigid body carried by n <= 8 rotors whose speeds
// are state (first-order motors), with rotor and body drag, blade flapping and torque noise;
// brushless motors with their electrical power; ESCs that quantise PWM and latch it at their frame
// rate. Frames: world ENU (x east, y north, z up), body FLU (x forward, y left, z up). Integration:
// classical RK4 (Boost.Odeint) in equal sub-steps with the inputs held over each.

#include <array>
#include <string>
#include <vector>

#include "swath/vehicle/clock.hpp"
#include "swath/vehicle/vec3.hpp"

namespace swath::vehicle {

inline constexpr double kStandardGravity_m_s2 = 9.80665;
inline constexpr std::size_t kMaxRotors = 8;

/// One rotor: where it sits and which way it turns.
struct Rotor {
  Vec3 position_m;          ///< body FLU, from the centre of mass
  int spin = +1;            ///< +1 counter-clockwise seen from above, -1 clockwise
  double efficiency = 1.0;  ///< thrust factor η in (0, 1]: < 1 for a coaxial pair's lower rotor
};

enum class RotorLayout { quad_x, hexa_x, y6 };

/// The rotors of a standard layout. quad_x and hexa_x: arms every 90° / 60° starting 45° / 30°
/// left of forward, spins alternating from `first_spin` (so diagonal pairs turn alike). y6: arms at
/// 60°, 180° and 300°, each with an upper rotor of `first_spin` 0.05 m above and a lower rotor of
/// the other spin 0.05 m below, of thrust efficiency `coaxial_lower_efficiency`. `arm_m` > 0.
std::vector<Rotor> rotor_layout(RotorLayout layout, double arm_m, int first_spin = +1,
                                double coaxial_lower_efficiency = 0.8);

/// Propellers, motors and ESC power (defaults: a 2212-920 motor with a 10" propeller).
struct Propulsion {
  double thrust_coeff_n_s2 = 8.0e-6;    ///< k_T: T = η k_T Ω², N/(rad/s)²
  double torque_coeff_nm_s2 = 1.28e-7;  ///< k_Q: drag torque k_Q Ω², N m/(rad/s)²
  double max_speed_rad_s = 1000.0;      ///< Ω_max
  double time_constant_s = 0.03;        ///< τ_m of Ω̇ = (Ω_cmd − Ω) / τ_m, > 0
  double rotor_inertia_kg_m2 = 3.0e-5;  ///< J_r, propeller and bell
  double kv_rpm_per_v = 920.0;          ///< K_v; K_t = K_e = 60 / (2π K_v)
  double resistance_ohm = 0.10;         ///< R_m, winding
  double no_load_current_a = 0.4;       ///< I_0
  double esc_efficiency = 0.95;         ///< η_esc in (0, 1]
  /// Translational lift (rotor_drag_torque_nm): the rotor's shaft power follows momentum theory
  /// in the airflow, so cruise costs less than hover. Off: the drag torque is k_Q Ω² always.
  bool translational_lift = false;
  double diameter_m = 0.254;           ///< D, the propeller's disk (A = π D² / 4), m, > 0
  double induced_power_factor = 1.15;  ///< κ: induced power κ T (v_i + u_z), ≥ 1
  /// K_t = K_e, N m/A = V s/rad.
  double motor_constant() const;
};

/// The body: mass, inertia and the drag (docs/swath-control.md, 'The simulated multirotor').
struct Frame {
  double mass_kg = 1.5;
  Vec3 inertia_kg_m2{0.015, 0.015, 0.027};       ///< principal, body FLU
  Vec3 drag_linear_n_per_m_s{0.25, 0.25, 0.10};  ///< D, rotor drag per body axis
  Vec3 drag_cda_m2{0.02, 0.02, 0.04};            ///< CdA, quadratic body drag per body axis
  double air_density_kg_m3 = 1.225;              ///< ρ
  double flapping_nm_per_m_s = 0.01;             ///< k_f of M_f = −k_f (e3 × v_r)
  /// M_n: Gauss–Markov torque noise (vibration, imbalance) per body axis; drawn by the
  /// simulation and given to integrate() as an input.
  double torque_noise_sigma_nm = 0.002;
  double torque_noise_time_constant_s = 0.05;
};

struct Airframe {
  std::string name = "quad-f450";
  Frame frame;
  std::vector<Rotor> rotors = rotor_layout(RotorLayout::quad_x, 0.225);
  Propulsion propulsion;
};

/// The state (docs/swath-control.md, 'The simulated multirotor'): position and velocity (world
/// ENU), attitude (body to world), body rates (body FLU) and the rotor speeds (the first
/// rotors.size() are used).
struct MultirotorState {
  Vec3 position_m, velocity_m_s;
  Quat attitude;
  Vec3 rate_rad_s;
  std::array<double, kMaxRotors> rotor_rad_s{};
};

/// What acts on the body from outside, held constant over an integration step.
struct MultirotorInputs {
  std::array<double, kMaxRotors> command_rad_s{};  ///< Ω_cmd, clamped to [0, Ω_max]
  Vec3 wind_m_s;                                   ///< air velocity, world ENU
  Vec3 torque_noise_nm;                            ///< M_n, body FLU
  /// Each rotor's drag torque over k_Q Ω² (drag_torque_factors: translational lift), held like
  /// the wind (FlightModel refreshes it at every wind update): the airflow changes little in a
  /// few milliseconds, and solving Glauert's equation in every RK4 stage would cost more than
  /// the rest of the plant.
  std::array<double, kMaxRotors> drag_torque_factor{1, 1, 1, 1, 1, 1, 1, 1};
};
static_assert(kMaxRotors == 8, "drag_torque_factor's initialiser lists every rotor");

/// The forces and moments on the body in a state, and the rotor accelerations.
struct Wrench {
  Vec3 force_world_n;   ///< thrust and drag, world ENU (gravity not included)
  Vec3 torque_body_nm;  ///< every moment of the model (see `Frame`), body FLU
  std::array<double, kMaxRotors> rotor_accel_rad_s2{};
  std::array<double, kMaxRotors> rotor_drag_torque_nm{};  ///< each rotor's aerodynamic torque
};
Wrench applied_wrench(const Airframe& airframe, const MultirotorState& state,
                      const MultirotorInputs& inputs);
/// applied_wrench's force_world_n alone (the same arithmetic, so the same bits): what the
/// accelerometer's truth needs, without the moments.
Vec3 applied_force_world_n(const Airframe& airframe, const MultirotorState& state,
                           const MultirotorInputs& inputs);
/// The motors' electrical power in a state, W: motor_power_at_torque_w of applied_wrench's rotor
/// accelerations and drag torques (the same arithmetic), without the body's forces.
double motors_power_w(const Airframe& airframe, const MultirotorState& state,
                      const MultirotorInputs& inputs);

/// Advances the state by `duration_s` (>= 0) in equal RK4 sub-steps of at most `max_step_s`
/// (> 0); the attitude is renormalised after each sub-step.
MultirotorState integrate(const Airframe& airframe, MultirotorState state,
                          const MultirotorInputs& inputs, double duration_s, double max_step_s);

/// Glauert's induced velocity v_i, m/s: the positive root of v = v_h² / √(u_xy² + (v + u_z)²),
/// v_h the hover induced velocity, u_xy the airspeed in the disk plane, u_z the airspeed into the
/// disk along the thrust axis (climb or a forward-tilted disk in cruise positive). u_z is held
/// at −v_h and above (momentum theory has no solution in the vortex-ring state below).
double induced_velocity_m_s(double hover_induced_m_s, double edgewise_m_s, double axial_m_s);

/// One rotor's aerodynamic drag torque, N m, at speed Ω with the air moving past it at
/// `air_body_m_s` (the body's velocity relative to the air, body FLU; z along the thrust).
/// Without translational lift: k_Q Ω². With it, the shaft power k_Q Ω³ measured in hover is
/// split into profile power k_Q Ω³ − κ T v_h (held) and induced power κ T (v_i + u_z), which
/// momentum theory scales with the airflow: Q = k_Q Ω² + κ T (v_i + u_z − v_h) / Ω, ≥ 0,
/// T = η k_T Ω², v_h = √(T / 2ρA).
double rotor_drag_torque_nm(const Propulsion& propulsion, double efficiency,
                            double air_density_kg_m3, double speed_rad_s, const Vec3& air_body_m_s);

/// rotor_drag_torque_nm over k_Q Ω²: 1 without translational lift or at rest.
double drag_torque_factor(const Propulsion& propulsion, double efficiency, double air_density_kg_m3,
                          double speed_rad_s, const Vec3& air_body_m_s);
/// drag_torque_factor of every rotor in a state with the wind `wind_m_s` (world ENU).
std::array<double, kMaxRotors> drag_torque_factors(const Airframe& airframe,
                                                   const MultirotorState& state,
                                                   const Vec3& wind_m_s);

/// The share of a rotor's hover shaft power that is induced, κ T v_h / (k_Q Ω³) = κ η^1.5
/// k_T^1.5 / (k_Q √(2ρA)) (κ times the figure of merit; the same at every Ω).
double induced_power_share(const Propulsion& propulsion, double efficiency,
                           double air_density_kg_m3);

/// A motor's current for an aerodynamic torque `drag_torque_nm`, A:
/// (Q + J_r Ω̇) / K_t + I_0.
double motor_current_at_torque_a(const Propulsion& propulsion, double drag_torque_nm,
                                 double accel_rad_s2);
/// Its electrical input power, W: (R I + K_e Ω) I / η_esc, never negative.
double motor_power_at_torque_w(const Propulsion& propulsion, double speed_rad_s,
                               double drag_torque_nm, double accel_rad_s2);

/// One motor's electrical input from the ESC's supply, W: (R I + K_e Ω) I / η_esc with
/// I = (k_Q Ω² + J_r Ω̇) / K_t + I_0, never negative (ESCs do not regenerate here).
double motor_power_w(const Propulsion& propulsion, double speed_rad_s, double accel_rad_s2);
/// The current of that motor, A.
double motor_current_a(const Propulsion& propulsion, double speed_rad_s, double accel_rad_s2);

/// Hover in still air, in closed form: every rotor at the speed whose thrusts carry m g.
struct Hover {
  std::array<double, kMaxRotors> rotor_rad_s{};
  double motor_power_w = 0.0;  ///< all motors, W
};
Hover hover(const Airframe& airframe);

/// The ESC of one motor: PWM quantised to `resolution_us`, latched at the next frame of
/// `frame_rate_hz` (0: at once), mapped to Ω_cmd = Ω_max √u (thrust linear in u) or Ω_max u.
struct EscSettings {
  double pwm_min_us = 1000, pwm_max_us = 2000, resolution_us = 1;
  double frame_rate_hz = 490;  ///< ArduCopter's default; 0 applies every command at once
  bool thrust_linear = true;
};

class Esc {
 public:
  Esc(const EscSettings& settings, double max_speed_rad_s);
  /// A new PWM command at `now` (applied at the next frame).
  void command(double pwm_us, SimTime now);
  /// Ω_cmd the motor follows at `now`.
  double speed_command_rad_s(SimTime now);
  /// PWM as the ESC resolves it.
  double quantised_us(double pwm_us) const;
  /// The first frame at or after `t`: frames fall on whole multiples of the frame period.
  SimTime next_frame(SimTime t) const;

 private:
  EscSettings settings_;
  double max_speed_rad_s_;
  SimTime period_ns_ = 0;
  double applied_us_, pending_us_;
  SimTime pending_at_ = 0;
  bool has_pending_ = false;
};

/// Mechanical energy of the body, J: ½ m |v|² + m g z + ½ ωᵀ J ω (rotors excluded).
double body_energy_j(const Airframe& airframe, const MultirotorState& state);
/// Angular momentum of the body in world ENU, N m s (rotors excluded).
Vec3 body_angular_momentum_world(const Airframe& airframe, const MultirotorState& state);

}  // namespace swath::vehicle
