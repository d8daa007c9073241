"""Fuzzed inputs: parameter, study, calibration-CSV and object files, and the command line.

For any input the result is a valid object (or run) or one ValueError line; never another
exception (a traceback for the user) and never a partial output file. The command line's
long-running work (benchmark, study, calibration, video) is replaced by a stand-in that records
the call, so a valid argument list costs nothing; what is fuzzed is everything up to it.
"""

from __future__ import annotations

import json
import os
import string
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gripper.calibration.measured import read_measured_csv
from gripper.cli.main import main
from gripper.core.params import GripperParams
from gripper.objects.files import object_from_dict
from gripper.studies.study_file import load_study

# CI runs the same examples every time (derandomize); a local run explores new ones.
FUZZ = settings(max_examples=100, deadline=None, derandomize=os.environ.get("CI") == "true",
                suppress_health_check=[HealthCheck.function_scoped_fixture])

# Values a hand-edited file may hold: numbers of every kind, text, flags, lists and tables.
scalars = st.one_of(
    st.integers(-10**6, 10**6), st.floats(allow_nan=True, allow_infinity=True), st.booleans(),
    st.text(string.ascii_letters + string.digits + "_.-:/ ", max_size=12),
)
values = st.recursive(scalars, lambda inner: st.one_of(st.lists(inner, max_size=4),
                                                         st.dictionaries(st.text(string.ascii_lowercase, min_size=1,
                                                                                 max_size=6), inner, max_size=3)),
                      max_leaves=6)


def _one_line_error(fn, *args, **kwargs):
    """Call ``fn``; a ValueError is allowed if it is one line. Anything else fails the test."""
    try:
        return fn(*args, **kwargs)
    except ValueError as e:
        assert "\n" not in str(e) and str(e), repr(str(e))
        return None


def _mix(real: dict) -> st.SearchStrategy:
    """Tables that start from the real sections and their own keys, with fuzzed values, an
    unknown key or section now and then, or a section that is not a table."""
    def table(sec):
        keys = list(real[sec]) if isinstance(real[sec], dict) else []
        return st.dictionaries(st.sampled_from([*keys, "bogus"]) if keys else st.just("bogus"), values,
                               min_size=1, max_size=4)

    section = st.sampled_from([*real, "bogus"]).flatmap(
        lambda sec: st.tuples(st.just(sec), table(sec) if sec in real else values))
    return st.lists(section, max_size=4).map(dict)


PARAMS = GripperParams().to_dict()


@FUZZ
@given(data=_mix(PARAMS))
def test_parameter_files(data):
    p = _one_line_error(GripperParams.from_dict, data)
    if p is not None:
        p.validate()


OBJECT = {"object": {"name": "x", "kind": "rigid_box", "size": [0.02, 0.02, 0.03], "mass": 0.06, "friction": 0.6,
                     "yaw_symmetric": False, "close_command": 3.0, "mesh": "a.stl", "density": 600.0},
          "damage": {"criterion": "contact_force", "limit": 50.0},
          "material": {"youngs_modulus": 1e6, "thickness": 1e-4, "yield_strain": 0.01},
          "reasons": {"mass": "weighed"}}


@FUZZ
@given(data=_mix(OBJECT), kind=st.sampled_from(["rigid_box", "rigid_cylinder", "mesh", "balloon", "paper_box",
                                                "bag", "jelly"]))
def test_object_files(data, kind):
    if isinstance(data.get("object"), dict):
        data["object"].setdefault("kind", kind)
    _one_line_error(object_from_dict, data, where="object file fuzz.toml")


def _toml(data: dict) -> str:
    """A TOML text of ``data`` (tables of scalars, lists and inline tables)."""
    def val(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, float) and v != v:
            return "nan"
        if isinstance(v, float) and v in (float("inf"), float("-inf")):
            return "inf" if v > 0 else "-inf"
        if isinstance(v, int | float):
            return repr(v)
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, list):
            return "[" + ", ".join(val(x) for x in v) + "]"
        return "{ " + ", ".join(f"{json.dumps(k)} = {val(x)}" for k, x in v.items()) + " }"
    out = []
    for sec, table in data.items():
        if isinstance(table, dict):
            out.append(f"[{sec}]")
            out += [f"{json.dumps(k)} = {val(v)}" for k, v in table.items()]
        else:
            out.insert(0, f"{json.dumps(sec)} = {val(table)}")
    return "\n".join(out) + "\n"


STUDY = {"study": {"name": "s", "design": "one_at_a_time", "seed": 0, "points": 4, "base": "p.toml"},
         "vary": {"finger.cut_angle_deg": [40.0, 50.0], "material.shore_a": [15.0]},
         "responses": {"bending": {"r_max": 0.4}, "grasp": {"objects": ["block"], "trials": 1}},
         "objective": {"minimize": "tension_for_angle_N", "at_least": {"grasp_block_success_rate": 1.0}}}


@FUZZ
@given(data=_mix(STUDY))
def test_study_files(tmp_path, data):
    f = tmp_path / "study.toml"
    f.write_text(_toml(data))
    _one_line_error(load_study, f)


csv_cells = st.one_of(st.sampled_from(["tension_N", "angle_B2_deg", "angle_B3_deg", "tip_x_m", "tip_z_m", "r"]),
                      st.floats(allow_nan=True, allow_infinity=True).map(repr), st.text("0123456789.-e#x", max_size=6))


@FUZZ
@given(rows=st.lists(st.lists(csv_cells, min_size=1, max_size=4), min_size=0, max_size=6))
def test_calibration_csv(tmp_path, rows):
    f = tmp_path / "bench.csv"
    f.write_text("\n".join(",".join(r) for r in rows) + "\n")
    _one_line_error(read_measured_csv, f, 6, min_points=1, closure_angle_deg=42.7)


# --- the command line -------------------------------------------------------------------------

CALLED: list[str] = []


@pytest.fixture
def stand_ins(monkeypatch):
    """The long-running entry points, replaced by stand-ins that check nothing and return at once."""
    import gripper.bench.benchmark as bench
    import gripper.calibration.pipeline as pipeline
    import gripper.render.video as video
    import gripper.studies.study as study

    def fake(name, result):
        def f(*a, **k):
            CALLED.append(name)
            if isinstance(result, Exception):
                raise result
            return result
        return f

    summary = {"objects": {}, "config_hash": "0", "versions": {}, "wall_time_s": 0.0}
    monkeypatch.setattr(bench, "run_benchmark", fake("bench", summary))
    monkeypatch.setattr(bench, "format_table", lambda s: "")
    def fake_study(st_, out, **_):  # writes what the command prints back: recommendations.md
        CALLED.append("study")
        Path(out).mkdir(parents=True, exist_ok=True)
        (Path(out) / "recommendations.md").write_text("stand-in\n")
        return []

    monkeypatch.setattr(study, "run_study", fake_study)
    monkeypatch.setattr(pipeline, "calibrate", fake("calibrate", ValueError("stand-in: not run")))
    monkeypatch.setattr(video, "record_trial_video", fake("video", ValueError("stand-in: not run")))
    import gripper.experiments.crush as crush
    import gripper.experiments.pullout as pullout
    import gripper.experiments.smoke as smoke
    import gripper.studies.envelope as envelope

    for module, name in ((envelope, "run_envelope"), (smoke, "random_control_rollout"),
                         (crush, "crush_test"), (pullout, "run_pullout")):
        monkeypatch.setattr(module, name, fake(name, ValueError("stand-in: not run")))


FLAGS = {
    "bench": ["--objects", "--trials", "--seed", "--workers", "--noise", "--mass-noise", "--friction-noise",
              "--close-scale", "--params", "--springs", "--calibration", "--out", "--plot"],
    "params": ["--out", "--params", "--springs", "--calibration"],
    "study": ["--workers", "--out"],
    "calibrate": ["--reference", "--reading", "--tension-max", "--levels", "--held-out", "--mesh-scale", "--out"],
    "video": ["--object", "--out", "--camera", "--width", "--height", "--fps", "--seed", "--index", "--still"],
    "envelope": ["--out", "--sizes", "--masses", "--frictions", "--shapes", "--trials", "--seed", "--grip-tension"],
    "check": ["--duration", "--seed", "--params"],
    "crush": ["--objects", "--depth", "--speed", "--hold"],
    "pullout": ["--objects", "--rate", "--max-force", "--grip-tension", "--grip-pressure", "--policy"],
}
arg_values = st.one_of(st.sampled_from(["block", "balloon,block", "block,block", "mesh:nowhere.stl", "mesh:x::abc",
                                        "nope", "0", "-1", "2", "1e9", "1e400", "nan", "inf", "", "paper", "fmbs",
                                        "front", "x.png", "OUT", "OUT/sub", "FILE", "one_at_a_time", "sphere",
                                        "0.03,0.03", "/proc/none/x", "x" * 300, "../../etc/evil"]),
                       st.text(string.ascii_letters + string.digits + ".,:-_/", max_size=8))


@FUZZ
@given(command=st.sampled_from(sorted(FLAGS)), data=st.data())
def test_command_line(stand_ins, tmp_path, command, data, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)  # relative output names land in the test's folder
    flags = data.draw(st.lists(st.sampled_from(FLAGS[command]), max_size=4, unique=True))
    argv = [command]
    if command == "study":
        argv.append(data.draw(arg_values))
    for flag in flags:
        v = data.draw(arg_values)
        v = v.replace("OUT", str(tmp_path / "out")).replace("FILE", str(tmp_path / "file.txt"))
        argv += [flag, v]
    (tmp_path / "file.txt").write_text("not a parameter file")
    before = sorted(p for p in tmp_path.rglob("*"))
    try:
        rc = main(argv)
    except SystemExit as e:  # argparse's own usage errors: exit 2 with its message
        rc = e.code
    except ValueError as e:  # a stand-in said "not run": the input got through every check
        assert str(e) == "stand-in: not run", e
        rc = 0
    err = capsys.readouterr().err.strip().splitlines()
    assert rc in (0, 2), (argv, rc, err)
    if rc == 2 and err and not err[-1].startswith("usage:"):
        assert len([ln for ln in err if "error" in ln]) == 1, (argv, err)
    leftovers = [p for p in tmp_path.rglob("*") if p not in before and p.name.startswith(".")]
    assert not leftovers, leftovers  # no half-written temporary file
    if rc == 2:
        made = [p for p in tmp_path.rglob("*") if p not in before]
        assert not made or command == "params" and all(Path(p).suffix in (".json", ".toml") for p in made), made
