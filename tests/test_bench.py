"""Benchmark runner: files, resume, refusal of a changed configuration, bad input, workers,
and a SIGKILL in the middle of a run."""

import json
import subprocess
import sys
import time

import pytest
from helpers import kill_after_lines

from gripper.cli.main import main

BASE = ["bench", "--objects", "block", "--seed", "7", "--no-progress"]


def _lines(path):
    return [json.loads(x) for x in (path / "trials.jsonl").read_text().splitlines()]


def _strip(recs):
    return [{k: v for k, v in r.items() if k != "wall_time_s"} for r in recs]


def _summary(path):
    s = json.loads((path / "summary.json").read_text())
    s.pop("wall_time_s"), s.pop("resumed")  # of this call, not of the results
    for o in s["objects"].values():
        o.pop("mean_wall_time_s")
    return s


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("ref")
    assert main([*BASE, "--trials", "4", "--workers", "1", "--out", str(out)]) == 0
    return out


def test_outputs(reference):
    recs = _lines(reference)
    assert [r["index"] for r in recs] == [0, 1, 2, 3]
    s = json.loads((reference / "summary.json").read_text())
    b = s["objects"]["block"]
    for key in ("trials", "successes", "success_rate", "ci95", "damage_rate", "median_peak_force_N",
                "p95_peak_force_N", "mean_wall_time_s"):
        assert key in b
    assert b["trials"] == 4 and b["successes"] == sum(r["success"] for r in recs)
    assert {"config_hash", "versions", "wall_time_s"} <= set(s)
    assert (reference / "summary.csv").read_text().startswith("object,trials")
    assert all(r["warnings"] == 0 for r in recs)


def test_rerun_skips_finished_trials(reference, tmp_path):
    before = (reference / "trials.jsonl").read_bytes()
    t0 = time.perf_counter()
    assert main([*BASE, "--trials", "4", "--workers", "1", "--out", str(reference)]) == 0
    assert time.perf_counter() - t0 < 1.0  # nothing re-simulated (one trial takes about 1 s)
    assert (reference / "trials.jsonl").read_bytes() == before


def test_changed_configuration_is_refused(reference, capsys):
    before = (reference / "trials.jsonl").read_bytes()
    code = main([*BASE, "--trials", "4", "--noise", "0.005", "--out", str(reference)])
    assert code == 2
    err = capsys.readouterr().err
    assert "another configuration" in err and err.count("\n") == 1
    assert (reference / "trials.jsonl").read_bytes() == before


@pytest.mark.parametrize("args, field", [
    (["--objects", "sphere"], "unknown object"),
    (["--trials", "0"], "--trials"),
    (["--noise", "-0.01"], "--noise"),
    (["--objects", "mesh:/nonexistent.stl"], "mesh"),
])
def test_bad_input_exit_2(tmp_path, capsys, args, field):
    out = tmp_path / "run"
    out.mkdir()
    (out / "keep.txt").write_text("data")
    code = main(["bench", "--no-progress", "--out", str(out), *args])
    assert code == 2
    assert field in capsys.readouterr().err
    assert (out / "keep.txt").read_text() == "data"


def test_two_workers_give_the_same_records(reference, tmp_path):
    out = tmp_path / "w2"
    assert main([*BASE, "--trials", "4", "--workers", "2", "--out", str(out)]) == 0
    assert _strip(_lines(out)) == _strip(_lines(reference))


def test_sigkill_then_resume_equals_uninterrupted(reference, tmp_path):
    out = tmp_path / "killed"
    cmd = [sys.executable, "-m", "gripper.cli.main", *BASE, "--trials", "4", "--workers", "1", "--out", str(out)]
    n_before = kill_after_lines(cmd, out / "trials.jsonl", 2)
    assert 2 <= n_before < 4
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    recs = _lines(out)
    assert sorted(r["index"] for r in recs) == [0, 1, 2, 3]  # each trial exactly once
    assert _strip(recs) == _strip(_lines(reference))
    assert _summary(out) == _summary(reference)
