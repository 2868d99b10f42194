"""swath-fleet's Python apps in the installed tree (docs/swath-fleet.md "Apps in Python"): the
case studies of share/swath/apps give the built-in apps' events.jsonl byte for byte, and an app
with tasks, futures and cancellation passes `swath-fleet check`."""
import json
import subprocess

import pytest

from conftest import SOURCE

CASES = [("road", "road", "3"), ("wifi", "rf_field", "2"), ("hotspot", "hotspot", "4"),
         ("multiplexing", "sites", "2"), ("tracking", "tracking", "3")]


def fleet(prefix, *args):
    return subprocess.run([str(prefix / "bin" / "swath-fleet")] + [str(a) for a in args],
                          capture_output=True, text=True)


@pytest.mark.parametrize("name,world,drones", CASES)
def test_python_case_study_gives_the_builtin_apps_events(prefix, tmp_path, name, world, drones):
    app = prefix / "share" / "swath" / "apps" / (name + ".py")
    assert app.is_file()
    for seed in ("3", "4"):
        runs = {}
        for label, which in (("cpp", name), ("py", app)):
            out = tmp_path / f"{label}-{seed}"
            r = fleet(prefix, "run", which, "--world", world, "--drones", drones, "--seed", seed,
                      "-o", out)
            assert r.returncode == 0, r.stderr
            runs[label] = (out / "events.jsonl").read_bytes()
        assert len(runs["cpp"]) > 1000
        assert runs["py"] == runs["cpp"], f"{name} seed {seed}"


def test_python_app_with_tasks_futures_and_cancellation(prefix, tmp_path):
    app = SOURCE / "tests" / "fleet" / "python_apps" / "tasks_app.py"
    out = tmp_path / "run"
    r = fleet(prefix, "run", app, "--world", "sites", "--drones", "3", "-o", out)
    assert r.returncode == 0, r.stderr
    c = fleet(prefix, "check", out)
    assert c.returncode == 0, c.stdout + c.stderr
    events = [json.loads(line) for line in (out / "events.jsonl").read_text().splitlines()]
    assert sum(e["ev"] == "task_cancelled" for e in events) == 1
    metrics = json.loads((out / "summary.json").read_text())["app_metrics"]
    assert metrics["cancel_seen"] == 1 and metrics["parcel_dropped"] == 1
