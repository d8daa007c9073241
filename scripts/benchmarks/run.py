"""The speed benchmarks' one runner: list them, or run some (or all) in turn, each in a fresh
interpreter, and print what each prints (medians of repeats and side-by-side ratios; machines
here are shared and noisy, so no benchmark asserts a time).

Run:
    .venv/bin/python scripts/benchmarks/run.py --list
    .venv/bin/python scripts/benchmarks/run.py env trial            # bench_env.py, bench_trial.py
    .venv/bin/python scripts/benchmarks/run.py import -- --repeats 9  # options after -- go to each
    .venv/bin/python scripts/benchmarks/run.py --all
"""

from __future__ import annotations

import argparse
import ast
import os
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent


def benchmarks() -> dict[str, Path]:
    """Every ``bench_<name>.py`` here (and ``profile_trials.py``), by name."""
    out = {p.stem.removeprefix("bench_"): p for p in sorted(HERE.glob("bench_*.py"))}
    out["profile_trials"] = HERE / "profile_trials.py"
    return out


def summary(path: Path) -> str:
    doc = ast.get_docstring(ast.parse(path.read_text())) or ""
    return doc.splitlines()[0] if doc else ""


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("names", nargs="*", help="benchmarks to run (see --list)")
    ap.add_argument("--list", action="store_true", help="list the benchmarks and what each measures")
    ap.add_argument("--all", action="store_true", help="run every benchmark (tens of minutes)")
    argv = sys.argv[1:]
    extra = argv[argv.index("--") + 1:] if "--" in argv else []
    args = ap.parse_args(argv[:argv.index("--")] if "--" in argv else argv)
    known = benchmarks()
    if args.list or not (args.names or args.all):
        for name, path in known.items():
            print(f"{name:<16} {summary(path)}")
        return 0
    unknown = [n for n in args.names if n not in known]
    if unknown:
        print(f"run.py: unknown benchmark {', '.join(unknown)}; allowed: {', '.join(known)}", file=sys.stderr)
        return 2
    env = {**os.environ, "MUJOCO_GL": os.environ.get("MUJOCO_GL", "egl")}
    failed = []
    for name in (list(known) if args.all else args.names):
        print(f"== {name}: {summary(known[name])}", flush=True)
        t0 = time.perf_counter()
        rc = subprocess.run([sys.executable, str(known[name]), *extra], env=env).returncode
        print(f"== {name}: exit {rc}, {time.perf_counter() - t0:.0f} s wall\n", flush=True)
        if rc:
            failed.append(name)
    if failed:
        print(f"run.py: failed: {', '.join(failed)}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
