#!/usr/bin/python3
"""swath-fleet's Python apps (docs/swath-fleet.md "Apps in Python"), end to end through the program.

python_apps_test.py SWATH_FLEET SOURCE_DIR: tasks, futures and cancellation checked by
`swath-fleet check` and parsed back from events.jsonl; the same seed gives the same bytes
whatever the Python threads' timing (random sleeps, runs side by side); a Python exception is one
sentence naming the file and line; the case studies in share/apps/ give the C++ apps' events;
wifi_sklearn.py (scikit-learn's GP) maps the field about as well as the built-in wifi app.
"""
import json
import os
import re
import selectors
import signal
import subprocess
import sys
import tempfile
import time
import unittest
from types import SimpleNamespace
from concurrent.futures import ThreadPoolExecutor

import fleet_runs
from fleet_runs import events

try:
    import numpy as np
    HAVE_NUMPY = True
except ImportError:
    HAVE_NUMPY = False
try:
    import sklearn  # noqa: F401  (share/apps/wifi_sklearn.py's, Debian's python3-sklearn)
    HAVE_SKLEARN = HAVE_NUMPY
except ImportError:
    HAVE_SKLEARN = False

FLEET, SOURCE = sys.argv[1], sys.argv[2]
HERE = os.path.join(SOURCE, "tests", "fleet", "python_apps")
APPS = os.path.join(SOURCE, "share", "apps")
# 1,000 live tasks spawn and end within this (wall seconds; 25 s when every hand-over woke every
# task's thread).
MANY_TASKS_S = 15


def run(app, world, out, *extra):
    return subprocess.run([FLEET, "run", app, "--world", world, "-o", out, *extra],
                          capture_output=True, text=True)


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


class PythonApps(fleet_runs.RunsInTemporaryDirectory):
    FLEET = FLEET

    def test_tasks_futures_cancellation(self):
        out = self.out("run")
        r = run(os.path.join(HERE, "tasks_app.py"), "sites", out, "--drones", "3", "--seed", "5")
        self.assertEqual(r.returncode, 0, r.stderr)
        c = subprocess.run([FLEET, "check", out], capture_output=True, text=True)
        self.assertEqual(c.returncode, 0, c.stdout + c.stderr)
        ev = events(out)
        created = {e["task"]: e for e in ev if e["ev"] == "task_created"}
        kinds = sorted(e.get("kind", "") for e in created.values())
        self.assertEqual(kinds.count("photo"), 2, created)
        loiter = [t for t, e in created.items() if e.get("kind") == "loiter"]
        parcel = [t for t, e in created.items() if e.get("kind") == "parcel"]
        self.assertEqual(len(loiter), 1)
        self.assertEqual(len(parcel), 1)
        self.assertIs(created[loiter[0]]["interruptible"], False)
        self.assertIs(created[parcel[0]]["same_drone"], True)
        ends = {e["task"]: e["ev"] for e in ev if e["ev"].startswith("task_") and e["ev"] != "task_created"}
        self.assertEqual(ends[loiter[0]], "task_cancelled")
        self.assertEqual(ends[parcel[0]], "task_done")
        with open(os.path.join(out, "summary.json")) as f:
            metrics = json.load(f)["app_metrics"]
        self.assertEqual(metrics["cancel_seen"], 1)
        self.assertEqual(metrics["photos"], 2)
        self.assertEqual(metrics["parcel_dropped"], 1)

    def test_same_seed_same_bytes_whatever_the_timing(self):
        app = os.path.join(HERE, "tasks_app.py")
        outs = [self.out(f"run{i}") for i in range(4)]
        with ThreadPoolExecutor(4) as pool:  # side by side: the threads' timing differs
            results = list(pool.map(lambda o: run(app, "sites", o, "--drones", "3", "--seed", "9"), outs))
        for r in results:
            self.assertEqual(r.returncode, 0, r.stderr)
        first = read_bytes(os.path.join(outs[0], "events.jsonl"))
        self.assertGreater(len(first), 0)
        for o in outs[1:]:
            self.assertEqual(read_bytes(os.path.join(o, "events.jsonl")), first, o)

    def test_exception_in_a_task_names_file_and_line(self):
        out = self.out("run")
        app = os.path.join(HERE, "raising_app.py")
        r = run(app, "sites", out, "--drones", "2")
        self.assertEqual(r.returncode, 4, r.stderr)  # the app did not complete
        self.assertIn(app + " line 9: ZeroDivisionError: ", r.stderr)
        self.assertEqual(r.stderr.count("ZeroDivisionError"), 1, r.stderr)  # said once
        ev = events(out)  # every line whole: the log was closed
        failed = [e for e in ev if e["ev"] == "task_failed"]
        self.assertTrue(any("line 9: ZeroDivisionError" in e.get("reason", "") for e in failed), failed)

    def test_sigint_aborts_a_python_app_run_with_its_files(self):
        out = self.out("run")
        p = subprocess.Popen([FLEET, "run", os.path.join(APPS, "tracking.py"), "--world", "tracking",
                              "--drones", "3", "--backend", "sim", "--pace", "10", "-o", out],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        time.sleep(1.5)
        p.send_signal(signal.SIGINT)
        _, err = p.communicate(timeout=60)
        self.assertEqual(p.returncode, 130, err)
        self.assertEqual(events(out)[-1]["ev"], "run_end")

    def test_a_sensor_of_the_apps_own(self):
        out = self.out("run")
        r = run(os.path.join(HERE, "sensor_app.py"), "sites", out, "--drones", "1")
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(out, "summary.json")) as f:
            metrics = json.load(f)["app_metrics"]
        self.assertAlmostEqual(metrics["sense_s"], 7.0, places=6)  # the sensor's own time
        self.assertAlmostEqual(metrics["error"], 0.0, places=6)  # its reading where it was
        self.assertTrue(any(e["ev"] == "action_done" and e.get("name") == "gas" for e in events(out)))

    def test_a_file_without_app_is_bad_input(self):
        out = self.out("run")
        r = run(os.path.join(HERE, "no_app.py"), "sites", out)
        self.assertEqual(r.returncode, 2)
        self.assertIn("no_app.py: defines no function APP(bee)", r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1)
        self.assertFalse(os.path.exists(out))

    def test_a_syntax_error_is_bad_input_naming_the_line(self):
        out = self.out("run")
        app = os.path.join(HERE, "syntax_error_app.py")
        r = run(app, "sites", out)
        self.assertEqual(r.returncode, 2)
        self.assertIn(app + " line 4: SyntaxError", r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertFalse(os.path.exists(out))

    # ---- apps that keep their turn, spawn without end, or break their sensors ----------------

    def wait_for_stderr(self, p, text, timeout_s=60):
        # Reads the raw pipe, not readline(): at the end of a run that has exited, readline()
        # returns "" at once, forever, and a loop waiting for `text` never ends.
        seen = b""
        deadline = time.monotonic() + timeout_s
        with selectors.DefaultSelector() as waiting:
            waiting.register(p.stderr, selectors.EVENT_READ)
            while text.encode() not in seen:
                left_s = deadline - time.monotonic()
                if left_s <= 0 or not waiting.select(left_s):
                    self.fail(f"swath-fleet wrote no {text!r} within {timeout_s} s: {seen!r}")
                chunk = os.read(p.stderr.fileno(), 4096)
                if not chunk:
                    self.fail(f"swath-fleet ended (exit {p.wait()}) before it wrote {text!r}: "
                              + seen.decode(errors="replace"))
                seen += chunk

    def test_a_signal_stops_a_task_that_keeps_its_turn(self):
        # The task flies out, then loops in pure Python: the runtime waits for its turn, yet
        # SIGINT and SIGTERM still abort the run (exit 130, 143), the drone told to return.
        app = self.app("spin.py", "import sys\n"
                       "def t(bee):\n"
                       "    bee.act('fly_to', 20.0, 0.0).value\n"
                       "    print('spinning', file=sys.stderr, flush=True)\n"
                       "    while True:\n"
                       "        pass\n"
                       "def APP(bee):\n"
                       "    bee.newTask(t).value\n")
        for sig, code in ((signal.SIGINT, 130), (signal.SIGTERM, 143)):
            out = self.out("spin-%d" % code)
            p = subprocess.Popen([FLEET, "run", app, "--world", "hotspot", "--drones", "1",
                                  "--pace", "20", "-o", out],
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            try:
                self.wait_for_stderr(p, "spinning")
                p.send_signal(sig)
                _, err = p.communicate(timeout=30)
            finally:
                if p.poll() is None:
                    p.kill()
                    p.communicate()
            self.assertEqual(p.returncode, code, err)
            ev = events(out)
            self.assertEqual(ev[-1]["ev"], "run_end")
            self.assertEqual([e["command"] for e in ev if e["ev"] == "abort_command"], ["rtl"])
            # The loop's line, `while` or `pass`, wherever the exception found it.
            self.assertRegex("\n".join(self.failed_reasons(out)),
                             re.escape(app) + " line [56]: stopped by %s while it kept its turn" %
                             signal.Signals(sig).name)
            self.check_passes(out)

    def test_max_time_bounds_the_wall_time_of_an_app_that_never_waits(self):
        # A task spawned first is ready when the main is stopped: the run still fails for the
        # main's own reason.
        spin = self.app("spin_main.py", "def APP(bee):\n    bee.newTask(lambda b: b.act('hover', 1.0).value)\n"
                        "    while True:\n        pass\n")
        out = self.out("spin")
        start = time.monotonic()
        r = subprocess.run([FLEET, "run", spin, "--world", "hotspot", "--drones", "1",
                            "--max-time", "2", "-o", out], capture_output=True, text=True, timeout=60)
        self.assertLess(time.monotonic() - start, 30)
        self.assertEqual(r.returncode, 4, r.stderr)
        self.assertRegex(r.stderr, re.escape(spin) + " line [34]: kept its turn \\(never waited on a "
                         "future\\) for more than --max-time, 2 s of wall-clock time")
        # The run failed for the main's own reason, not for tasks waking each other.
        self.assertNotIn("kept waking each other", r.stderr)
        self.assertEqual(fleet_runs.summary(out)["failure"], "the app's main failed")
        self.check_passes(out)
        # Tasks that only spawn and return keep the runtime busy without the clock moving: the
        # hover the main waits for never comes.
        chain = self.app("chain_nowait.py", "def t(bee):\n    bee.newTask(t)\n    return 1\n"
                         "def slow(bee):\n    return bee.act('hover', 1.0).value\n"
                         "def APP(bee):\n    bee.newTask(t)\n    bee.newTask(slow).value\n")
        out = self.out("chain")
        r = subprocess.run([FLEET, "run", chain, "--world", "hotspot", "--drones", "1",
                            "--max-time", "2", "-o", out], capture_output=True, text=True, timeout=60)
        # Whichever bound comes first ends it: 2 s of wall-clock time, or 20,000 tasks at one
        # instant (a fast machine makes them within the 2 s).
        self.assertEqual(r.returncode, 4, r.stderr)
        self.assertRegex(r.stderr, "the app's tasks kept waking each other for more than "
                         "max_time_s \\(2 s\\) of wall-clock time without letting the clock move"
                         "|the app created more than 20000 tasks at 0 s without letting the clock "
                         "move")
        self.assertEqual(events(out)[-1]["ev"], "run_end")

    def test_live_tasks_are_bounded_and_spawn_in_linear_time(self):
        # 1,000 tasks alive at once, each on its own thread, waiting for a drone: a hand-over wakes
        # one thread only. 2,001 tasks that each wait on the next: the last cannot start.
        many = self.app("many.py", "def t(bee, i):\n    return bee.act('hover', 0.0).value\n"
                        "def APP(bee):\n    fs = [bee.newTask(t, i) for i in range(1000)]\n"
                        "    for f in fs:\n        f.value\n")
        out = self.out("many")
        start = time.monotonic()
        r = subprocess.run([FLEET, "run", many, "--world", "hotspot", "--drones", "4", "-o", out],
                           capture_output=True, text=True, timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertLess(time.monotonic() - start, MANY_TASKS_S)
        chain = self.app("chain.py", "def t(bee):\n    return bee.newTask(t).value\n"
                         "def APP(bee):\n    bee.newTask(t).value\n")
        out = self.out("chain")
        r = subprocess.run([FLEET, "run", chain, "--world", "hotspot", "--drones", "1", "-o", out],
                           capture_output=True, text=True, timeout=120)
        self.assertEqual(r.returncode, 4, r.stderr)
        self.assertIn(chain + " line 2: bee.newTask: more than 2000 tasks alive at once", r.stderr)
        self.check_passes(out)

    def test_a_sensor_that_fails_fails_its_task(self):
        for name, body, why in (
                ("str", "return 'not a list'", 'line 1: sensor "s" must return a list of numbers, not a str'),
                ("boom", "raise ValueError('sensor broke')", "line 2: ValueError: sensor broke")):
            app = self.app(name + ".py", "def s(x, y, t):\n    %s\nSENSORS = {'s': (1.0, s)}\n"
                           "def t(bee):\n    bee.act('fly_to', 5.0, 5.0)\n"
                           "    return bee.act('sense', 's').value\n"
                           "def APP(bee):\n    bee.newTask(t).value\n" % body)
            out = self.out(name)
            r = run(app, "hotspot", out, "--drones", "1")
            self.assertEqual(r.returncode, 4, r.stderr)  # an exception in a task, not exit 1
            self.assertIn(app + " " + why, r.stderr)
            self.assertTrue(any(app + " " + why in x for x in self.failed_reasons(out)))
            self.check_passes(out)

    def test_bad_sensors_tables_are_bad_input(self):
        for entry, why in (("(1.0, 3)", "its reading must be a function fn(x_m, y_m, t_s), not 3"),
                           ("(-5.0, ok)", "time_s must be a number of seconds from 0 to 3600, not -5.0"),
                           ("(float('nan'), ok)", "not nan"), ("(1e300, ok)", "not 1e+300"),
                           ("('5', ok)", "not '5'"), ("ok", "must be (time_s, fn(x_m, y_m, t_s))")):
            app = self.app("st.py", "def ok(x, y, t): return [1.0]\nSENSORS = {'s': %s}\n"
                           "def APP(bee): pass\n" % entry)
            out = self.out("st")
            r = run(app, "hotspot", out, "--drones", "1")
            self.assertEqual(r.returncode, 2, entry + ": " + r.stderr)
            self.assertIn(app + ': SENSORS["s"]', r.stderr)
            self.assertIn(why, r.stderr)
            self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
            self.assertFalse(os.path.exists(out))

    def test_bad_action_arguments_fail_the_task_on_its_line(self):
        for call, why in (("bee.act('hover', -10.0)", "seconds must be from 0 to 86400 s, not -10"),
                          ("bee.act('hover', float('nan'))", "seconds must be finite, not nan"),
                          ("bee.act('fly_to', 10.0, 10.0, float('nan'))", "z_m must be finite, not nan"),
                          ("bee.act('fly_to', 'a', 'b')", "x_m must be a number, not a str"),
                          ("bee.act('sense', 5)", "sensor must be a string, not a int"),
                          ("bee.cancelTasks([1])", "each item must be a task's Future, not a int"),
                          ("bee.newTask(t, kind='x' * 2000000)", "kind must be at most 256 bytes long"),
                          ("bee.metric('m', 'high') or bee.newTask(t)", "value must be a number, not a str")):
            app = self.app("act.py", "def t(bee):\n    return 1\ndef u(bee):\n    %s.value\n"
                           "def APP(bee):\n    bee.newTask(u).value\n" % call)
            out = self.out("act")
            r = run(app, "hotspot", out, "--drones", "1")
            self.assertEqual(r.returncode, 4, call + ": " + r.stderr)
            self.assertIn(app + " line 4: ", r.stderr)
            self.assertIn(why, r.stderr)
            self.check_passes(out)

    @unittest.skipUnless(HAVE_NUMPY, "needs numpy (Debian's python3-numpy)")
    def test_numpy_numbers_are_numbers(self):
        # Apps compute with NumPy: its scalars are numbers to fly_to, hover and metric, and a
        # sensor may return them (or an array).
        app = self.app("np.py", "import numpy as np\n"
                       "def t(bee):\n"
                       "    bee.act('fly_to', np.float32(12.5), np.int64(7), np.float64(0)).value\n"
                       "    bee.act('hover', np.float32(1.5)).value\n"
                       "    bee.metric('m', np.float32(2.5))\n"
                       "    return 1\n"
                       "def APP(bee):\n    bee.newTask(t).value\n")
        out = self.out("np")
        r = run(app, "hotspot", out, "--drones", "1")
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(out, "summary.json")) as f:
            self.assertEqual(json.load(f)["app_metrics"]["m"], 2.5)
        self.assertTrue(any(e["ev"] == "dispatch" for e in events(out)))
        self.check_passes(out)

    def test_os_exit_in_a_task_does_not_end_the_run(self):
        app = self.app("osexit.py", "import os\ndef t(bee):\n    os._exit(0)\n"
                       "def APP(bee):\n    bee.newTask(t).value\n")
        out = self.out("osexit")
        r = run(app, "hotspot", out, "--drones", "1")
        self.assertEqual(r.returncode, 4, r.stderr)
        self.assertIn(app + " line 3: SystemExit: os._exit(0): an app ends by returning from APP",
                      r.stderr)
        self.assertEqual(events(out)[-1]["ev"], "run_end")

    def test_a_file_python_cannot_decode_is_bad_input_naming_the_file(self):
        app = self.out("binary.py")
        with open(app, "wb") as f:
            f.write(b"\xff\xfe bad\n")
        r = run(app, "hotspot", self.out("binary"))
        self.assertEqual(r.returncode, 2)
        # The file is compiled from its bytes: Python places the undecodable byte on line 1.
        self.assertIn(app + " line 1: SyntaxError: ", r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertNotIn("line None", r.stderr)
        self.assertFalse(os.path.exists(self.out("binary")))

    def parity(self, name, world, seeds, *extra, mutation=None):
        # The Python file is what runs (it logs under the built-in's name): a changed copy of it
        # gives other events.
        mutant = self.out(name + "-mutant.py")
        with open(os.path.join(APPS, name + ".py")) as f:
            text = f.read()
        self.assertIn(mutation[0], text)
        with open(mutant, "w") as f:
            f.write(text.replace(mutation[0], mutation[1]))
        m = run(mutant, world, self.out(name + "-mutant"), "--seed", str(seeds[0]), *extra)
        self.assertEqual(m.returncode, 0, m.stderr)
        cpp0 = self.out(f"{name}-first")
        run(name, world, cpp0, "--seed", str(seeds[0]), *extra)
        self.assertNotEqual(read_bytes(os.path.join(self.out(name + "-mutant"), "events.jsonl")),
                            read_bytes(os.path.join(cpp0, "events.jsonl")))
        for seed in seeds:
            cpp, py = self.out(f"{name}-{seed}-cpp"), self.out(f"{name}-{seed}-py")
            a = run(name, world, cpp, "--seed", str(seed), *extra)
            b = run(os.path.join(APPS, name + ".py"), world, py, "--seed", str(seed), *extra)
            self.assertEqual(a.returncode, b.returncode, b.stderr)
            ea = read_bytes(os.path.join(cpp, "events.jsonl"))
            eb = read_bytes(os.path.join(py, "events.jsonl"))
            self.assertGreater(len(ea), 1000)
            self.assertEqual(ea, eb, f"{name} seed {seed}")

    def test_parity_hotspot(self):
        self.parity("hotspot", "hotspot", [1, 2], "--drones", "4",
                    mutation=("x + dx, y + dy", "x + dy, y + dx"))

    def test_parity_road(self):
        self.parity("road", "road", [1, 2], "--drones", "3",
                    mutation=("90.0 - r.values[2]", "91.0 - r.values[2]"))

    def test_parity_multiplexing(self):
        self.parity("multiplexing", "sites", [1, 2], "--drones", "2",
                    mutation=('"video", same_drone=True', '"video", same_drone=False'))

    def test_parity_wifi(self):
        self.parity("wifi", "rf_field", [1, 2], "--drones", "2",
                    mutation=("< below_db", "< below_db + 1.0"))

    def test_parity_tracking(self):
        self.parity("tracking", "tracking", [1, 2], "--drones", "3",
                    mutation=("+ 2.0, 10.0", "+ 4.0, 10.0"))


# The world's reading at each place, from the world itself: an app of the test's own senses there
# (a reading's noise is a hash of the place, never of time or order, so it reads what an app
# sensing there read) and reports each value as a metric; a task reads a group of places in turn.
READER = """WORLD = "rf_field"
GROUPS = {groups!r}


def read(bee, places):
    values = []
    for x, y in places:
        bee.act("fly_to", x, y, 0.0)
        values.append(bee.act("sense", "rssi").value.values[0])
    return values


def APP(bee):
    tasks = [bee.newTask(read, g) for g in GROUPS]
    i = 0
    for t in tasks:
        for v in t.value:
            bee.metric("r%05d" % i, v)
            i += 1
"""

RF = {"x0_m": -25.0, "y0_m": -35.0, "width_m": 50.0, "height_m": 70.0, "cell_m": 5.0,
      "gp_length_m": 12.0, "gp_sigma_f": 6.0, "gp_sigma_n_db": 2.0, "cancel_below_db": 3.0}
RING_M = [(0.05, 0.0), (-0.05, 0.0), (0.0, 0.05), (0.0, -0.05),
          (0.05, 0.05), (-0.05, -0.05), (0.05, -0.05), (-0.05, 0.05)]


def rf_grid():
    """The cell centres of share/worlds/rf_field.yaml's fence (50 x 70 m centred on the origin)."""
    n_x, n_y = int(RF["width_m"] / RF["cell_m"]), int(RF["height_m"] / RF["cell_m"])
    return [(RF["x0_m"] + (i + 0.5) * RF["cell_m"], RF["y0_m"] + (j + 0.5) * RF["cell_m"])
            for j in range(n_y) for i in range(n_x)]


def sensed_places(out):
    return [(e["x_m"], e["y_m"]) for e in events(out) if e["ev"] == "action_done" and e["name"] == "rssi"]


def rbf_gp_map(xy, values, at):
    """The built-in wifi app's map (fleet/apps/src/gaussian_process.hpp), in closed form: RBF
    sigma_f^2 exp(-d^2 / 2 l^2), noise sigma_n^2, prior mean the readings' mean."""
    xy, at, v = np.asarray(xy), np.asarray(at), np.asarray(values)

    def k(a, b):
        d2 = ((a[:, None, :] - b[None, :, :]) ** 2).sum(-1)
        return RF["gp_sigma_f"] ** 2 * np.exp(-d2 / (2 * RF["gp_length_m"] ** 2))

    kk = k(xy, xy) + RF["gp_sigma_n_db"] ** 2 * np.eye(len(xy))
    return v.mean() + k(at, xy) @ np.linalg.solve(kk, v - v.mean())


@unittest.skipUnless(HAVE_SKLEARN, "skipped: scikit-learn is not importable (Debian's python3-sklearn)")
class WifiSklearn(unittest.TestCase):
    SEED = "3"

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        self.app = os.path.join(APPS, "wifi_sklearn.py")

    def out(self, name):
        return os.path.join(self.tmp.name, name)

    def read_world(self, places, group=1):
        app = self.out("reader%d.py" % len(os.listdir(self.tmp.name)))
        places = [(float(x), float(y)) for x, y in places]
        with open(app, "w") as f:
            f.write(READER.format(groups=[places[i:i + group] for i in range(0, len(places), group)]))
        out = app[:-3]
        r = run(app, "rf_field", out, "--drones", "20", "--seed", self.SEED)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(out, "summary.json")) as f:
            metrics = json.load(f)["app_metrics"]
        return [metrics["r%05d" % i] for i in range(len(places))]

    def sklearn_app(self):
        sys.path.insert(0, APPS)
        self.addCleanup(sys.path.remove, APPS)
        import wifi_sklearn
        return wifi_sklearn

    def test_runs_checked_and_same_bytes(self):
        outs = [self.out("a"), self.out("b")]
        for o in outs:
            r = run(self.app, "rf_field", o, "--drones", "2", "--seed", self.SEED)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertEqual(r.stderr, "")
            c = subprocess.run([FLEET, "check", o], capture_output=True, text=True)
            self.assertEqual(c.returncode, 0, c.stdout + c.stderr)
        for name in ("events.jsonl", "summary.json", "dtg.json", "tracks.geojson"):
            self.assertEqual(read_bytes(os.path.join(outs[0], name)), read_bytes(os.path.join(outs[1], name)), name)
        sensed = sensed_places(outs[0])
        self.assertGreater(len(sensed), 10)
        self.assertEqual(len(set(sensed)), len(sensed))  # never the same cell twice

    def test_map_about_as_good_as_the_built_in_apps(self):
        grid = rf_grid()
        ring = [(x + dx, y + dy) for x, y in grid for dx, dy in RING_M]
        truth = np.asarray(self.read_world(ring, group=len(RING_M))).reshape(len(grid), len(RING_M)).mean(axis=1)
        cpp, py = self.out("cpp"), self.out("py")
        for app, o in (("wifi", cpp), (self.app, py)):
            r = run(app, "rf_field", o, "--drones", "2", "--seed", self.SEED)
            self.assertEqual(r.returncode, 0, r.stderr)
        cpp_xy = sensed_places(cpp)
        cpp_map = rbf_gp_map(cpp_xy, self.read_world(cpp_xy), grid)
        py_xy = sensed_places(py)
        m = self.sklearn_app()
        w = SimpleNamespace(**RF)
        gp, mean_db = m.fit_map(w, py_xy, self.read_world(py_xy))
        with open(os.path.join(py, "summary.json")) as f:
            metrics = json.load(f)["app_metrics"]
        py_map = m.predict_map(gp, mean_db, grid)
        self.assertEqual(metrics["cells_sensed"], len(py_xy))
        self.assertAlmostEqual(float(np.mean(py_map)), metrics["map_mean_dbm"], places=5)  # the app's map
        rmse_cpp = float(np.sqrt(np.mean((cpp_map - truth) ** 2)))
        rmse_py = float(np.sqrt(np.mean((py_map - truth) ** 2)))
        spread = float(np.std(truth))
        print(f"\nwifi map RMSE vs the world's signal (spread {spread:.2f} dB): built-in {rmse_cpp:.2f} dB "
              f"from {len(cpp_xy)} readings, sklearn {rmse_py:.2f} dB from {len(py_xy)}", file=sys.stderr)
        self.assertLess(rmse_cpp, 0.3 * spread)  # the yardstick itself maps the field
        self.assertLess(rmse_py, 1.5 * rmse_cpp)  # about as good: within 50 %, from fewer readings


def runs_python_apps():
    """Whether FLEET runs Python apps: one built without them (SWATH_PYTHON off, or no python3-dev
    and python3-pybind11) takes APP.py for the name of a built-in app it does not know."""
    with tempfile.TemporaryDirectory() as tmp:
        app = os.path.join(tmp, "empty.py")
        with open(app, "w") as f:
            f.write("def APP(bee):\n    pass\n")
        r = run(app, "hotspot", os.path.join(tmp, "run"), "--drones", "1")
        return not (r.returncode == 2 and f'unknown app "{app}"' in r.stderr)


if __name__ == "__main__":
    if not runs_python_apps():
        # Every test would fail on the same missing feature; CTest runs this file only for a
        # swath-fleet built with Python apps (tests/CMakeLists.txt), so here it is a wrong call.
        sys.exit(f"python_apps_test.py: {FLEET} is built without Python apps (SWATH_PYTHON off, or "
                 "no python3-dev/python3-pybind11): nothing here can run; test a build with them")
    unittest.main(argv=sys.argv[:1], verbosity=2)
