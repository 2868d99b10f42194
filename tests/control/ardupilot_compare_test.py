#!/usr/bin/python3
"""The metric functions of scripts/ardupilot-compare (the ArduCopter-vs-swath comparison; CI
cannot fly SITL, so the comparison itself is a measurement in docs/swath-control.md) on synthetic
tracks whose answers are known in closed form."""
import importlib.machinery
import importlib.util
import math
import os
import sys
import unittest

SCRIPT = os.path.join(os.path.dirname(__file__), '..', '..', 'scripts', 'ardupilot-compare')
loader = importlib.machinery.SourceFileLoader('ardupilot_compare', SCRIPT)
spec = importlib.util.spec_from_loader('ardupilot_compare', loader)
compare = importlib.util.module_from_spec(spec)
loader.exec_module(compare)

# A lawnmower's first turn: east 100 m, north 20 m, west 100 m.
PATH = [(0.0, 0.0), (100.0, 0.0), (100.0, 20.0), (0.0, 20.0)]


class CrossTrack(unittest.TestCase):
    def test_offsets_across_a_leg_come_back_with_their_quantiles(self):
        # Points 0, D/(N-1), ..., D south of the middle of the first leg: each one's distance is
        # its offset; over an evenly spaced sample the median is D/2, the 95th percentile
        # (linear interpolation) 0.95 D and the maximum D.
        n, d = 101, 4.0
        points = [(50.0, -d * k / (n - 1)) for k in range(n)]
        xte = compare.cross_track_m(points, PATH)
        for k, e in enumerate(xte):
            self.assertAlmostEqual(e, d * k / (n - 1), places=12)
        self.assertAlmostEqual(compare.quantile(xte, 0.5), d / 2, places=12)
        self.assertAlmostEqual(compare.quantile(xte, 0.95), 0.95 * d, places=12)
        self.assertEqual(max(xte), d)

    def test_beyond_a_corner_the_distance_is_to_the_corner(self):
        # Past the path's first corner, outside the turn: the corner (100, 0) is nearest, at
        # hypot(10, 5) (a line's extension would give 5).
        self.assertAlmostEqual(compare.cross_track_m([(110.0, -5.0)], PATH)[0], math.hypot(10, 5),
                               places=12)
        # Inside the turn, nearer the second leg than the first: 3 m from x = 100.
        self.assertAlmostEqual(compare.cross_track_m([(97.0, 10.0)], PATH)[0], 3.0, places=12)

    def test_circle_about_the_middle_of_the_last_leg(self):
        # Points on a circle of radius 2 about (50, 20): distance |2 sin(theta)| from the leg
        # y = 20 (the other legs are 50 m away); its RMS over a whole turn is 2 / sqrt(2).
        n = 3600
        pts = [(50 + 2 * math.cos(2 * math.pi * k / n), 20 + 2 * math.sin(2 * math.pi * k / n))
               for k in range(n)]
        xte = compare.cross_track_m(pts, PATH)
        self.assertAlmostEqual(compare.rms(xte), math.sqrt(2), places=9)
        self.assertAlmostEqual(max(xte), 2.0, places=9)


class Attitude(unittest.TestCase):
    def test_rms_per_axis_with_the_yaw_wrapped(self):
        # Roll setpoint A sin(w t) over whole periods against a level truth: RMS A / sqrt(2);
        # pitch a constant 1.5 deg off; yaw 359 wanted and 1 flown: 2 deg off, not 358.
        n, a = 1000, 3.0
        desired = [[a * math.sin(2 * math.pi * 5 * k / n), 1.5, 359.0] for k in range(n)]
        true = [[0.0, 0.0, 1.0] for _ in range(n)]
        r = compare.attitude_rms(desired, true)
        self.assertAlmostEqual(r[0], a / math.sqrt(2), places=9)
        self.assertAlmostEqual(r[1], 1.5, places=12)
        self.assertAlmostEqual(r[2], 2.0, places=9)

    def test_interpolated_yaw_crosses_north_the_short_way(self):
        self.assertAlmostEqual(compare.interpolate([0.0, 1.0], [[359.0], [3.0]], 0.25)[0], 360.0)


class Quiet(unittest.TestCase):
    def test_mid_leg_samples_with_a_steady_yaw_are_quiet(self):
        # Along the first leg at 1 m/s, one sample a second at x = 0 .. 100: quiet where
        # 15 < x < 85 (69 samples: 16 .. 84), less the second after a yaw step at x = 50
        # (samples 50: the step itself, its wanted yaw differs from 49's), and never in the
        # first second.
        t = [float(k) for k in range(101)]
        xy = [(float(k), 0.0) for k in range(101)]
        yaw = [90.0 if k < 50 else 95.0 for k in range(101)]
        mask = compare.quiet_mask(t, xy, yaw, PATH)
        quiet = [k for k, q in enumerate(mask) if q]
        self.assertEqual(quiet, [k for k in range(16, 85) if k != 50])


class Clock(unittest.TestCase):
    def test_offset_and_drift_come_back_from_the_simulated_attitude(self):
        # The plant rolls 10 sin(t) + 4 sin(2.3 t) deg at 50 Hz for 400 s; ArduPilot's clock reads
        # t_ap with plant time t_ap + 0.03 + 4e-4 t_ap (SIM_JSON's whole microseconds), and logs
        # SIM at 10 Hz: the map found is that line.
        truth_t = [k / 50 for k in range(50 * 400)]
        att = [[10 * math.sin(t) + 4 * math.sin(2.3 * t), 5 * math.cos(0.7 * t), 0.0] for t in truth_t]
        a, b = 0.03, 4e-4
        sim = []
        for k in range(1, 3900):
            t_ap = k / 10
            t = t_ap + a + b * t_ap
            sim.append((t_ap, [10 * math.sin(t) + 4 * math.sin(2.3 * t), 5 * math.cos(0.7 * t), 0.0]))
        fa, fb, residual = compare.clock_map(sim, truth_t, att)
        self.assertAlmostEqual(fb, b, delta=2e-5)
        self.assertAlmostEqual(fa, a, delta=3e-3)
        self.assertLess(residual, 0.05)


if __name__ == '__main__':
    result = unittest.main(exit=False, verbosity=1).result
    print('%d passed, %d failed' % (result.testsRun - len(result.failures) - len(result.errors),
                                    len(result.failures) + len(result.errors)))
    sys.exit(0 if result.wasSuccessful() else 1)
