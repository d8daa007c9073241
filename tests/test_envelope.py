"""The capability envelope: same records at 1 and 2 workers, resume after SIGKILL, refusal of
bad specs before any work, and the derived gripping range and payload."""

import json
import subprocess
import sys

import pytest
from helpers import kill_after_lines, run_into_fresh_folder

from gripper.cli.main import main
from gripper.studies.envelope import Envelope, envelope_object, load_envelope, summarize

SPEC = """[envelope]
shapes = ["sphere", "box"]
sizes = [0.045, 0.11]
masses = [0.05]
trials = 2
seed = 3
"""


@pytest.fixture(scope="module")
def ref_run(tmp_path_factory):
    """(the spec file, the folder of its run at 1 worker)."""
    return run_into_fresh_folder(tmp_path_factory, ["envelope"], text=SPEC, filename="small.toml")


def _records(out):
    return [{k: v for k, v in json.loads(line).items() if k != "wall_time_s"}
            for line in (out / "trials.jsonl").read_text().splitlines()]


def test_outputs_and_two_workers_give_the_same_records(ref_run, tmp_path):
    spec, reference = ref_run
    for name in ("envelope.csv", "summary.json", "map_sphere.png", "map_box.png"):
        assert (reference / name).is_file(), name
    rows = (reference / "envelope.csv").read_text().splitlines()
    assert len(rows) == 1 + 2 * 2 * 1 * 2  # header + shapes x sizes x masses x trials
    out = tmp_path / "w2"
    assert main(["envelope", str(spec), "--workers", "2", "--no-progress", "--out", str(out)]) == 0
    assert _records(out) == _records(reference)
    assert all(r["warnings"] == 0 and r["status"] == "ok" for r in _records(out))


def test_sigkill_then_resume_loses_and_repeats_nothing(ref_run, tmp_path):
    spec, reference = ref_run
    out = tmp_path / "killed"
    cmd = [sys.executable, "-m", "gripper.cli.main", "envelope", str(spec), "--workers", "1", "--no-progress",
           "--out", str(out)]
    n = kill_after_lines(cmd, out / "trials.jsonl", 3)
    assert 3 <= n < 8
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    recs = _records(out)
    assert [(r["point"], r["index"]) for r in recs] == [(k, i) for k in range(4) for i in range(2)]
    assert recs == _records(reference)


@pytest.mark.parametrize("line, key", [
    ('shapes = ["cone"]', "envelope.shapes"),
    ("sizes = [0.02, -0.01]", "envelope.sizes"),
    ("masses = []", "envelope.masses"),
    ("trials = 0", "envelope.trials"),
    ("grip_tension = 80.0", "envelope.grip_tension"),
    ("colour = 1", "envelope.colour"),
])
def test_a_bad_spec_is_refused_before_any_work(line, key, tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text(f"[envelope]\n{line}\n")
    out = tmp_path / "out"
    assert main(["envelope", str(path), "--no-progress", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and key in err[0], err
    assert not out.exists()


def test_the_shipped_envelope_meets_the_issues_size():
    env = load_envelope("default")
    assert len(env.shapes) >= 3 and len(env.sizes) >= 8 and len(env.masses) >= 5 and env.trials >= 3
    assert min(env.sizes) < 0.5 * 0.080 < 0.080 < max(env.sizes)  # well below to above the opening


def test_envelope_objects_are_the_sizes_asked_for():
    s = envelope_object("sphere", 0.03, 0.2, 0.6)
    assert s.kind == "rigid_sphere" and s.size == (0.015,) * 3 and s.mass == 0.2 and s.yaw_symmetric
    b = envelope_object("box", 0.11, 1.0, 0.4)
    assert b.kind == "rigid_box" and b.size[:2] == (0.055, 0.055) and not b.yaw_symmetric and b.oversize


def test_gripping_range_and_payload_from_the_held_points():
    """Held: at least 2 of 3 trials. Range: the held sizes at the lightest mass; payload: the
    heaviest mass held at any size."""
    env = Envelope(shapes=("cylinder",), sizes=(0.02, 0.04, 0.06), masses=(0.1, 0.5), trials=3)
    wins = {(0.02, 0.1): 1, (0.04, 0.1): 2, (0.06, 0.1): 3, (0.02, 0.5): 0, (0.04, 0.5): 3, (0.06, 0.5): 1}
    records = []
    for k, (_, w, m, _) in enumerate(env.points()):
        for i in range(3):
            records.append({"point": k, "index": i, "status": "ok", "success": i < wins[(w, m)], "warnings": 0})
    s = summarize(records, env)["shapes"]["cylinder"]
    assert s["gripping_range_m"] == [0.04, 0.06]
    assert s["payload_kg"] == 0.5


def test_flags_replace_the_files_keys(tmp_path, capsys):
    out = tmp_path / "flags"
    assert main(["envelope", "--shapes", "box", "--sizes", "0.045", "--masses", "0.05", "--trials", "1",
                 "--frictions", "0.6", "--workers", "1", "--no-progress", "--out", str(out)]) == 0
    rows = (out / "envelope.csv").read_text().splitlines()
    assert len(rows) == 2 and rows[1].startswith("box,0.045,0.05,0.6,0,ok,")
    assert "gripping range" in capsys.readouterr().out
