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

An older source tree runs with ``PYTHONPATH=<its checkout>`` (its command is run as
``python -m``, flat ``gripper.cli`` or layered ``gripper.cli.main``).
"""

import argparse
import csv
import hashlib
import importlib.util
import json
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


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, required=True, help="a new folder for the runs")
    ap.add_argument("--json", type=Path, help="also write the hashes here")
    args = ap.parse_args()
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
