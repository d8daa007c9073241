"""Run folders have one writer and one command (a start on issue 46): a second run into a folder
that a run is writing is refused in one line, and a command refuses another command's folder."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

GRIPPER = [sys.executable, "-m", "gripper.cli.main"]


def _cli(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([*GRIPPER, *args], cwd=cwd, capture_output=True, text=True, timeout=600,
                          stdin=subprocess.DEVNULL)


def test_a_second_writer_is_refused_and_nothing_is_duplicated(tmp_path):
    bench = ["bench", "--objects", "block", "--trials", "4", "--workers", "1", "--no-progress", "--out", "run"]
    first = subprocess.Popen([*GRIPPER, *bench], cwd=tmp_path, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                             text=True, stdin=subprocess.DEVNULL)
    try:
        lock = tmp_path / "run" / ".lock"
        deadline = time.monotonic() + 120
        while not (lock.is_file() and lock.read_text().strip() == str(first.pid)):  # the first holds it
            assert first.poll() is None and time.monotonic() < deadline, first.stderr.read() if first.stderr else ""
            time.sleep(0.05)
        second = _cli(*bench, cwd=tmp_path)
        assert second.returncode == 2
        lines = second.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].endswith(
            f"--out: run is being written by another run (process {first.pid}); wait for it to end, "
            "or choose another --out folder"), lines
    finally:
        assert first.wait(timeout=600) == 0
    records = [json.loads(line) for line in (tmp_path / "run" / "trials.jsonl").read_text().splitlines()]
    assert sorted(r["index"] for r in records) == [0, 1, 2, 3]  # each trial once
    # the lock is the OS's: free again once its holder has ended, so the run resumes
    again = _cli(*bench, cwd=tmp_path)
    assert again.returncode == 0, again.stderr


def test_a_command_refuses_another_commands_folder(tmp_path):
    (tmp_path / "run").mkdir()
    (tmp_path / "run" / "config.json").write_text(json.dumps({"config_hash": "0"}))
    before = sorted(os.listdir(tmp_path / "run"))
    done = _cli("envelope", "--shapes", "box", "--sizes", "0.04", "--masses", "0.05", "--frictions", "0.6",
                "--trials", "1", "--no-progress", "--out", "run", cwd=tmp_path)
    assert done.returncode == 2
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].endswith(
        "--out: run holds a benchmark's run (config.json); choose another --out folder"), lines
    assert sorted(os.listdir(tmp_path / "run")) == before  # nothing written


def _bench(tmp_path: Path, out: str, seed: int, trials: int = 2) -> subprocess.CompletedProcess:
    return _cli("bench", "--objects", "block", "--trials", str(trials), "--seed", str(seed), "--workers", "1",
                "--no-progress", "--out", out, cwd=tmp_path)


def test_a_folder_of_mixed_runs_is_refused_and_left_as_it_was(tmp_path):
    """Records are checked against the run's configuration on resume: a record of another seed
    appended by hand, the same trial twice, or a folder whose config.json was removed and rerun
    with another seed are each refused in one line naming the record; nothing is written."""
    assert _bench(tmp_path, "s0", 0).returncode == 0
    assert _bench(tmp_path, "s1", 1, trials=1).returncode == 0
    trials = tmp_path / "s0" / "trials.jsonl"
    own = trials.read_text()
    foreign = (tmp_path / "s1" / "trials.jsonl").read_text()
    cases = {
        "another seed's record appended": (own + foreign, None, 0,
                                           "record 3 (trial block-1-0000) belongs to another run"),
        "a trial twice": (own + own.splitlines(True)[0], None, 0, "record 3 repeats trial block-0-0000"),
        "config.json removed, rerun with another seed": (own, "remove", 1,
                                                         "record 1 (trial block-0-0000) belongs to another run"),
    }
    config = (tmp_path / "s0" / "config.json").read_text()
    summary = (tmp_path / "s0" / "summary.json").read_text()
    for name, (text, config_action, seed, message) in cases.items():
        trials.write_text(text)
        (tmp_path / "s0" / "config.json").write_text(config)
        if config_action == "remove":
            (tmp_path / "s0" / "config.json").unlink()
        done = _bench(tmp_path, "s0", seed)
        lines = done.stderr.strip().splitlines()
        assert done.returncode == 2 and len(lines) == 1 and message in lines[0], (name, lines)
        assert trials.read_text() == text, name  # no record lost, none added
        assert (tmp_path / "s0" / "summary.json").read_text() == summary, name  # no summary of a mixed file
        assert (tmp_path / "s0" / "config.json").exists() == (config_action is None), name  # none written


def test_a_folder_without_its_config_resumes_its_own_run_and_the_summary_counts_it_once(tmp_path):
    """config.json removed: the same configuration resumes (the records are its own, each
    once) and its summary counts exactly this run's trials; summarize() itself refuses a record of
    another configuration, so no summary can count one."""
    import pytest

    from gripper.bench.benchmark import BenchConfig, summarize
    assert _bench(tmp_path, "s0", 0, trials=2).returncode == 0
    assert _bench(tmp_path, "s1", 1, trials=1).returncode == 0
    (tmp_path / "s0" / "config.json").unlink()
    again = _bench(tmp_path, "s0", 0, trials=3)  # one more trial of the same configuration
    assert again.returncode == 0, again.stderr
    records = [json.loads(x) for x in (tmp_path / "s0" / "trials.jsonl").read_text().splitlines()]
    assert [r["index"] for r in records] == [0, 1, 2] and {r["seed"] for r in records} == {0}
    summary = json.loads((tmp_path / "s0" / "summary.json").read_text())
    assert summary["objects"]["block"]["trials"] == 3
    cfg = BenchConfig(objects=("block",), trials=3, seed=0).validate()
    assert {r["run_config_hash"] for r in records} == {cfg.hash()}
    foreign = json.loads((tmp_path / "s1" / "trials.jsonl").read_text().splitlines()[0])
    with pytest.raises(ValueError, match=r"record 4 \(block-1-0000\) belongs to another run"):
        summarize([*records, foreign], cfg)


def test_a_study_folder_with_a_foreign_record_is_refused(tmp_path):
    study = tmp_path / "s.toml"
    study.write_text('[study]\nname = "t"\n[vary]\n"finger.hole_height" = [0.011]\n'
                     '[responses]\ntension_for_angle = { angle_deg = 60.0 }\n')
    run = ["study", "s.toml", "--out", "st", "--workers", "1", "--no-progress"]
    assert _cli(*run, cwd=tmp_path).returncode == 0
    results = tmp_path / "st" / "results.jsonl"
    own = results.read_text()
    for text, message in ((own + own.splitlines(True)[0], "record 3 repeats point 0"),
                          (own.replace('"run_config_hash": "', '"run_config_hash": "0'), "belongs to another run")):
        results.write_text(text)
        done = _cli(*run, cwd=tmp_path)
        lines = done.stderr.strip().splitlines()
        assert done.returncode == 2 and len(lines) == 1 and message in lines[0], lines
        assert results.read_text() == text
