"""swath.classify and swath.plan against the installed `swath` program: the same dicts, the same
files byte for byte, the same messages for bad input (docs/install.md)."""
import json
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import swath

FIELDS = ["share/fields/meadow.geojson", "share/fields/bowtie.geojson",
          "share/fields/orchard.csv", "share/fields/vineyard.kml"]


def files_of(folder):
    """Every file under FOLDER, by relative path, with its bytes."""
    folder = Path(folder)
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file()}


def test_the_module_is_the_installed_one(prefix):
    assert Path(swath.__file__).resolve().is_relative_to(prefix.resolve())
    assert swath.__version__ in subprocess.run([str(prefix / "bin" / "swath"), "--version"],
                                               capture_output=True, text=True).stdout


@pytest.mark.parametrize("field", FIELDS)
def test_classify_gives_the_programs_json(cli, field):
    run = cli(["classify", field, "--json"])
    assert run.returncode == 0, run.stderr
    assert swath.classify(field) == json.loads(run.stdout)


def test_classify_takes_the_programs_options(cli):
    run = cli(["classify", "share/fields/yard-local.csv", "--local", "--json"])
    facts = swath.classify(Path("share/fields/yard-local.csv"), local=True)
    assert facts == json.loads(run.stdout)
    assert facts["area_m2"] == pytest.approx(11400.0)


# Each case: the module's keyword arguments and the same request as the program's options.
PLANS = {
    "basic": ({"camera": "sony-ilce-qx1", "altitude_m": 60},
              ["--camera", "sony-ilce-qx1", "--altitude", "60"]),
    "home-and-flags": ({"camera": "sony-ilce-qx1", "altitude_m": 60.0, "home": (47.3965, 8.5405),
                        "side_overlap": 0.8, "land": True, "crosshatch": False, "litchi": True},
                       ["--camera", "sony-ilce-qx1", "--altitude", "60", "--home", "47.3965,8.5405",
                        "--side-overlap", "0.8", "--land", "--litchi"]),
    "fleet-region": ({"camera": "sony-ilce-qx1", "gsd_cm": 2.0,
                      "fleet": "share/fleets/three-quads.yaml", "division": "region",
                      "balance": "makespan", "fence_files": True},
                     ["--camera", "sony-ilce-qx1", "--gsd", "2", "--fleet",
                      "share/fleets/three-quads.yaml", "--division", "region", "--balance",
                      "makespan", "--fence-files"]),
    "zones-and-lists": ({"camera": "sony-ilce-qx1", "altitude_m": 60,
                         "exclude": ["share/zones/meadow-mast.geojson",
                                     "share/zones/meadow-pond.geojson"],
                         "clearance": 8, "energy_plan": "meadow.stages",
                         "energy_computation": [(2, 10), (32, 448)], "render": True,
                         "size": "400x300"},
                        ["--camera", "sony-ilce-qx1", "--altitude", "60", "--exclude",
                         "share/zones/meadow-mast.geojson", "--exclude",
                         "share/zones/meadow-pond.geojson", "--clearance", "8", "--energy-plan",
                         "meadow.stages", "--energy-computation", "2,10", "--energy-computation",
                         "32,448", "--render", "--size", "400x300"]),
}


@pytest.mark.parametrize("case", sorted(PLANS))
def test_plan_writes_the_programs_files(cli, tmp_path, case):
    kwargs, options = PLANS[case]
    field = "share/fields/meadow.geojson"
    run = cli(["plan", field, *options, "-o", tmp_path / "cli"])
    assert run.returncode == 0, run.stderr
    plan = swath.plan(field, out=tmp_path / "py", **kwargs)
    expected = files_of(tmp_path / "cli")
    assert "summary.json" in expected and len(expected) >= 8
    got = files_of(tmp_path / "py")
    assert sorted(got) == sorted(expected)
    for name in expected:
        assert got[name] == expected[name], name
    # The report and warnings are the program's, with the output folder's name in them.
    assert plan.report == run.stdout.replace(str(tmp_path / "cli"), str(tmp_path / "py"))
    # The written set as summary.json lists it (the hidden manifest of the set aside).
    assert sorted(plan.files) == sorted(n for n in expected if not n.startswith("."))


def test_plan_gives_the_summary_and_each_drones_path_and_photos(tmp_path):
    home = (47.3968, 8.5401)
    plan = swath.plan("share/fields/meadow.geojson", camera="sony-ilce-qx1", altitude_m=60,
                      home=home, drones=2, out=tmp_path)
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert plan.summary == summary
    assert [d.name for d in plan.drones] == [d["name"] for d in summary["drones"]]
    assert [len(d.photos) for d in plan.drones] == [d["photos"] for d in summary["drones"]]
    photos_csv = (tmp_path / "photos.csv").read_text().splitlines()
    assert sum(len(d.photos) for d in plan.drones) == len(photos_csv) - 1
    for drone in plan.drones:
        assert len(drone.photos) > 10
        # Every path leaves from home and comes back to it; the mission starts there too.
        for end in (drone.path[0], drone.path[-1], drone.waypoints[0][:2]):
            assert end == pytest.approx(home, abs=1e-9)
        # Each photo is taken on the path: on one of its legs, to within a centimetre.
        for photo in drone.photos:
            assert photo[2] == pytest.approx(60.0)
            assert distance_to_path_m(photo[:2], drone.path) < 0.01


def distance_to_path_m(point, path):
    """The distance from POINT to the polyline PATH, all (lat, lon), in a local flat frame
    (metres; the area spans under a kilometre)."""
    lat0 = math.radians(point[0])
    def xy(p):
        return (math.radians(p[1]) * math.cos(lat0) * 6371008.8, math.radians(p[0]) * 6371008.8)
    px, py = xy(point)
    best = math.inf
    for a, b in zip(path, path[1:]):
        (ax, ay), (bx, by) = xy(a), xy(b)
        dx, dy = bx - ax, by - ay
        t = 0.0 if dx == dy == 0 else max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) /
                                                    (dx * dx + dy * dy)))
        best = min(best, math.hypot(px - ax - t * dx, py - ay - t * dy))
    return best


BAD = {
    "missing-field": ("share/fields/no-such-field.geojson", {"camera": "sony-ilce-qx1",
                                                            "altitude_m": 60},
                      ["--camera", "sony-ilce-qx1", "--altitude", "60"]),
    "unknown-camera": ("share/fields/meadow.geojson", {"camera": "no-such-camera",
                                                      "altitude_m": 60},
                       ["--camera", "no-such-camera", "--altitude", "60"]),
    "home-out-of-range": ("share/fields/meadow.geojson", {"camera": "sony-ilce-qx1",
                                                          "altitude_m": 60, "home": (95, 8)},
                          ["--camera", "sony-ilce-qx1", "--altitude", "60", "--home", "95,8"]),
    "not-a-number": ("share/fields/meadow.geojson", {"camera": "sony-ilce-qx1",
                                                     "altitude_m": "sixty"},
                     ["--camera", "sony-ilce-qx1", "--altitude", "sixty"]),
    "not-a-choice": ("share/fields/meadow.geojson", {"camera": "sony-ilce-qx1", "altitude_m": 60,
                                                     "division": "diagonal", "drones": 2},
                     ["--camera", "sony-ilce-qx1", "--altitude", "60", "--division", "diagonal",
                      "--drones", "2"]),
    "crossing-area": ("share/fields/bowtie.geojson", {"camera": "sony-ilce-qx1",
                                                      "altitude_m": 60},
                      ["--camera", "sony-ilce-qx1", "--altitude", "60"]),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_input_raises_the_programs_sentence(cli, tmp_path, case):
    field, kwargs, options = BAD[case]
    run = cli(["plan", field, *options, "-o", tmp_path / "out"])
    assert run.returncode == 2
    with pytest.raises(swath.InputError) as error:
        swath.plan(field, out=tmp_path / "out", **kwargs)
    assert str(error.value) == run.stderr.rstrip("\n")
    assert str(error.value).startswith("swath")
    assert not (tmp_path / "out").exists()


def test_classify_bad_input(cli):
    run = cli(["classify", "share/fields/no-such-field.geojson", "--json"])
    assert run.returncode == 2
    with pytest.raises(swath.InputError) as error:
        swath.classify("share/fields/no-such-field.geojson")
    assert str(error.value) == run.stderr.rstrip("\n")


def test_a_keyword_that_is_no_option_is_refused(tmp_path):
    with pytest.raises(swath.InputError, match="--no-such-option"):
        swath.plan("share/fields/meadow.geojson", camera="sony-ilce-qx1", altitude_m=60,
                   no_such_option=3, out=tmp_path)
    with pytest.raises(swath.InputError, match="--render is a flag"):
        swath.plan("share/fields/meadow.geojson", camera="sony-ilce-qx1", altitude_m=60,
                   render="yes", out=tmp_path)
    assert not any(tmp_path.iterdir())


def moved_copy(prefix, root):
    """The installed program, module and data copied to another prefix, with one more camera in
    its data: found there only if the copy looks for its data from where it is."""
    for part in ["bin/swath", "share/swath", "lib/swath", "lib/python3"]:
        source = prefix / part
        if source.is_dir():
            shutil.copytree(source, root / part, symlinks=True)
        else:
            (root / part).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, root / part)
    camera = (prefix / "share/swath/cameras/sony-ilce-qx1.yaml").read_text()
    (root / "share/swath/cameras/moved-test-camera.yaml").write_text(
        camera.replace("Sony ILCE-QX1", "Moved Test Camera"))
    env = {k: v for k, v in os.environ.items() if not k.startswith("SWATH_")}
    env["PYTHONPATH"] = str(root / "lib/python3/dist-packages")
    return env


def test_a_moved_tree_finds_its_own_data(prefix, tmp_path):
    root = tmp_path / "moved"
    env = moved_copy(prefix, root)
    listed = subprocess.run([str(root / "bin/swath"), "cameras"], capture_output=True, text=True,
                            env=env)
    assert listed.returncode == 0, listed.stderr
    assert "moved-test-camera" in listed.stdout
    script = ("import swath, sys; p = swath.plan('share/fields/meadow.geojson', "
              "camera='moved-test-camera', altitude_m=60, out=sys.argv[1]); "
              "print(p.report)")
    run = subprocess.run([sys.executable, "-c", script, str(tmp_path / "out")],
                         capture_output=True, text=True, env=env)
    assert run.returncode == 0, run.stderr
    assert "Moved Test Camera" in run.stdout


def test_a_moved_tree_draws_with_its_own_module(prefix, tmp_path):
    """coverage.png is drawn by the moved tree's libswath_draw.so, in the program (the
    loader's own trace says which file it opened) and in the module (the process's mappings)."""
    root = tmp_path / "moved"
    env = moved_copy(prefix, root)
    module = str(root / "lib/swath/libswath_draw.so")
    run = subprocess.run([str(root / "bin/swath"), "plan", "share/fields/meadow.geojson",
                          "--camera", "sony-ilce-qx1", "--altitude", "60", "--render", "--size",
                          "200x150", "-o", str(tmp_path / "cli")],
                         capture_output=True, text=True, env={**env, "LD_DEBUG": "files"})
    assert run.returncode == 0, run.stderr
    opened = [line for line in run.stderr.splitlines()
              if "libswath_draw.so" in line and "file=" in line]
    assert opened and all(module in line for line in opened), opened
    script = ("import swath, sys; swath.plan('share/fields/meadow.geojson', camera='sony-ilce-qx1',"
              " altitude_m=60, render=True, size='200x150', out=sys.argv[1]); "
              "print(''.join(l for l in open('/proc/self/maps') if 'libswath_draw' in l))")
    run = subprocess.run([sys.executable, "-c", script, str(tmp_path / "py")],
                         capture_output=True, text=True, env=env)
    assert run.returncode == 0, run.stderr
    mapped = {line.split()[-1] for line in run.stdout.splitlines() if line.strip()}
    assert mapped == {module}
    assert (tmp_path / "py/coverage.png").read_bytes() == (tmp_path / "cli/coverage.png").read_bytes()


def test_swath_share_dir_overrides_the_installed_data(prefix, tmp_path):
    """SWATH_SHARE_DIR wins over the installed tree, for the program and for the module."""
    share = tmp_path / "share"
    shutil.copytree(prefix / "share/swath", share)
    camera = (share / "cameras/sony-ilce-qx1.yaml").read_text()
    (share / "cameras/override-test-camera.yaml").write_text(
        camera.replace("Sony ILCE-QX1", "Override Test Camera"))
    env = {**os.environ, "SWATH_SHARE_DIR": str(share)}
    listed = subprocess.run([str(prefix / "bin/swath"), "cameras"], capture_output=True,
                            text=True, env=env)
    assert "override-test-camera" in listed.stdout
    script = ("import swath, sys; print(swath.plan('share/fields/meadow.geojson', "
              "camera='override-test-camera', altitude_m=60, out=sys.argv[1]).report)")
    run = subprocess.run([sys.executable, "-c", script, str(tmp_path / "out")],
                         capture_output=True, text=True, env=env)
    assert run.returncode == 0, run.stderr
    assert "Override Test Camera" in run.stdout
