"""Headless grasp benchmark: many seeded trials per object, on Dask ``distributed``.

Output folder layout:

- ``config.json``: the run's configuration (parameters, protocol, noise, seed, objects) and
  its hash; a rerun with a different configuration into the same folder is refused;
- ``trials.jsonl``: one JSON line per finished trial, appended in trial order, flushed and
  fsynced as it goes (a crash loses at most the trial being written; a torn last line is
  dropped on resume);
- ``summary.csv`` / ``summary.json``: per object ``trials``, ``errors`` (unstable),
  ``successes``, ``success_rate`` (over the trials that ran to their end: neither unstable nor
  ``no_object``, which the JSON counts as ``no_object``), ``ci95`` (Wilson score interval),
  ``damage_rate``, ``median_peak_force_N``, ``p95_peak_force_N``, ``mean_wall_time_s``; plus
  ``config_hash``, ``versions`` and ``wall_time_s``.

Trials run on a Dask ``LocalCluster`` (one single-threaded worker process per ``workers``) or
on an existing cluster (``scheduler``); ``workers=1`` without a scheduler runs in this process.
Every trial is a pure function of (configuration, object, seed, index), so the records do not
depend on the number of workers.

Example:
    >>> from gripper.bench.benchmark import BenchConfig, run_benchmark
    >>> summary = run_benchmark(BenchConfig(objects=("block",), trials=2), "runs/demo")  # doctest: +SKIP
"""

from __future__ import annotations

import dataclasses
import json
import math
import statistics
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np

from gripper.bench.defaults import DEFAULT_TRIALS, DEFAULT_WORKERS
from gripper.bench.execution import check_same_run, read_jsonl
from gripper.bench.resumable import ResumableRun
from gripper.core.arguments import check_instance
from gripper.core.atomic import write_csv_atomic, write_text_atomic
from gripper.core.fields import Validated
from gripper.core.hashing import stable_hash
from gripper.core.params import GripperParams
from gripper.core.provenance import versions
from gripper.core.ranges import SEED_MAX, TRIALS_MAX
from gripper.drives import drive_for
from gripper.experiments.approach import check_fits_opening
from gripper.experiments.protocol import GraspProtocol, TrialNoise
from gripper.experiments.record import TrialRecord
from gripper.experiments.trial import run_trial
from gripper.objects.grasp_object import GraspObject
from gripper.objects.library import DEFAULT_OBJECTS, get_object, object_source


def wilson_interval(successes: int, n: int, z: float = 1.959964) -> tuple[float, float]:
    """Wilson score interval for a binomial proportion (95 % for the default z)."""
    if n == 0:
        return (0.0, 1.0)
    phat = successes / n
    den = 1 + z * z / n
    centre = (phat + z * z / (2 * n)) / den
    half = z * math.sqrt(phat * (1 - phat) / n + z * z / (4 * n * n)) / den
    return (max(0.0, centre - half), min(1.0, centre + half))


@dataclass(frozen=True)
class BenchConfig(Validated):
    """What to run. ``trials`` per object; ``seed`` the base seed of every trial."""

    objects: tuple[str, ...] = DEFAULT_OBJECTS
    trials: int = DEFAULT_TRIALS
    seed: int = 0
    params: GripperParams = field(default_factory=GripperParams)
    protocol: GraspProtocol = field(default_factory=GraspProtocol)
    noise: TrialNoise = field(default_factory=TrialNoise)

    def validate(self) -> BenchConfig:
        for name, cls in (("params", GripperParams), ("protocol", GraspProtocol), ("noise", TrialNoise)):
            if not isinstance(getattr(self, name), cls):
                raise TypeError(f"{name}: expected a {cls.__name__}, got {type(getattr(self, name)).__name__}")
        if isinstance(self.trials, bool) or not isinstance(self.trials, int) or not 1 <= self.trials <= TRIALS_MAX:
            raise ValueError(f"trials: must be an integer in [1, {TRIALS_MAX:,}], got {self.trials!r}")
        if not isinstance(self.seed, int) or isinstance(self.seed, bool) or not 0 <= self.seed <= SEED_MAX:
            raise ValueError(f"seed: must be an integer in [0, {SEED_MAX:,}], got {self.seed!r}")
        if isinstance(self.objects, str) or not isinstance(self.objects, tuple | list) or not self.objects \
                or not all(isinstance(o, str) for o in self.objects):
            raise ValueError(f"objects: give a non-empty tuple of object names, got {self.objects!r}")
        if len(self.objects) * self.trials > TRIALS_MAX:
            raise ValueError(f"trials: {len(self.objects)} objects × {self.trials:,} trials; at most {TRIALS_MAX:,} "
                             "in one run")
        twice = sorted({o for o in self.objects if self.objects.count(o) > 1})
        if twice:
            raise ValueError(f"objects: {', '.join(twice)} listed more than once; give each once")
        seen: dict[str, str] = {}
        for spec, name in zip(self.objects, self.names(), strict=True):
            if name in seen:
                raise ValueError(f"objects: {seen[name]!r} and {spec!r} are both named {name!r}; "
                                 "give each object of a run its own name")
            seen[name] = spec
        sources: dict[tuple, str] = {}
        for spec in self.objects:
            src = object_source(spec)
            if src in sources:
                raise ValueError(f"objects: {sources[src]!r} and {spec!r} are the same object ({src[1]}); give it once")
            sources[src] = spec
        self.params.validate()
        self.protocol.validate()
        self.noise.validate()
        for obj in self._resolved.values():  # each fits this design's opening
            check_fits_opening(obj, self.params)

        drive_for(self.params).check_set_point(self.protocol)
        return self

    def identity(self) -> dict:
        """Everything that decides a trial's outcome (not the trial count or object list),
        including the gripper and MuJoCo versions: a new version models objects differently,
        so its records must not be mixed into an old run's folder."""
        return {"params": self.params.to_dict(), "protocol": self.protocol.to_dict(),
                "noise": self.noise.to_dict(), "seed": self.seed,
                "objects": {o: obj.to_dict() for o, obj in self._resolved.items()},
                "versions": {k: v for k, v in versions().items() if k in ("gripper", "mujoco")}}

    def hash(self) -> str:
        return stable_hash([self.identity()])

    def names(self) -> tuple[str, ...]:
        """The objects' names as their records give them (:func:`get_object`): a built-in's
        name, an object file's ``object.name``, a ``mesh:`` spec exactly as given."""
        return tuple(obj.name for obj in self._resolved.values())

    @cached_property
    def _resolved(self) -> dict[str, GraspObject]:
        """Each object spec resolved once per configuration (a mesh spec reads its file and its
        hull; names, jobs, identity and the summary all need them)."""
        return {o: get_object(o) for o in self.objects}

    def jobs(self) -> list[tuple[str, int]]:
        """(object name, index) in the order records are written: object by object, as listed,
        each in index order."""
        return [(name, i) for name in self.names() for i in range(self.trials)]


# The files of a benchmark run folder.
RUN_FILES = ("config.json", "trials.jsonl", "summary.json", "summary.csv")


def _run_one(cfg: BenchConfig, obj: str, index: int, run_hash: str) -> dict:
    """One trial of object spec ``obj``, as the JSON record the run's file holds (``run_hash``:
    the run's configuration hash, computed once per run)."""
    rec = run_trial(obj, cfg.seed, index, params=cfg.params, protocol=cfg.protocol, noise=cfg.noise)
    return dataclasses.replace(rec, run_config_hash=run_hash).to_dict()


def _trial_key(rec: Mapping) -> tuple[str, int]:
    return rec["object"], int(rec["index"])


def read_trials(path: Path, *, repair: bool = True) -> list[TrialRecord]:
    """Complete records of ``trials.jsonl`` (a torn last line is cut off, with ``repair``), each
    checked against the record's schema (a bad one is a ValueError naming the file and the record)."""
    return [TrialRecord.from_dict(r, where=f"{path}: record {i + 1}")
            for i, r in enumerate(read_jsonl(path, repair=repair))]


def run_benchmark(cfg: BenchConfig, out: str | Path, *, workers: int = DEFAULT_WORKERS, scheduler: str | None = None,
                  progress: bool = True) -> dict:
    """Run (or resume) the benchmark into ``out``; return the summary dict.

    Raises:
        ValueError: bad configuration, or ``out`` holds a different configuration.
    """
    check_instance("cfg", cfg, BenchConfig, optional=False)
    check_instance("out", out, (str, Path), optional=False)
    cfg.validate()
    run_hash = cfg.hash()
    spec = dict(zip(cfg.names(), cfg.objects, strict=True))
    run = ResumableRun(marker="config.json", key="config", other="a run with another configuration",
                       files=RUN_FILES, records="trials.jsonl", label="grasp trials", run_hash=run_hash,
                       identity=cfg.identity(), jobs=cfg.jobs(),
                       job_args=lambda job: (cfg, spec[job[0]], job[1], run_hash), fn=_run_one,
                       record_key=_trial_key, describe=lambda r: f"trial {r['trial_id']}", read=read_trials,
                       reorder=True)
    with run.open(out, workers=workers, scheduler=scheduler, progress=progress) as done:
        summary = summarize(done.records, cfg, wall_time_s=time.perf_counter() - done.started,
                            resumed=done.resumed)
        write_summary(done.out, summary)
        return summary


def summarize(records: Sequence[Mapping], cfg: BenchConfig, wall_time_s: float = 0.0, resumed: int = 0) -> dict:
    """Per-object statistics of ``records`` (see the module docstring). ``wall_time_s`` is this
    call's; ``resumed`` counts the records it found in the folder from earlier calls."""
    check_same_run(records, cfg.hash(), "summary")
    per = {}
    for obj in cfg.names():
        rs = [r for r in records if r["object"] == obj]
        ok = [r for r in rs if r["status"] == "ok"]
        n = len(ok)
        s = sum(1 for r in ok if r["success"])
        forces = [r["peak_total_force_N"] for r in ok]
        lo, hi = wilson_interval(s, n)
        per[obj] = {
            "trials": len(rs), "errors": sum(1 for r in rs if r["status"] == "error"),
            "no_object": sum(1 for r in rs if r["status"] == "no_object"), "successes": s,
            "success_rate": s / n if n else None, "ci95": [lo, hi],
            "damage_rate": sum(1 for r in ok if r["damaged"]) / n if n else None,
            "median_peak_force_N": statistics.median(forces) if forces else None,
            "p95_peak_force_N": float(np.percentile(forces, 95)) if forces else None,
            "mean_wall_time_s": statistics.fmean(r["wall_time_s"] for r in rs) if rs else None,
            "warnings": sum(r["warnings"] for r in rs),
            "failed_phases": {ph: sum(1 for r in ok if r["failed_phase"] == ph)
                              for ph in ("lift", "hold", "shake", "damage")},
        }
    drive = drive_for(cfg.params)
    grip = (drive.format_set_point(drive.set_point(cfg.protocol)) if cfg.protocol.policy == "controller"
            else "each object's own closing command")
    return {"objects": per, "config_hash": cfg.hash(), "versions": versions(),
            "wall_time_s": wall_time_s, "resumed": resumed, "trials_per_object": cfg.trials, "seed": cfg.seed,
            "gripper": drive.model_name, "actuation": drive.kind, "grip": grip}


SUMMARY_COLUMNS = ("object", "trials", "errors", "successes", "success_rate", "ci95_low", "ci95_high",
                   "damage_rate", "median_peak_force_N", "p95_peak_force_N", "mean_wall_time_s", "warnings")


def write_summary(out: Path, summary: dict) -> None:
    """Write ``summary.json`` and ``summary.csv`` atomically (temp file, then rename)."""
    write_text_atomic(out / "summary.json", json.dumps(summary, indent=2, sort_keys=True))
    write_csv_atomic(out / "summary.csv", SUMMARY_COLUMNS, (
        [obj, s["trials"], s["errors"], s["successes"], s["success_rate"], s["ci95"][0], s["ci95"][1],
         s["damage_rate"], s["median_peak_force_N"], s["p95_peak_force_N"], s["mean_wall_time_s"], s["warnings"]]
        for obj, s in summary["objects"].items()))


def format_table(summary: dict) -> str:
    """The summary as a fixed-width text table."""
    def f(v, spec):
        return format(v, spec) if v is not None else "-"
    lines = ([f"{summary['actuation']} gripper ({summary['gripper']}), grip {summary['grip']}"]
             if "gripper" in summary else [])
    lines += [f"{'object':<10} {'trials':>6} {'err':>4} {'succ':>5} {'rate':>6} {'95% CI':>13} "
             f"{'damage':>7} {'F med N':>8} {'F p95 N':>8} {'wall s':>7}"]
    for obj, s in summary["objects"].items():
        ci = f"{s['ci95'][0]:.2f}-{s['ci95'][1]:.2f}"
        lines.append(f"{obj:<10} {s['trials']:>6} {s['errors']:>4} {s['successes']:>5} "
                     f"{f(s['success_rate'], '6.2f')} {ci:>13} {f(s['damage_rate'], '7.2f')} "
                     f"{f(s['median_peak_force_N'], '8.2f')} {f(s['p95_peak_force_N'], '8.2f')} "
                     f"{f(s['mean_wall_time_s'], '7.2f')}")
    resumed = summary.get("resumed", 0)
    total = sum(s["trials"] for s in summary["objects"].values())
    wall = f"wall {summary['wall_time_s']:.1f} s" + (
        f" for {total - resumed} new trials ({resumed} resumed from the folder)" if resumed else "")
    lines.append(f"config {summary['config_hash']}  {wall}  mujoco {summary['versions']['mujoco']}")
    return "\n".join(lines)
