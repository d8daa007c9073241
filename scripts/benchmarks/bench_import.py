"""Time ``import gripper`` and ``gripper --help`` in fresh interpreters: medians of --repeats.

Run: .venv/bin/python scripts/bench_import.py [--repeats 5] [--source DIR]

``--source DIR`` times another source tree of the package (e.g. a ``git worktree`` of an older
commit) with this interpreter, its command run as ``python -m``, for a before/after table.
"""

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def wall(cmd: list[str], env: dict[str, str]) -> float:
    t0 = time.perf_counter()
    # outside any checkout, so that ``-c`` / ``-m`` do not put one first on sys.path
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, env=env, cwd=tempfile.gettempdir())
    return time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--source", type=Path, help="time this source tree instead of the installed package")
    args = ap.parse_args()
    env = dict(os.environ)
    help_cmd = [str(Path(sys.executable).with_name("gripper")), "--help"]
    if args.source:
        env["PYTHONPATH"] = str(args.source.resolve())
        flat = (args.source / "gripper" / "cli.py").exists()
        help_cmd = [sys.executable, "-m", "gripper.cli" if flat else "gripper.cli.main", "--help"]
    cases = {"import gripper": [sys.executable, "-c", "import gripper"], "gripper --help": help_cmd}
    for name, cmd in cases.items():
        wall(cmd, env)  # warm the file cache
        times = [wall(cmd, env) for _ in range(args.repeats)]
        print(f"{name:16s} median {statistics.median(times):.3f} s  (min {min(times):.3f}, max {max(times):.3f})")


if __name__ == "__main__":
    main()
