"""What python_apps_test.py and robustness_test.py share: a run's files read back, and a test
case that keeps each test's runs and apps in a directory of its own, removed after it."""
import json
import os
import subprocess
import tempfile
import unittest


def events(out):
    """The run's events.jsonl, one dict per line."""
    with open(os.path.join(out, "events.jsonl")) as f:
        return [json.loads(line) for line in f]


def summary(out):
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


class RunsInTemporaryDirectory(unittest.TestCase):
    """FLEET: the swath-fleet program, set by the test script from its command line."""
    FLEET = None

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)

    def out(self, name):
        return os.path.join(self.tmp.name, name)

    def app(self, name, text):
        """An app file `name` (a path under the test's directory) holding `text`."""
        path = self.out(name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write(text)
        return path

    def check_passes(self, out):
        c = subprocess.run([self.FLEET, "check", out], capture_output=True, text=True)
        self.assertEqual(c.returncode, 0, c.stdout + c.stderr)

    def failed_reasons(self, out):
        return [e.get("reason", "") for e in events(out) if e["ev"] == "task_failed"]
