"""A newcomer's bad inputs, one case each: every one is refused with exit 2 and one line on
stderr naming what is wrong, before any work, leaving the folder as it was (files already
there keep their bytes). Ctrl-C ends a run with one line and exit 130, the finished trials kept,
no worker process left behind.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from gripper.cli.main import main

EXAMPLE_CSV = Path(__file__).parents[1] / "gripper" / "data" / "calibration" / "example_bench.csv"
UNCREATABLE = "/proc/no_such_process/run"  # /proc refuses new entries even to root


def _setup(tmp: Path) -> None:
    (tmp / "runD" / "trials.jsonl").mkdir(parents=True)  # a run folder whose record file is a folder
    (tmp / "young.toml").write_text("[material]\nyoungs_modulus = 1e300\n")
    (tmp / "tiny_step.toml").write_text("[sim]\ntimestep = 1e-12\n")
    (tmp / "empty.toml").write_text("")
    (tmp / "binary.toml").write_bytes(bytes(range(256)))
    (tmp / "nostudy.toml").write_text('[vary]\n"finger.cut_angle_deg" = [40.0]\n')
    (tmp / "long_name.toml").write_text(f'[object]\nname = "{"x" * 5000}"\nkind = "rigid_box"\n'
                                        'size = [0.02, 0.02, 0.02]\nmass = 0.05\nfriction = 0.6\n'
                                        '[damage]\ncriterion = "none"\n')
    (tmp / "evil_name.toml").write_text('[object]\nname = "../../etc/evil"\nkind = "rigid_box"\n'
                                        'size = [0.02, 0.02, 0.02]\nmass = 0.05\nfriction = 0.6\n'
                                        '[damage]\ncriterion = "none"\n')
    (tmp / "kept.txt").write_text("precious")


# (argv, a word the one line must contain). Paths are relative to the test's folder.
CASES = [
    # output paths that cannot be created, or whose files are of the wrong kind
    (["bench", "--objects", "block", "--trials", "1", "--out", UNCREATABLE], "--out"),
    (["params", "--out", UNCREATABLE + "/p.toml"], "--out"),
    (["video", "--object", "block", "--out", UNCREATABLE + "/v.mp4"], "--out"),
    (["video", "--object", "block", "--out", "v.mp4", "--still", UNCREATABLE + "/s.png"], "--still"),
    (["envelope", "--out", UNCREATABLE], "--out"),
    (["study", "one_at_a_time", "--out", UNCREATABLE], "--out"),
    (["calibrate", "--no-converge", "--out", UNCREATABLE], "--out"),
    (["train", "--out", UNCREATABLE], "--out"),
    (["bench", "--objects", "block", "--trials", "1", "--out", "runD"], "trials.jsonl"),
    (["bench", "--objects", "block", "--trials", "1", "--out", ""], "--out"),
    (["bench", "--objects", "block", "--trials", "1", "--out", "kept.txt"], "--out"),
    (["bench", "--objects", "block", "--plot", "kept.txt", "--out", "r"], "--plot"),
    # numbers out of range: nothing may hang or run backwards
    (["check", "--duration", "1e9"], "--duration"),
    (["check", "--duration", "-1"], "--duration"),
    (["check", "--duration", "nan"], "--duration"),
    (["check", "--seed", "-1"], "--seed"),
    (["play", "--run", "r", "--out", "v.mp4", "--seed", "-1"], "--seed"),
    (["bench", "--seed", "-1", "--out", "r"], "--seed"),
    (["bench", "--seed", "4294967296", "--out", "r"], "--seed"),
    (["bench", "--trials", "0", "--out", "r"], "--trials"),
    (["bench", "--workers", "0", "--out", "r"], "--workers"),
    (["video", "--object", "block", "--out", "v.mp4", "--width", "100000"], "--width"),
    (["bend", "--timestep", "1e-12"], "--timestep"),
    (["bend", "--duration", "1e9"], "--duration"),
    (["check", "--params", "tiny_step.toml"], "sim.timestep"),
    (["calibrate", "--levels", "1"], "--levels"),
    # physical values the model cannot step
    (["bench", "--objects", "block", "--trials", "1", "--params", "young.toml", "--out", "r"],
     "youngs_modulus"),
    (["check", "--params", "young.toml"], "youngs_modulus"),
    # files that are empty, binary or without their section
    (["bench", "--params", "empty.toml", "--out", "r"], "empty.toml"),
    (["bench", "--params", "binary.toml", "--out", "r"], "binary.toml"),
    (["study", "binary.toml", "--out", "r"], "binary.toml"),
    (["study", "nostudy.toml", "--out", "r"], "[study]"),
    # names and lists
    (["bench", "--objects", "block,block", "--out", "r"], "block"),
    (["crush", "--objects", "block,block"], "block"),
    (["pullout", "--objects", "block,block"], "block"),
    (["pullout", "--actuation", "pneumatic", "--grip-tension", "5"], "--grip-tension"),
    (["pullout", "--grip-pressure", "100000"], "--grip-pressure"),
    (["pullout", "--actuation", "pneumatic", "--grip-pressure", "9e9"], "grip_pressure"),
    (["bench", "--objects", "long_name.toml", "--out", "r"], "object.name"),
    (["bench", "--objects", "evil_name.toml", "--out", "r"], "object.name"),
    (["bench", "--objects", "../../etc/evil", "--out", "r"], "unknown object"),
    (["envelope", "--sizes", "0.03,0.03", "--out", "r"], "--sizes"),
    (["envelope", "--masses", "-1", "--out", "r"], "--masses"),
    # names longer than the file system allows (255 bytes)
    (["bench", "--objects", "block", "--out", "x" * 300], "--out"),
    (["bench", "--objects", "block", "--plot", "x" * 300 + ".png", "--out", "r"], "--plot"),
    (["bench", "--params", "x" * 300 + ".toml", "--out", "r"], "parameter file"),
    (["study", "x" * 300 + ".toml", "--out", "r"], "name too long"),
    (["envelope", "x" * 300 + ".toml", "--out", "r"], "name too long"),
    # calibration inputs
    (["calibrate", "--data", str(EXAMPLE_CSV), "--held-out", "99", "--out", "r"], "--held-out"),
]


@pytest.mark.parametrize("argv,word", CASES, ids=[" ".join(a)[:60] + f" [{k}]" for k, (a, _) in enumerate(CASES)])
def test_refused_in_one_line(argv, word, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    _setup(tmp_path)
    before = {p: (p.read_bytes() if p.is_file() else None) for p in tmp_path.rglob("*")}
    try:
        rc = main(argv)
    except SystemExit as e:  # argparse: its own exit
        rc = e.code
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2, (argv, rc, err)
    assert len(err) == 1 and "error" in err[0] and word in err[0], (argv, err)
    after = {p: (p.read_bytes() if p.is_file() else None) for p in tmp_path.rglob("*")}
    assert after == before, sorted(set(after) ^ set(before))  # nothing made, nothing changed


def test_version_names_the_package_and_mujoco(capsys):
    from importlib.metadata import version

    import mujoco

    assert main(["--version"]) == 0
    assert capsys.readouterr().out.strip() == f"gripper {version('gripper')} (MuJoCo {mujoco.__version__})"


def test_every_option_and_command_is_described():
    """Each option has help text, each command a description (``--help`` explains everything)."""
    from gripper.cli.main import build_parser

    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    for name, p in sub.choices.items():
        assert p.description, name
        for a in p._actions:
            if a.option_strings and a.dest != "help":
                assert a.help, (name, a.option_strings)


def _session_members(sid: int) -> list[str]:
    """Command lines of the live processes in session ``sid`` (Linux /proc; zombies excluded)."""
    out = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
            if int(fields[3]) == sid and fields[0] != "Z":  # state, ppid, pgrp, session, ...
                out.append((stat.parent / "cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace"))
        except (OSError, IndexError, ValueError):
            continue  # the process ended while we looked
    return out


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads sessions from Linux /proc")
def test_ctrl_c_ends_a_run_in_one_line_and_keeps_its_trials(tmp_path):
    """SIGINT to the whole process group, as a terminal's Ctrl-C sends it, with two workers."""
    out = tmp_path / "run"
    cmd = [sys.executable, "-m", "gripper.cli.main", "bench", "--objects", "block", "--trials", "40",
           "--out", str(out), "--no-progress", "--workers", "2"]
    # the run starts with Ctrl-C's default action, as a terminal's foreground job does, even when
    # the suite itself runs as a background job of a script (which inherits SIGINT ignored)
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True, cwd=tmp_path,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    trials = out / "trials.jsonl"
    deadline = time.monotonic() + 240
    while not (trials.exists() and trials.read_text().count("\n") >= 2):
        assert proc.poll() is None and time.monotonic() < deadline, proc.communicate()
        time.sleep(0.2)
    os.killpg(proc.pid, signal.SIGINT)
    stdout, stderr = proc.communicate(timeout=120)
    assert proc.returncode == 130, stderr
    assert stderr.strip().splitlines() == [
        "gripper bench: interrupted; finished results are kept (rerun to resume)"], stderr
    kept = trials.read_text()
    assert kept.endswith("\n") and kept.count("\n") >= 2
    # the cluster's processes end too (a resource tracker may take a moment): none left
    for _ in range(100):
        left = _session_members(proc.pid)
        if not left:
            break
        time.sleep(0.1)
    assert not left, left
    # a rerun resumes from the kept trials: the first are the same bytes, one more is added
    n = kept.count("\n")
    rerun = [*cmd[:6], "--trials", str(n + 1), "--out", str(out), "--no-progress"]
    done = subprocess.run(rerun, capture_output=True, text=True, cwd=tmp_path, timeout=240)
    assert done.returncode == 0, done.stderr
    lines = trials.read_text().splitlines()
    assert len(lines) == n + 1 and "\n".join(lines[:n]) + "\n" == kept


def test_a_mujoco_warning_leaves_no_log_file(tmp_path):
    """MuJoCo writes MUJOCO_LOG.TXT into the current folder on a warning unless told not to;
    the package tells it, whether gripper or mujoco is imported first."""
    step = ("m = mujoco.MjModel.from_xml_string('<mujoco><worldbody><body><freejoint/><geom size=\"1\"/>"
            "</body></worldbody></mujoco>'); d = mujoco.MjData(m); d.qvel[0] = float('nan'); "
            "mujoco.mj_step(m, d); assert d.warning[mujoco.mjtWarning.mjWARN_BADQVEL].number == 1")
    for first in ("import gripper, mujoco", "import mujoco, gripper"):
        done = subprocess.run([sys.executable, "-c", f"{first}; {step}"], cwd=tmp_path, capture_output=True,
                              text=True, timeout=120)
        assert done.returncode == 0, done.stderr
        assert "Nan, Inf or huge value in QVEL" in done.stderr  # the console copy stays
        assert list(tmp_path.iterdir()) == [], first
