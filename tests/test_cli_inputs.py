"""Bad output paths and an unreachable scheduler: one line, exit 2, nothing left behind, and
nothing run first."""

from __future__ import annotations

import socket
import subprocess
import sys

import pytest

from gripper.cli.main import main

COMMANDS = {
    "bench": ["bench", "--objects", "block", "--trials", "1", "--no-progress"],
    "study": ["study", "one_at_a_time", "--no-progress"],
    "calibrate": ["calibrate", "--no-converge"],
    "write-models": ["write-models"],
    "params": ["params"],
}


def _closed_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]  # closed again on exit: nothing listens there


def _run(argv, capsys):
    rc = main(argv)
    err = capsys.readouterr().err.strip().splitlines()
    return rc, err


def _tree(path):
    return sorted(p.relative_to(path) for p in path.rglob("*"))


@pytest.mark.parametrize("command", COMMANDS)
def test_out_is_an_existing_file(command, tmp_path, capsys):
    target = tmp_path / ("p.json" if command == "params" else "taken")
    if command == "params":
        target.mkdir()  # a folder where the file should go
    else:
        target.write_text("precious")
    before = _tree(tmp_path)
    rc, err = _run([*COMMANDS[command], "--out", str(target)], capsys)
    assert rc == 2 and len(err) == 1 and "--out" in err[0], err
    assert _tree(tmp_path) == before
    if command != "params":
        assert target.read_text() == "precious"


@pytest.mark.parametrize("command", COMMANDS)
def test_out_cannot_be_created(command, tmp_path, capsys):
    blocker = tmp_path / "a_file"
    blocker.write_text("x")
    target = blocker / "sub" / ("p.toml" if command == "params" else "run")
    rc, err = _run([*COMMANDS[command], "--out", str(target)], capsys)
    assert rc == 2 and len(err) == 1 and "--out" in err[0], err
    assert _tree(tmp_path) == [blocker.relative_to(tmp_path)]


@pytest.mark.parametrize("command", ["bench", "study"])
def test_unreachable_scheduler_is_refused_before_any_work(command, tmp_path, capsys):
    out = tmp_path / "run"
    rc, err = _run([*COMMANDS[command], "--out", str(out), "--scheduler",
                    f"tcp://127.0.0.1:{_closed_port()}"], capsys)
    assert rc == 2 and len(err) == 1 and "--scheduler" in err[0], err
    assert not out.exists()


def test_a_closed_pipe_ends_quietly():
    cmd = f"{sys.executable} -m gripper.cli.main bend | head -1"
    done = subprocess.run(["bash", "-c", cmd], capture_output=True, text=True, timeout=120)
    assert done.stdout.startswith("bending test"), done.stdout
    assert done.stderr == "", done.stderr


def test_a_failed_calibration_leaves_no_folder(tmp_path, monkeypatch):
    import gripper.calibration.pipeline as pipeline
    from gripper.core.resources import CALIBRATION_EXAMPLES_DIR

    def broken(*a, **k):
        raise ValueError("fit: stand-in failure")

    monkeypatch.setattr(pipeline, "fit_hinges", broken)
    out = tmp_path / "a" / "b" / "cal"
    with pytest.raises(ValueError, match="stand-in failure"):
        pipeline.calibrate(out, data=CALIBRATION_EXAMPLES_DIR / "example_bench.csv")
    assert list(tmp_path.iterdir()) == []
