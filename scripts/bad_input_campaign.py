"""A bad-input campaign against the command line, as a new user's typos would run it.

Every command starts from a cheap valid argument list; one option at a time gets a bad value
(out of range, not a number, empty, a path that cannot be written, a name that is too long or
escapes its folder). Each case runs as its own process with a time limit and is classed:

- ``refused``: exit 2 and one line on stderr, nothing new in the case's folder;
- ``accepted``: exit 0 (listed, to be read: a value that is allowed, or a silent acceptance);
- ``traceback``, ``hang``, ``other``: defects.

Run: ``.venv/bin/python scripts/bad_input_campaign.py [--only COMMAND] [--jobs 2]``; prints
the counts and every case that was not refused. Exit 1 if any case is a defect.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

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


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", help="one command")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=120.0)
    args = ap.parse_args()
    jobs = []
    for command, (base, options) in CASES.items():
        if args.only and command != args.only:
            continue
        for option, values in options.items():
            for value in values:
                argv = list(base)
                if option in argv:
                    k = argv.index(option)
                    argv[k + 1] = value
                else:
                    argv += [option, value]
                jobs.append((command, argv))
    with ThreadPoolExecutor(args.jobs) as pool:
        results = list(pool.map(lambda j: run_case(j[0], j[1], args.timeout), jobs))
    counts: dict[str, int] = {}
    for (command, argv), (kind, text) in zip(jobs, results, strict=True):
        counts[kind] = counts.get(kind, 0) + 1
        if kind != "refused":
            shown = " ".join(a if len(a) < 40 else a[:20] + "..." for a in argv)
            print(f"{kind:<10} gripper {command} {shown}\n           {text}")
    print(", ".join(f"{k} {v}" for k, v in sorted(counts.items())), f"of {len(jobs)} cases")
    return 1 if any(k in counts for k in ("traceback", "hang", "other")) else 0


if __name__ == "__main__":
    sys.exit(main())
