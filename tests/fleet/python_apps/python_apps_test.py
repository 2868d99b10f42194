#!/usr/bin/python3
"""swath-fleet's Python apps (docs/swath-fleet.md "Apps in Python"), end to end through the program.

python_apps_test.py SWATH_FLEET SOURCE_DIR: tasks, futures and cancellation checked by
`swath-fleet check` and parsed back from events.jsonl; the same seed gives the same bytes
whatever the Python threads' timing (random sleeps, runs side by side); a Python exception is one
sentence naming the file and line; the case studies in share/apps/ give the C++ apps' events.
"""
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
import unittest
from concurrent.futures import ThreadPoolExecutor

FLEET, SOURCE = sys.argv[1], sys.argv[2]
HERE = os.path.join(SOURCE, "tests", "fleet", "python_apps")
APPS = os.path.join(SOURCE, "share", "apps")


def run(app, world, out, *extra):
    return subprocess.run([FLEET, "run", app, "--world", world, "-o", out, *extra],
                          capture_output=True, text=True)


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


def events(out):
    with open(os.path.join(out, "events.jsonl")) as f:
        return [json.loads(line) for line in f]


class PythonApps(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)

    def out(self, name):
        return os.path.join(self.tmp.name, name)

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


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
