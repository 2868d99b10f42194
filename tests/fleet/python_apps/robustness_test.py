#!/usr/bin/python3
"""swath-fleet's runtime against apps that misbehave (docs/swath-fleet.md "Apps in Python").

robustness_test.py SWATH_FLEET SOURCE_DIR: an app retrying a refused look in zero simulated time
ends (the tracking apps stop following; any app is bounded in tasks per instant); a run stops on a
signal or --max-time whatever the app's Python does; a refusal at the call is ActionFailed; a
task_failed reason is one line and the same from run to run; an app's metrics keep summary.json
readable; a file at a non-ASCII path loads; a bad WORLD, NAME or async APP is bad input.
"""
import os
import shutil
import signal
import subprocess
import sys
import time
import unittest

import fleet_runs
from fleet_runs import events, summary

FLEET, SOURCE = sys.argv[1], sys.argv[2]
HERE = os.path.join(SOURCE, "tests", "fleet", "python_apps")
APPS = os.path.join(SOURCE, "share", "apps")
# One drone and an inclusion fence 40 m square round the tracking world's start: the walker
# leaves it at 13.9 s.
FENCED = os.path.join(HERE, "fence40_fleet.yaml")


def run(app, world, out, *extra, timeout=120):
    return subprocess.run([FLEET, "run", app, "--world", world, "-o", out, *extra],
                          capture_output=True, text=True, timeout=timeout)


class Robustness(fleet_runs.RunsInTemporaryDirectory):
    FLEET = FLEET

    # ---- zero simulated time ------------------------------------------------------------------

    def test_tracking_stops_following_a_walker_outside_the_fence(self):
        # The look the fence refuses would be refused again at the same instant: the built-in
        # app and tracking.py stop following, with the same bytes.
        cpp, py = self.out("cpp"), self.out("py")
        a = run("tracking", "tracking", cpp, "--fleet", FENCED, "--seed", "1", timeout=60)
        self.assertEqual(a.returncode, 0, a.stderr)
        self.check_passes(cpp)
        self.assertEqual(len(self.failed_reasons(cpp)), 1, self.failed_reasons(cpp))
        self.assertIn("outside", self.failed_reasons(cpp)[0])
        self.assertGreater(summary(cpp)["app_metrics"]["looks"], 0)
        b = run(os.path.join(APPS, "tracking.py"), "tracking", py, "--fleet", FENCED, "--seed", "1",
                timeout=60)
        self.assertEqual(b.returncode, 0, b.stderr)
        with open(os.path.join(cpp, "events.jsonl"), "rb") as f, \
                open(os.path.join(py, "events.jsonl"), "rb") as g:
            self.assertEqual(f.read(), g.read())

    def test_tasks_created_at_one_instant_are_bounded(self):
        # An app of its own retrying a refused fly_to at once, for ever: the run ends (exit 4).
        loop = self.app("loop.py", "from swath_fleet import ActionFailed\n"
                        "def t(bee):\n    return bee.act('fly_to', 1000.0, 0.0).value\n"
                        "def APP(bee):\n    while True:\n        try:\n"
                        "            bee.newTask(t).value\n        except ActionFailed:\n"
                        "            pass\n")
        out = self.out("loop")
        r = run(loop, "tracking", out, "--fleet", FENCED, "--max-time", "60", timeout=300)
        self.assertEqual(r.returncode, 4, r.stderr)
        s = summary(out)
        self.assertIn("created more than 20000 tasks at 0 s without letting the clock move",
                      s["failure"])
        created = sum(1 for e in events(out) if e["ev"] == "task_created")
        self.assertLessEqual(created, 20002)
        self.check_passes(out)

    # ---- stopping whatever the app does -------------------------------------------------------

    def stop(self, text, *extra, sig=None, after="spinning"):
        """Runs the app (paced), sends `sig` once stderr says `after`; the exit code, stderr, the
        wall seconds from the signal (or the start) to the end, and the output folder."""
        app, out = self.app("stop.py", text), self.out("stop")
        p = subprocess.Popen([FLEET, "run", app, "--world", "hotspot", "--drones", "1", "--pace",
                              "20", "-o", out, *extra],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        try:
            start = time.monotonic()
            if sig is not None:
                while after not in p.stderr.readline():
                    pass
                start = time.monotonic()
                p.send_signal(sig)
            _, err = p.communicate(timeout=40)
        finally:
            if p.poll() is None:
                p.kill()
                p.communicate()
        return p.returncode, err, time.monotonic() - start, out

    BARE_EXCEPT = ("import sys\n"
                   "def t(bee):\n"
                   "    bee.act('fly_to', 20.0, 0.0).value\n"
                   "    print('spinning', file=sys.stderr, flush=True)\n"
                   "    while True:\n"
                   "        try:\n"
                   "            while True:\n"
                   "                pass\n"
                   "        except:  # noqa: E722  (also catches TaskKilled)\n"
                   "            pass\n"
                   "def APP(bee):\n"
                   "    bee.newTask(t).value\n")

    def test_a_signal_stops_an_app_that_catches_task_killed(self):
        for sig, code in ((signal.SIGINT, 130), (signal.SIGTERM, 143)):
            rc, err, took_s, out = self.stop(self.BARE_EXCEPT, sig=sig)
            self.assertEqual(rc, code, err)
            self.assertLess(took_s, 10)
            ev = events(out)
            self.assertEqual(ev[-1]["ev"], "run_end")
            self.assertEqual([e["command"] for e in ev if e["ev"] == "abort_command"], ["rtl"])
            self.assertIn("stop.py: stopped by %s while it kept its turn; abandoned 2 s later" %
                          signal.Signals(sig).name, "\n".join(self.failed_reasons(out)))
            self.check_passes(out)

    def test_max_time_stops_an_app_inside_a_c_call(self):
        rc, err, took_s, out = self.stop("import time\ndef APP(bee):\n    time.sleep(1000)\n",
                                         "--max-time", "2")
        self.assertEqual(rc, 4, err)
        self.assertLess(took_s, 15)
        self.assertIn("kept its turn (never waited on a future) for more than --max-time, 2 s of "
                      "wall-clock time; abandoned 2 s later", "\n".join(self.failed_reasons(out)))
        self.check_passes(out)

    # ---- what an app sees and what the log says -----------------------------------------------

    def test_refusals_at_the_call_raise_action_failed(self):
        app = self.app("refused.py", "def fly(bee):\n"
                       "    try:\n        bee.act('fly_to', 100.0, 0.0).value\n"
                       "    except BaseException as e:\n        return type(e).__name__\n"
                       "def sense(bee):\n"
                       "    try:\n        bee.act('sense', 'no-such-sensor').value\n"
                       "    except BaseException as e:\n        return type(e).__name__\n"
                       "def raw(bee):\n    return bee.act('fly_to', 100.0, 0.0).value\n"
                       "def APP(bee):\n"
                       "    bee.metric('fly_' + bee.newTask(fly).value, 1)\n"
                       "    bee.metric('sense_' + bee.newTask(sense).value, 1)\n"
                       "    try:\n        bee.newTask(raw).value\n"
                       "    except BaseException as e:\n"
                       "        bee.metric('future_' + type(e).__name__, 1)\n")
        out = self.out("refused")
        r = run(app, "tracking", out, "--fleet", FENCED)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(set(summary(out)["app_metrics"]),
                         {"fly_ActionFailed", "sense_ActionFailed", "future_ActionFailed"})
        # The refused task's reason is the runtime's, as for the built-in apps.
        self.assertEqual(len(self.failed_reasons(out)), 1)
        self.assertTrue(self.failed_reasons(out)[0].startswith("fly_to (100, 0, 0) m is "))

    def test_task_failed_reasons_are_one_line_and_the_same_each_run(self):
        app = self.app("noargs.py", "def t(bee):\n    return bee.act().value\n"
                       "def u(bee):\n    return bee.newTask().value\n"
                       "def APP(bee):\n    for f in (t, u):\n        try:\n"
                       "            bee.newTask(f).value\n        except Exception:\n"
                       "            pass\n")
        logs = []
        for i in range(2):
            out = self.out("noargs%d" % i)
            r = run(app, "hotspot", out, "--drones", "1", "--seed", "1")
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(os.path.join(out, "events.jsonl"), "rb") as f:
                logs.append(f.read())
            reasons = self.failed_reasons(out)
            self.assertEqual(len(reasons), 2, reasons)
            for reason in reasons:
                self.assertNotIn("\n", reason)
                self.assertNotIn(" at 0x", reason)
            self.assertEqual(reasons[0], app + " line 2: TypeError: bee.act(name, *args): the "
                             "action's name is missing (fly_to, sense, hover, custom)")
        self.assertEqual(logs[0], logs[1])

    def test_metrics_are_bounded_and_summary_stays_readable(self):
        # 250 NULs and 4 digits: 1,536 bytes each in summary.json as counted, 1,365 fit 2 MiB.
        app = self.app("metrics.py", "def APP(bee):\n    for i in range(1365):\n"
                       "        bee.metric('\\x00' * 250 + '%04d' % i, i)\n"
                       "    bee.metric('\\x00' * 250 + '0000', -1)  # a name again: no new one\n"
                       "    bee.metric('\\x00' * 250 + 'more', 1)\n")
        out = self.out("metrics")
        start = time.monotonic()
        r = run(app, "hotspot", out, "--drones", "1")
        self.assertLess(time.monotonic() - start, 30)
        self.assertEqual(r.returncode, 4, r.stderr)
        self.assertIn(app + " line 5: ValueError: metric \"" + "\\x00" * 40 + "...\": more than "
                      "10000 metric names or 2 MiB of them in summary.json", r.stderr)
        self.assertLess(os.path.getsize(os.path.join(out, "summary.json")), 4 << 20)
        metrics = summary(out)["app_metrics"]
        self.assertEqual(len(metrics), 1365)
        self.assertEqual(metrics["\x00" * 250 + "0000"], -1)
        # Short names: 10,000 fit (the readings of python_apps_test's world reader), not 10,001.
        many = self.app("many.py", "def APP(bee):\n    for i in range(10001):\n"
                        "        bee.metric('r%05d' % i, i)\n")
        r = run(many, "hotspot", self.out("many"), "--drones", "1")
        self.assertEqual(r.returncode, 4, r.stderr)
        self.assertIn(many + " line 3: ValueError: metric \"r10000\": more than 10000", r.stderr)
        self.assertEqual(len(summary(self.out("many"))["app_metrics"]), 10000)
        c = subprocess.run([FLEET, "collect", out, "-o", self.out("col")], capture_output=True,
                           text=True, timeout=60)
        self.assertEqual(c.returncode, 0, c.stderr)

    # ---- loading ------------------------------------------------------------------------------

    def test_an_app_at_a_non_ascii_path_runs(self):
        app = self.out("ünï/app.py")
        os.makedirs(os.path.dirname(app))
        shutil.copy(os.path.join(APPS, "hotspot.py"), app)
        with open(os.path.join(os.path.dirname(app), "helper_ü.py"), "w") as f:
            f.write("X = 1\n")
        with open(app, "a") as f:
            f.write("import helper_ü  # noqa: E402  (beside the app)\n")
        out = self.out("unicode")
        r = run(app, "hotspot", out, "--drones", "2")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("final_distance_to_source_m", summary(out)["app_metrics"])
        bad = self.app("ünï/bad.py", "def APP(bee):\n    return 1 +\n")
        r = run(bad, "hotspot", self.out("bad"))
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn(bad + " line 2: SyntaxError", r.stderr)

    def test_bad_world_name_or_async_app_is_bad_input(self):
        cases = {
            "WORLD = 5\ndef APP(bee):\n    pass\n": "WORLD must name a world kind (",
            "WORLD = 'moon'\ndef APP(bee):\n    pass\n": ", not 'moon'",
            "NAME = 7\ndef APP(bee):\n    pass\n": "NAME must be a non-empty string, not 7",
            "async def APP(bee):\n    pass\n": "APP must be a plain function (def APP(bee): ...)",
            "def APP(bee):\n    yield 1\n": "APP must be a plain function",
        }
        for i, (text, want) in enumerate(cases.items()):
            app, out = self.app("bad%d.py" % i, text), self.out("bad%d" % i)
            r = run(app, "hotspot", out)
            self.assertEqual(r.returncode, 2, text + r.stderr)
            self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
            self.assertTrue(r.stderr.startswith("swath-fleet: " + app + ": "), r.stderr)
            self.assertIn(want, r.stderr)
            self.assertNotIn("register_app", r.stderr)
            self.assertFalse(os.path.exists(out))


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
