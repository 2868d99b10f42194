"""swath from Python: classify areas and plan camera surveys (docs/install.md).

    import swath
    facts = swath.classify("share/fields/meadow.geojson")         # classify --json, as a dict
    plan = swath.plan("share/fields/meadow.geojson", camera="sony-ilce-qx1", altitude_m=60,
                      out="out", side_overlap=0.8, render=True)  # any `swath plan` option
    plan.summary["coverage"], plan.drones[0].path, plan.drones[0].photos

Both run the `swath` program's own commands in this process: the same options, checks, messages
and files byte for byte. Bad input raises swath.InputError carrying the program's message.
"""

import csv
import json
import os
from dataclasses import dataclass, field as _field
from pathlib import Path

from . import _layout
from . import _swath

__all__ = ["InputError", "Plan", "Drone", "classify", "plan", "__version__"]
__version__ = _swath.version


def _use_installed_tree():
    """Points the C++ code at the installed tree's data and modules (PREFIX/share/swath,
    PREFIX/lib/swath): a program finds them from its own place, a Python process from this
    package's. Settings already in the environment win; the build tree needs none."""
    prefix = (Path(__file__).resolve().parent / _layout.PACKAGE_TO_PREFIX).resolve()
    share = prefix / "share" / "swath"
    if not (share / "cameras").is_dir():
        return
    os.environ.setdefault("SWATH_SHARE_DIR", str(share))
    for variable, name in (("SWATH_GIS_MODULE", "libswath_gis.so"),
                           ("SWATH_RENDER_MODULE", "libswath_draw.so")):
        module = prefix / "lib" / "swath" / name
        if module.is_file():
            os.environ.setdefault(variable, str(module))


_use_installed_tree()


class InputError(ValueError):
    """Bad input or usage: the message is the sentence `swath` prints (exit code 2)."""


@dataclass
class Drone:
    """One drone of a plan: `path` its flight from home back to home as (lat_deg, lon_deg)
    tuples (mission.geojson's path), `waypoints` its mission's positioned items in flight order
    and `photos` its planned photos, as (lat_deg, lon_deg, alt_m) tuples (waypoints.csv,
    photos.csv)."""
    name: str
    path: list = _field(default_factory=list)
    waypoints: list = _field(default_factory=list)
    photos: list = _field(default_factory=list)


@dataclass
class Plan:
    """What `swath plan` wrote into `out`: summary.json as a dict, the drones, the file names in
    the order written, the printed report and the warnings."""
    out: Path
    summary: dict
    drones: list
    files: list
    report: str
    warnings: list


# Parameters named with their unit where the program's option is not.
_UNIT_NAMES = {"altitude_m": "altitude", "gsd_cm": "gsd", "speed_m_s": "speed"}


def _option_text(value):
    """A value as the command line gives it: a pair (LAT, LON) or (LO, HI) as 'a,b'."""
    if isinstance(value, tuple):
        return ",".join(_option_text(v) for v in value)
    if isinstance(value, float):
        return repr(value)
    return os.fspath(value) if isinstance(value, os.PathLike) else str(value)


def _arguments(command, options):
    """Keyword arguments as `swath COMMAND` options, by the program's own list of them: a flag
    for True (nothing for False), a list repeats the option, None leaves it out."""
    known = {name: (takes_value, repeats) for name, takes_value, repeats in _swath.options(command)}
    args = []
    for key, value in options.items():
        if value is None:
            continue
        name = _UNIT_NAMES.get(key, key).replace("_", "-")
        if name not in known:
            raise InputError(f"swath {command}: no option --{name} (from the keyword '{key}'); "
                             f"see swath {command} --help")
        takes_value, repeats = known[name]
        if not takes_value:
            if value is True:
                args.append(f"--{name}")
            elif value is not False:
                raise InputError(f"swath {command}: --{name} is a flag: give True or False")
            continue
        values = value if isinstance(value, list) else [value]
        if len(values) > 1 and not repeats:
            raise InputError(f"swath {command}: --{name} takes one value")
        for v in values:
            args += [f"--{name}", _option_text(v)]
    return args


def _run(args):
    code, out, err = _swath.run(args)
    if code == 2:
        raise InputError(err.rstrip("\n"))
    if code != 0:
        raise RuntimeError(err.rstrip("\n") or f"swath {args[0]}: exit code {code}")
    return out, err


def classify(path, **options):
    """`swath classify PATH --json` (options such as local=True, polygon=2 as for the program):
    the area's type, measures, minimum height and sweep direction as a dict."""
    out, _ = _run(["classify", os.fspath(path), "--json"] + _arguments("classify", options))
    return json.loads(out)


def plan(field, camera=None, altitude_m=None, home=None, out=None, **options):
    """`swath plan FIELD --camera CAMERA --altitude ALTITUDE_M --home LAT,LON -o OUT [options]`:
    every option of the program by its long name with '_' for '-' (True for a flag, a list to
    repeat one, a tuple for a pair); writes the same files as the program and returns a Plan."""
    if out is None:
        raise InputError("swath plan: no output directory: give out=DIR")
    named = {"camera": camera, "altitude_m": altitude_m, "home": home, "output": out}
    if isinstance(home, (list, tuple)):
        named["home"] = tuple(home)
    stdout, stderr = _run(["plan", os.fspath(field)] + _arguments("plan", {**named, **options}))
    return _read_plan(Path(out), stdout, stderr)


def _rows(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def _point(row):
    return (float(row["lat"]), float(row["lon"]), float(row["alt_m"]))


def _read_plan(out, stdout, stderr):
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    drones = [Drone(d["name"]) for d in summary["drones"]]
    by_number = {d["drone"]: drone for d, drone in zip(summary["drones"], drones)}
    mission = json.loads((out / "mission.geojson").read_text(encoding="utf-8"))
    for feature in mission["features"]:
        if feature["properties"].get("role") == "path":
            by_number[feature["properties"]["drone"]].path += [
                (p[1], p[0]) for p in feature["geometry"]["coordinates"]]
    for row in _rows(out / "waypoints.csv"):
        if row["lat"]:  # commands (speed, camera, gimbal, return) have no position
            by_number[int(row["drone"])].waypoints.append(_point(row))
    for row in _rows(out / "photos.csv"):
        by_number[int(row["drone"])].photos.append(_point(row))
    warnings = [line.split(": warning: ", 1)[1] for line in stderr.splitlines()
                if ": warning: " in line]
    return Plan(out, summary, drones, list(summary["files"]), stdout, warnings)
