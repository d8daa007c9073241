"""A bad-input campaign against the command line, as a new user's typos would run it (slow:
``scripts/test.sh --slow``; it was ``scripts/bad_input_campaign.py`` until 0.17.0).

Every command starts from a cheap valid argument list; one option at a time gets a bad value
(out of range, not a number, empty, a path that cannot be written, a name that is too long or
escapes its folder). Each case runs as its own process with a time limit and is classed:

- ``refused``: exit 2 and one line on stderr, nothing new in the case's folder;
- ``accepted``: exit 0 (a value that is allowed);
- ``traceback``, ``hang``, ``other``: defects, which fail the case.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

GRIPPER = [sys.executable, "-m", "gripper.cli.main"]
NUMBERS = ["-1", "0", "1e9", "nan", "inf", "-inf", "1e400", "abc", ""]
PATHS = ["", "/proc/no_such/x", "EXISTING_FILE", "EXISTING_DIR", "x" * 300]
NAMES = ["", ",", "x" * 5000, "../../etc/passwd", "block,block", "nope"]
FILES = ["", "missing.toml", "BINARY.toml", "EMPTY.toml", "EXISTING_DIR", "x" * 300 + ".toml"]

# command: (cheap valid argv, {option: values})
CASES = {
    "bench": (["--objects", "block", "--trials", "1", "--no-progress", "--out", "run"],
              {"--trials": NUMBERS, "--seed": NUMBERS, "--workers": NUMBERS, "--noise": NUMBERS,
               "--mass-noise": NUMBERS, "--friction-noise": NUMBERS, "--grip-tension": NUMBERS,
               "--close-scale": NUMBERS, "--objects": NAMES, "--out": PATHS, "--plot": PATHS,
               "--params": FILES, "--calibration": FILES, "--scheduler": ["", "nohost:1", "tcp://"]}),
    "check": (["--duration", "0.05"], {"--duration": NUMBERS, "--seed": NUMBERS, "--params": FILES}),
    "bend": (["--duration", "0.05", "--points", "5"],
             {"--duration": NUMBERS, "--timestep": NUMBERS, "--r-max": NUMBERS, "--points": NUMBERS,
              "--figure": PATHS}),
    "params": (["--out", "p.toml"], {"--out": PATHS, "--params": FILES}),
    "video": (["--object", "block", "--out", "v.gif", "--width", "32", "--height", "32", "--fps", "5"],
              {"--object": NAMES, "--out": PATHS, "--width": NUMBERS, "--height": NUMBERS, "--fps": NUMBERS,
               "--seed": NUMBERS, "--index": NUMBERS, "--camera": ["", "nope"], "--still": PATHS}),
    "envelope": (["--out", "env", "--shapes", "box", "--sizes", "0.04", "--masses", "0.05", "--frictions",
                  "0.6", "--trials", "1", "--no-progress"],
                 {"--sizes": NUMBERS, "--masses": NUMBERS, "--frictions": NUMBERS, "--shapes": NAMES,
                  "--trials": NUMBERS, "--seed": NUMBERS, "--grip-tension": NUMBERS, "--out": PATHS}),
    "crush": (["--objects", "block", "--depth", "0.005", "--hold", "0"],
              {"--objects": NAMES, "--depth": NUMBERS, "--speed": NUMBERS, "--hold": NUMBERS}),
    "pullout": (["--objects", "block", "--max-force", "2"],
                {"--objects": NAMES, "--rate": NUMBERS, "--max-force": NUMBERS, "--grip-tension": NUMBERS}),
    "calibrate": (["--out", "cal", "--data", "gripper/data/calibration/example_bench.csv"],
                  {"--levels": NUMBERS, "--mesh-scale": NUMBERS, "--tension-max": NUMBERS,
                   "--held-out": ["99", "-1", "a", "0,0", "0,1,2,3,4"], "--data": FILES, "--out": PATHS}),
    "study": (["tiny_study.toml", "--out", "st", "--no-progress"],
              {"--workers": NUMBERS, "--out": PATHS}),
    "train": (["--out", "tr", "--steps", "1"],
              {"--steps": NUMBERS, "--seed": NUMBERS, "--n-envs": NUMBERS, "--chunk-steps": NUMBERS,
               "--eval-episodes": NUMBERS, "--objects": NAMES, "--set": ["x", "=1"], "--out": PATHS}),
    "play": (["--run", "nowhere", "--out", "v.mp4"],
             {"--seed": NUMBERS, "--width": NUMBERS, "--height": NUMBERS, "--out": PATHS}),
}
ROOT = Path(__file__).resolve().parents[1]
TIMEOUT = 120.0  # s per case: the slowest valid case (a calibration from bench data) takes about 40 s


def _prepare(folder: Path) -> None:
    (folder / "EXISTING_FILE").write_text("precious")
    (folder / "EXISTING_DIR").mkdir()
    (folder / "BINARY.toml").write_bytes(bytes(range(256)))
    (folder / "EMPTY.toml").write_text("")
    (folder / "tiny_study.toml").write_text('[study]\nname = "tiny"\n[vary]\n"finger.cut_angle_deg" = [40.0]\n'
                                            '[responses]\nbending = { r_max = 0.1 }\n')


def _tree(folder: Path) -> dict[Path, bytes | None]:
    """Every path under ``folder`` with its bytes (None for a folder)."""
    return {p: (p.read_bytes() if p.is_file() else None) for p in folder.rglob("*")}


def run_case(command: str, argv: list[str], timeout: float) -> tuple[str, str]:
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        _prepare(folder)
        argv = [str(ROOT / a) if a.startswith("gripper/data/") else a for a in argv]
        before = _tree(folder)
        env = dict(os.environ, PYTHONPATH=str(ROOT), MUJOCO_GL="egl")
        try:
            done = subprocess.run([*GRIPPER, command, *argv], cwd=folder, capture_output=True, text=True,
                                  timeout=timeout, env=env, stdin=subprocess.DEVNULL)
        except subprocess.TimeoutExpired:
            return "hang", f"no end within {timeout:g} s"
        err = done.stderr.strip().splitlines()
        after = _tree(folder)
        if "Traceback (most recent call last)" in done.stderr:
            return "traceback", err[-1] if err else ""
        if done.returncode == 2:
            if len(err) == 1 and after == before:
                return "refused", err[0]
            return "other", f"exit 2 with {len(err)} lines, files changed: {after != before}: {err[:3]}"
        if done.returncode == 0:
            return "accepted", (done.stdout.strip().splitlines() or [""])[-1][:160]
        return "other", f"exit {done.returncode}: {err[-1] if err else ''}"


def _cases() -> list[tuple[str, list[str]]]:
    jobs = []
    for command, (base, options) in CASES.items():
        for option, values in options.items():
            for value in values:
                argv = list(base)
                if option in argv:
                    k = argv.index(option)
                    argv[k + 1] = value
                else:
                    argv += [option, value]
                jobs.append((command, argv))
    return jobs


@pytest.mark.slow
@pytest.mark.parametrize(("command", "argv"), _cases(),
                         ids=lambda v: v if isinstance(v, str) else " ".join(a[:20] for a in v))
def test_a_bad_value_is_refused_or_allowed_never_a_defect(command, argv):
    kind, text = run_case(command, argv, TIMEOUT)
    assert kind in ("refused", "accepted"), f"{kind}: gripper {command} {' '.join(argv)}: {text}"
