"""Behaviour fingerprint: hashes of what the simulator computes, to show that a refactor
changed nothing.

Three artefacts per gripper (cable and pneumatic), each through the public entry points only
(``gym.make`` and the CLI), so the same script runs on any version from 0.16.0:

- ``env``: SHA-256 of every observation, reward and termination flag of seeded random-action
  episodes of the registered ``SoftGripperGrasp-v*`` (block, then cylinder);
- ``bench``: SHA-256 of ``trials.jsonl`` from ``gripper bench --trials 2`` on the five default
  objects, records sorted by (object, index), with the keys that are not physics removed: the
  wall time, the package versions and the run's configuration hash (which embeds the version);
- ``study``: SHA-256 of ``results.csv`` from a two-point study with every response kind.

Run: .venv/bin/python scripts/fingerprint.py --out runs/fingerprint [--json FILE]

A hash says only whether anything changed. ``--compare OLD NEW`` says what: the two runs' folders
(``--out`` of two versions) compared record by record, the records of either schema read
through :func:`gripper.experiments.record.upgrade_record`: every outcome (status, success,
failed phase, damage, grasp, pose) must be equal and every number within ``--rtol`` (0.1 %);
each other difference is listed with its size, and the study results row by row the same way.

An older source tree runs with ``PYTHONPATH=<its checkout>`` (its command is run as
``python -m``, flat ``gripper.cli`` or layered ``gripper.cli.main``).
"""

import argparse
import csv
import hashlib
import importlib.util
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

import gymnasium as gym
import numpy as np

NOT_PHYSICS = ("wall_time_s", "versions", "run_config_hash")

STUDY = """
[study]
name = "fingerprint"
design = "one_at_a_time"
seed = 0

[vary]
"finger.cut_angle_deg" = [40.0]

[responses]
bending = { r_max = 0.45 }
tension_for_angle = { angle_deg = 90.0 }
blocked_force = { r = 0.15 }
grasp = { objects = ["block"], trials = 1 }
"""

PNEUMATIC_STUDY = """
[study]
name = "fingerprint_pneumatic"
design = "one_at_a_time"
seed = 0

[fixed]
"actuation.kind" = "pneumatic"

[vary]
"pneumatic.n_segments" = [6]

[responses]
grasp = { objects = ["block"], trials = 1 }
"""


def env_id() -> str:
    """The environment id this version registers (v8 in 0.17.0, v9 from 0.18.0, ...)."""
    import gripper  # noqa: F401  (registers it)

    return next(k for k in gym.registry if k.startswith("SoftGripperGrasp-v"))


def env_hash(actuation: str, steps: int = 120) -> str:
    h = hashlib.sha256()
    for obj in ("block", "cylinder"):
        env = gym.make(env_id(), objects=obj, actuation=actuation)
        env.action_space.seed(0)
        obs, _ = env.reset(seed=0)
        h.update(np.asarray(obs, np.float64).tobytes())
        for _ in range(steps):
            obs, rew, term, trunc, _ = env.step(env.action_space.sample())
            h.update(np.asarray(obs, np.float64).tobytes())
            h.update(np.float64(rew).tobytes() + bytes([term, trunc]))
            if term or trunc:
                obs, _ = env.reset()
        env.close()
    return h.hexdigest()


def gripper_cli(*args: str) -> None:
    layered = importlib.util.find_spec("gripper.cli") is not None and importlib.util.find_spec(
        "gripper.cli").submodule_search_locations is not None
    module = "gripper.cli.main" if layered else "gripper.cli"
    # run outside any checkout, so that ``-m`` does not put one first on sys.path
    subprocess.run([sys.executable, "-m", module, *args, "--no-progress"], check=True,
                   stdout=subprocess.DEVNULL, cwd=tempfile.gettempdir())


def bench_hash(out: Path, actuation: str) -> str:
    gripper_cli("bench", "--trials", "2", "--workers", "2", "--actuation", actuation, "--out", str(out))
    recs = [json.loads(line) for line in (out / "trials.jsonl").read_text().splitlines()]
    recs = [{k: v for k, v in r.items() if k not in NOT_PHYSICS} for r in recs]
    recs.sort(key=lambda r: (r["object"], r["index"]))
    return hashlib.sha256(json.dumps(recs, sort_keys=True).encode()).hexdigest()


def study_hash(out: Path, study: str) -> str:
    toml = out.with_suffix(".toml")
    toml.write_text(study)
    gripper_cli("study", str(toml), "--workers", "2", "--out", str(out))
    with open(out / "results.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    rows = [{k: v for k, v in r.items() if k not in NOT_PHYSICS} for r in rows]
    return hashlib.sha256(json.dumps(rows, sort_keys=True).encode()).hexdigest()


def _flatten(value, key: str = "") -> dict[str, object]:
    """Nested dicts and lists as {dotted.key: leaf}."""
    if isinstance(value, dict):
        return {k: v for name, sub in value.items() for k, v in _flatten(sub, f"{key}.{name}" if key else name).items()}
    if isinstance(value, list):
        return {k: v for i, sub in enumerate(value) for k, v in _flatten(sub, f"{key}[{i}]").items()}
    return {key: value}


def _differences(old: dict, new: dict, rtol: float) -> list[str]:
    """What differs between two flattened rows: numbers beyond ``rtol``, anything else (the
    outcomes: status, success, failed phase, damage, grasp, pose) at all, keys present in one only."""
    out = []
    for key in sorted(set(old) | set(new)):
        a, b = old.get(key, "<absent>"), new.get(key, "<absent>")
        numbers = all(isinstance(v, int | float) and not isinstance(v, bool) for v in (a, b))
        if numbers:
            if not math.isclose(a, b, rel_tol=rtol, abs_tol=1e-12):
                out.append(f"{key}: {a!r} -> {b!r} ({(b - a) / a:+.2%})" if a else f"{key}: {a!r} -> {b!r}")
        elif a != b:
            out.append(f"{key}: {a!r} -> {b!r}")
    return out


def compare(old_dir: Path, new_dir: Path, rtol: float) -> int:
    """Print what differs between two fingerprint folders; return the number of differences."""
    from gripper.experiments.record import upgrade_record

    skip = {*NOT_PHYSICS, "config_hash"}
    n = 0
    for actuation in ("cable", "pneumatic"):
        recs = []
        for folder in (old_dir, new_dir):
            rows = [upgrade_record(json.loads(line))
                    for line in (folder / f"bench_{actuation}" / "trials.jsonl").read_text().splitlines() if line]
            recs.append({r["trial_id"]: _flatten({k: v for k, v in r.items() if k not in skip}) for r in rows})
        for tid in sorted(set(recs[0]) | set(recs[1])):
            diffs = _differences(recs[0].get(tid, {}), recs[1].get(tid, {}), rtol)
            n += len(diffs)
            for line in diffs:
                print(f"{actuation} bench {tid}: {line}")
        tables = []
        for folder in (old_dir, new_dir):
            with open(folder / f"study_{actuation}" / "results.csv", newline="") as f:
                tables.append({(r["point"], r["metric"]): r for r in csv.DictReader(f)})
        for key in sorted(set(tables[0]) | set(tables[1])):
            a, b = ({k: float(v) if k == "value" and v else v for k, v in t.get(key, {}).items()} for t in tables)
            diffs = _differences(a, b, rtol)
            n += len(diffs)
            for line in diffs:
                print(f"{actuation} study point {key[0]} {key[1]}: {line}")
    print(f"{n} differences beyond {rtol:.1%} or in an outcome")
    return n


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, help="a new folder for the runs")
    ap.add_argument("--json", type=Path, help="also write the hashes here")
    ap.add_argument("--compare", type=Path, nargs=2, metavar=("OLD", "NEW"),
                    help="compare two --out folders instead of running")
    ap.add_argument("--rtol", type=float, default=1e-3, help="relative tolerance of --compare (0.1 %%)")
    args = ap.parse_args()
    if args.compare:
        sys.exit(1 if compare(*args.compare, args.rtol) else 0)
    if args.out is None:
        ap.error("--out is required (or --compare OLD NEW)")
    args.out = args.out.resolve()
    args.out.mkdir(parents=True, exist_ok=False)
    result = {}
    for actuation, study in (("cable", STUDY), ("pneumatic", PNEUMATIC_STUDY)):
        result[f"{actuation}.env"] = env_hash(actuation)
        result[f"{actuation}.bench"] = bench_hash(args.out / f"bench_{actuation}", actuation)
        result[f"{actuation}.study"] = study_hash(args.out / f"study_{actuation}", study)
    for k, v in result.items():
        print(f"{k:16s} {v}")
    if args.json:
        args.json.write_text(json.dumps(result, indent=1) + "\n")


if __name__ == "__main__":
    main()
