// Mixer (docs/swath-control.md: mixer A A⁺ = I): the pseudo-inverse on the paper's
// airframes, the saturation order (yaw first, then the collective, roll and pitch last) and the
// quantised pulses.

#include <gtest/gtest.h>

#include <cmath>

#include "swath/control/mixer.hpp"
#include "swath/vehicle/random.hpp"

namespace swath::control {
namespace {

MixerRotors layout_of(vehicle::RotorLayout kind) {
  return standard_layout(kind, kind == vehicle::RotorLayout::hexa_x ? 0.275 : 0.225, true, 0.8);
}

// The wrench A f, computed from the rotor list itself rather than from the matrices under test.
Wrench wrench_of(const MixerRotors& l, const MixerOutput& out) {
  Wrench w;
  for (std::size_t i = 0; i < l.count; ++i) {
    const Rotor& r = l.rotors[i];
    const double thrust = r.efficiency * out.force_n[i];
    w.thrust_n += thrust;
    w.torque_nm += cross(r.position_m, Vec3{0, 0, thrust});
    w.torque_nm.z -=
        (r.ccw ? 1.0 : -1.0) * l.torque_coeff_nm_s2 / l.thrust_coeff_n_s2 * out.force_n[i];
  }
  return w;
}

TEST(Mixer, PseudoInverseIsARightInverseOnEveryFrame) {
  for (const vehicle::RotorLayout kind :
       {vehicle::RotorLayout::quad_x, vehicle::RotorLayout::hexa_x, vehicle::RotorLayout::y6}) {
    const MixerRotors l = layout_of(kind);
    const auto m = mixer_matrices(l);
    ASSERT_TRUE(m.has_value());
    for (std::size_t r = 0; r < 4; ++r)
      for (std::size_t c = 0; c < 4; ++c) {
        double s = 0;
        for (std::size_t i = 0; i < l.count; ++i)
          s += m->effectiveness[r][i] * m->pseudo_inverse[i][c];
        EXPECT_NEAR(s, r == c ? 1.0 : 0.0, 1e-12) << static_cast<int>(kind) << " " << r << c;
      }
  }
}

TEST(Mixer, HoverOfASymmetricQuadSharesTheWeightEqually) {
  const MixerRotors l = layout_of(vehicle::RotorLayout::quad_x);
  const auto m = mixer_matrices(l);
  const MixerOutput out = mix(l, *m, Wrench{1.5 * 9.80665, {}});
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(out.force_n[i], 1.5 * 9.80665 / 4, 1e-12);
  // The hover speed: √(m g / (4 k_T)) = 678.0 rad/s before quantisation.
  EXPECT_NEAR(std::sqrt(out.force_n[0] / l.thrust_coeff_n_s2), 678.0, 0.05);
  // The bundled hexa-f550: 2.4 kg on six rotors hovers at 700.2 rad/s.
  const MixerRotors hexa = layout_of(vehicle::RotorLayout::hexa_x);
  const MixerOutput h = mix(hexa, *mixer_matrices(hexa), Wrench{2.4 * 9.80665, {}});
  for (std::size_t i = 0; i < 6; ++i)
    EXPECT_NEAR(std::sqrt(h.force_n[i] / hexa.thrust_coeff_n_s2), 700.2, 0.05);
}

TEST(Mixer, RequestsWithinReachAreProducedExactly) {
  vehicle::SplitMix64 rng(7);
  for (const vehicle::RotorLayout kind :
       {vehicle::RotorLayout::quad_x, vehicle::RotorLayout::hexa_x, vehicle::RotorLayout::y6}) {
    const MixerRotors l = layout_of(kind);
    const auto m = mixer_matrices(l);
    for (int trial = 0; trial < 200; ++trial) {
      const Wrench want{rng.uniform(10, 20),
                        {rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), rng.uniform(-0.02, 0.02)}};
      const MixerOutput out = mix(l, *m, want);
      ASSERT_EQ(out.yaw_scale, 1.0);
      ASSERT_EQ(out.roll_pitch_scale, 1.0);
      const Wrench got = wrench_of(l, out);
      EXPECT_NEAR(got.thrust_n, want.thrust_n, 1e-9);
      EXPECT_NEAR(got.torque_nm.x, want.torque_nm.x, 1e-9);
      EXPECT_NEAR(got.torque_nm.y, want.torque_nm.y, 1e-9);
      EXPECT_NEAR(got.torque_nm.z, want.torque_nm.z, 1e-9);
    }
  }
}

// The largest share of (τx, τy) any collective can carry with every rotor force in [0, f_max]:
// a grid over share and collective, independent of the mixer's bisection.
double best_roll_pitch_scale(const MixerRotors& l, const MixerMatrices& m, double tx, double ty) {
  const double f_max = l.max_rotor_force_n();
  double best = 0;
  for (int ks = 0; ks <= 2000; ++ks) {
    const double k = ks / 2000.0;
    for (int ts = 0; ts <= 4000; ++ts) {
      const double t = ts / 4000.0 * f_max * static_cast<double>(l.count) / 0.8;
      bool ok = true;
      for (std::size_t i = 0; i < l.count && ok; ++i) {
        const double f = m.pseudo_inverse[i][0] * t +
                         k * (m.pseudo_inverse[i][1] * tx + m.pseudo_inverse[i][2] * ty);
        ok = f >= 0 && f <= f_max;
      }
      if (ok) {
        best = k;
        break;
      }
    }
  }
  return best;
}

TEST(Mixer, AtFullThrottleTheCollectiveGivesWayToRollAndPitch) {
  // A climb at 95 % of the rotors' thrust with a roll and pitch request that fits only below it:
  // attitude is kept in full (ArduPilot's and PX4's priority) and the collective reduced just
  // enough: the most loaded rotor sits at f_max.
  for (const vehicle::RotorLayout kind :
       {vehicle::RotorLayout::quad_x, vehicle::RotorLayout::hexa_x, vehicle::RotorLayout::y6}) {
    const MixerRotors l = layout_of(kind);
    const auto m = mixer_matrices(l);
    const double f_max = l.max_rotor_force_n();
    const double thrust = 0.95 * f_max * static_cast<double>(l.count);
    const Wrench request{thrust, {0.4, -0.3, 0.0}};
    const MixerOutput out = mix(l, *m, request);
    EXPECT_EQ(out.roll_pitch_scale, 1.0);
    EXPECT_TRUE(out.thrust_clipped);
    const Wrench got = wrench_of(l, out);
    EXPECT_NEAR(got.torque_nm.x, 0.4, 1e-9);
    EXPECT_NEAR(got.torque_nm.y, -0.3, 1e-9);
    EXPECT_LT(got.thrust_n, thrust);
    EXPECT_GT(got.thrust_n, 0.8 * thrust);
    double most = 0;
    for (std::size_t i = 0; i < l.count; ++i) most = std::max(most, out.force_n[i]);
    EXPECT_NEAR(most, f_max, 1e-9 * f_max);
    // The same at idle: a collective of 2 % is raised so that no rotor would need to push.
    const MixerOutput idle =
        mix(l, *m, Wrench{0.02 * f_max * static_cast<double>(l.count), {0.4, -0.3, 0.0}});
    EXPECT_EQ(idle.roll_pitch_scale, 1.0);
    EXPECT_NEAR(wrench_of(l, idle).torque_nm.x, 0.4, 1e-9);
  }
}

TEST(Mixer, YawIsGivenUpFirstThenRollAndPitch) {
  for (const vehicle::RotorLayout kind :
       {vehicle::RotorLayout::quad_x, vehicle::RotorLayout::hexa_x, vehicle::RotorLayout::y6}) {
    const MixerRotors l = layout_of(kind);
    const auto m = mixer_matrices(l);
    const double f_max = l.max_rotor_force_n();
    const double thrust = 0.5 * f_max * static_cast<double>(l.count) * 0.9;
    // Too much yaw alone: thrust and roll/pitch exact, yaw cut to where a rotor hits a bound.
    const Wrench yaw_heavy{thrust, {0.2, -0.1, 5.0}};
    const MixerOutput a = mix(l, *m, yaw_heavy);
    EXPECT_EQ(a.roll_pitch_scale, 1.0);
    EXPECT_GT(a.yaw_scale, 0.0);
    EXPECT_LT(a.yaw_scale, 1.0);
    const Wrench got_a = wrench_of(l, a);
    EXPECT_NEAR(got_a.thrust_n, thrust, 1e-9);
    EXPECT_NEAR(got_a.torque_nm.x, 0.2, 1e-9);
    EXPECT_NEAR(got_a.torque_nm.y, -0.1, 1e-9);
    EXPECT_NEAR(got_a.torque_nm.z, a.yaw_scale * 5.0, 1e-9);
    bool at_bound = false;  // the yaw kept is the most there is: some rotor sits on a bound
    for (std::size_t i = 0; i < l.count; ++i)
      at_bound = at_bound || a.force_n[i] < 1e-9 || a.force_n[i] > f_max - 1e-9;
    EXPECT_TRUE(at_bound);
    // Too much roll and pitch for any collective: roll and pitch are scaled together (their
    // ratio kept) to the most any collective allows, found here by brute force over collectives.
    const Wrench rp_heavy{thrust, {30.0, 20.0, 0.05}};
    const MixerOutput b = mix(l, *m, rp_heavy);
    EXPECT_GT(b.roll_pitch_scale, 0.0);
    EXPECT_LT(b.roll_pitch_scale, 1.0);
    const Wrench got_b = wrench_of(l, b);
    EXPECT_NEAR(got_b.torque_nm.x / got_b.torque_nm.y, 1.5, 1e-9);
    EXPECT_NEAR(got_b.torque_nm.x, b.roll_pitch_scale * 30.0, 1e-6);
    for (std::size_t i = 0; i < l.count; ++i) {
      EXPECT_GE(b.force_n[i], 0.0);
      EXPECT_LE(b.force_n[i], f_max);
    }
    EXPECT_NEAR(b.roll_pitch_scale, best_roll_pitch_scale(l, *m, 30.0, 20.0), 1e-3);
    // A collective beyond every rotor at full speed is clipped to it.
    const MixerOutput c = mix(l, *m, Wrench{1e4, {}});
    EXPECT_TRUE(c.thrust_clipped);
    EXPECT_FALSE(a.thrust_clipped);
  }
}

TEST(Mixer, PulsesAreQuantisedToTheNearestLevel) {
  MixerRotors l = layout_of(vehicle::RotorLayout::quad_x);
  l.resolution_us = 4.0;
  const auto m = mixer_matrices(l);
  vehicle::SplitMix64 rng(11);
  for (int trial = 0; trial < 500; ++trial) {
    const Wrench w{rng.uniform(0, 30), {rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), 0}};
    const MixerOutput out = mix(l, *m, w);
    for (std::size_t i = 0; i < l.count; ++i) {
      const double exact = l.pwm_min_us + 1000.0 * out.force_n[i] / l.max_rotor_force_n();
      const double level = (out.pwm_us[i] - l.pwm_min_us) / l.resolution_us;
      EXPECT_EQ(level, std::round(level));  // on the grid
      EXPECT_LE(std::abs(out.pwm_us[i] - exact), l.resolution_us / 2 + 1e-9);
      // The commanded speed is the one the quantised pulse asks for: Ω = Ω_max √u.
      const double u = (out.pwm_us[i] - 1000.0) / 1000.0;
      EXPECT_NEAR(out.speed_cmd_rad_s[i], 1000.0 * std::sqrt(u), 1e-9);
    }
  }
  EXPECT_EQ(quantise_pwm_us(l, 0.0), 1000.0);
  EXPECT_EQ(quantise_pwm_us(l, 1.0), 2000.0);
  EXPECT_EQ(quantise_pwm_us(l, 2.0), 2000.0);
  EXPECT_EQ(quantise_pwm_us(l, 0.0019), 1000.0);  // 1.9 µs rounds down to level 0
  EXPECT_EQ(quantise_pwm_us(l, 0.0021), 1004.0);  // 2.1 µs rounds up to level 1
  l.mapping = EscMapping::linear;                 // Ω = Ω_max u: the pulse is √(f / f_max)
  const MixerOutput lin = mix(l, *m, Wrench{4 * 0.25 * l.max_rotor_force_n(), {}});
  EXPECT_EQ(lin.pwm_us[0], 1500.0);
  EXPECT_NEAR(lin.speed_cmd_rad_s[0], 500.0, 1e-9);
}

TEST(Mixer, FramesThatCannotControlFourAxesAreRefused) {
  MixerRotors line = standard_layout(vehicle::RotorLayout::quad_x, 0.2);
  for (std::size_t i = 0; i < 4; ++i)
    line.rotors[i].position_m = {0.1 * static_cast<double>(i), 0, 0};
  EXPECT_FALSE(mixer_matrices(line).has_value());  // no roll authority
  MixerRotors same_spin = standard_layout(vehicle::RotorLayout::quad_x, 0.2);
  for (std::size_t i = 0; i < 4; ++i) same_spin.rotors[i].ccw = true;
  EXPECT_FALSE(mixer_matrices(same_spin).has_value());  // yaw column parallel to thrust
  MixerRotors three = standard_layout(vehicle::RotorLayout::quad_x, 0.2);
  three.count = 3;
  EXPECT_FALSE(mixer_matrices(three).has_value());
}

}  // namespace
}  // namespace swath::control
