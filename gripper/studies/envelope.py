"""The gripper's capability envelope: which shapes, sizes, masses and frictions the grasp
controller holds at one grip set-point.

An envelope file (TOML) gives shapes, widths, masses, frictions, trials, a seed and the grip
set-point; every point is a set of trials on the benchmark's execution layer, and the summary
gives each shape's gripping range and payload. The format and the derived figures:
``docs/envelope.md``, "The envelope file".

Example:
    >>> from gripper.studies.envelope import load_envelope
    >>> load_envelope("default").trials                     # doctest: +SKIP
    3
"""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

from gripper.bench.defaults import DEFAULT_WORKERS
from gripper.core.arguments import check_instance
from gripper.core.atomic import write_atomic, write_csv_atomic
from gripper.core.hashing import stable_hash
from gripper.core.params import GripperParams
from gripper.core.ranges import FRICTION, OBJECT_MASS, SEED_MAX, TRIALS_MAX
from gripper.core.resources import STUDIES_DIR
from gripper.core.user_files import read_user_data
from gripper.drives import drive_for
from gripper.experiments.protocol import GRIP_TENSION, GraspProtocol, TrialNoise
from gripper.objects.envelope_objects import (
    HELD_FRACTION,
    SHAPES,
    check_envelope_points,
    envelope_object,
    point_held,
)

KEYS = ("shapes", "sizes", "masses", "frictions", "trials", "seed", "grip_tension", "grip_pressure")


@dataclass(frozen=True)
class Envelope:
    """A validated envelope spec (see the module docstring); SI units."""

    shapes: tuple[str, ...] = ("sphere", "cylinder", "box")
    sizes: tuple[float, ...] = (0.010, 0.020, 0.030, 0.045, 0.060, 0.075, 0.090, 0.110)
    masses: tuple[float, ...] = (0.05, 0.2, 0.5, 1.0, 2.0)
    frictions: tuple[float, ...] = (0.6,)
    trials: int = 3
    seed: int = 0
    grip_tension: float = GRIP_TENSION
    grip_pressure: float = GraspProtocol().grip_pressure  # the pneumatic gripper's set-point [Pa]
    params: GripperParams = field(default_factory=GripperParams)

    def validate(self) -> Envelope:
        def fail(key, msg):
            return ValueError(f"envelope.{key}: {msg}")

        if not self.shapes or any(s not in SHAPES for s in self.shapes):
            raise fail("shapes", f"give one or more of {', '.join(SHAPES)}, got {list(self.shapes)!r}")
        if len(set(self.shapes)) != len(self.shapes):
            raise fail("shapes", f"each shape once, got {list(self.shapes)!r}")
        # widths from 1 mm to 0.3 m (beyond any palm); every point's object is then built once
        for key, lo, hi in (("sizes", 1e-3, 0.3), ("masses", 1e-3, OBJECT_MASS.hi),
                            ("frictions", FRICTION.lo, FRICTION.hi)):
            vals = getattr(self, key)
            if not vals or any(isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v)
                               or not lo <= v <= hi for v in vals):
                raise fail(key, f"give a list of numbers in [{lo:g}, {hi:g}], got {list(vals)!r}")
            if len(set(vals)) != len(vals):
                raise fail(key, f"each value once, got {list(vals)!r}")
        try:
            check_envelope_points(self.shapes, self.sizes, self.masses, self.frictions)
        except ValueError as e:
            raise ValueError(f"envelope.{e}") from None
        if isinstance(self.trials, bool) or not isinstance(self.trials, int) or not 1 <= self.trials <= 1000:
            raise fail("trials", f"must be an integer in [1, 1000], got {self.trials!r}")
        if isinstance(self.seed, bool) or not isinstance(self.seed, int) or not 0 <= self.seed <= SEED_MAX:
            raise fail("seed", f"must be an integer in [0, {SEED_MAX:,}], got {self.seed!r}")
        total = len(self.points()) * self.trials
        if total > TRIALS_MAX:
            raise fail("trials", f"{len(self.points()):,} points × {self.trials} trials = {total:,} trials; at most "
                       f"{TRIALS_MAX:,} (a day of trials on one core)")
        drive = drive_for(self.params)
        try:
            drive.check_set_point(self.protocol())
        except ValueError as e:
            raise fail(drive.set_point_field, str(e).split(": ", 1)[-1]) from None
        return self

    def protocol(self) -> GraspProtocol:
        return GraspProtocol(policy="controller", grip_tension=self.grip_tension,
                             grip_pressure=self.grip_pressure).validate()

    def points(self) -> list[tuple[str, float, float, float]]:
        """(shape, size, mass, friction) in the order records are written."""
        return [(s, w, m, mu) for s in self.shapes for w in self.sizes for m in self.masses for mu in self.frictions]

    def jobs(self) -> list[tuple[int, int]]:
        """(point index, trial index) in record order."""
        return [(k, i) for k in range(len(self.points())) for i in range(self.trials)]

    def identity(self) -> dict:
        from gripper.core.provenance import versions

        return {"shapes": list(self.shapes), "sizes": list(self.sizes), "masses": list(self.masses),
                "frictions": list(self.frictions), "trials": self.trials, "seed": self.seed,
                "grip_tension": self.grip_tension, "grip_pressure": self.grip_pressure,
                "params": self.params.to_dict(),
                "protocol": self.protocol().to_dict(), "noise": TrialNoise().to_dict(),
                "versions": {k: v for k, v in versions().items() if k in ("gripper", "mujoco")}}

    def hash(self) -> str:
        return stable_hash([self.identity()])


def load_envelope(path: str | Path, **overrides) -> Envelope:
    """Parse an envelope file, or the shipped one by name (``default``); ``overrides`` replace
    its keys (the command line's flags). Every error names the key.

    Raises:
        ValueError: unreadable file, bad TOML, unknown key, or a value out of range.
    """
    path = Path(path)
    shipped = STUDIES_DIR / f"envelope_{path.name}.toml"
    if not path.exists() and path.suffix == "" and path.parent == Path(".") and shipped.is_file():
        path = shipped
    data = read_user_data(path, "envelope", (".toml",))
    if set(data) != {"envelope"} or not isinstance(data["envelope"], dict):
        raise ValueError(f"envelope: {path}: expected one [envelope] table, got {sorted(data)}")
    spec = dict(data["envelope"])
    unknown = sorted(set(spec) - set(KEYS))
    if unknown:
        raise ValueError(f"envelope.{unknown[0]}: unknown key; allowed: {', '.join(KEYS)}")
    spec.update({k: v for k, v in overrides.items() if v is not None})
    params = spec.get("params", GripperParams())
    own = drive_for(params).set_point_field
    for key in ("grip_tension", "grip_pressure"):
        if key in spec and key != own:
            raise ValueError(f"envelope.{key} (--{key.replace('_', '-')}): a set-point of the other gripper; this "
                             f"envelope runs the {params.actuation.kind} gripper, whose set-point is {own}")
    for key in ("shapes", "sizes", "masses", "frictions"):
        if key in spec:
            if not isinstance(spec[key], list | tuple):
                raise ValueError(f"envelope.{key}: must be a list, got {spec[key]!r}")
            spec[key] = tuple(spec[key])
    return Envelope(**spec).validate()


def _run_one(env: Envelope, k: int, index: int, run_hash: str) -> dict:
    from gripper.experiments.trial import run_trial

    shape, size, mass, mu = env.points()[k]
    rec = run_trial(envelope_object(shape, size, mass, mu), env.seed, index, params=env.params,
                    protocol=env.protocol())
    return {"point": k, "shape": shape, "size_m": size, "mass_kg": mass, "friction": mu,
            **dataclasses.replace(rec, run_config_hash=run_hash).to_dict()}


# The files of an envelope's run folder (and one map_<shape>.png per shape).
RUN_FILES = ("envelope.json", "trials.jsonl", "envelope.csv", "summary.json")


def run_envelope(env: Envelope, out: str | Path, *, workers: int = DEFAULT_WORKERS, scheduler: str | None = None,
                 progress: bool = True) -> dict:
    """Run (or resume) the envelope into ``out``; write the table, the maps and the summary."""
    from gripper.bench.resumable import ResumableRun

    check_instance("env", env, Envelope, optional=False)
    check_instance("out", out, (str, Path), optional=False)
    env.validate()
    h = env.hash()
    run = ResumableRun(marker="envelope.json", key="envelope", other="another envelope", files=RUN_FILES,
                       records="trials.jsonl", label="envelope trials", run_hash=h, identity=env.identity(),
                       jobs=env.jobs(), job_args=lambda job: (env, *job, h), fn=_run_one,
                       record_key=lambda r: (r["point"], r["index"]),
                       describe=lambda r: f"point {r.get('point')}, trial {r.get('index')}")
    with run.open(out, workers=workers, scheduler=scheduler, progress=progress) as done:
        write_table(done.records, done.out / "envelope.csv")
        summary = summarize(done.records, env)
        write_atomic(done.out / "summary.json",
                     lambda tmp: Path(tmp).write_text(json.dumps(summary, indent=2, sort_keys=True)))
        write_maps(done.records, env, done.out)
        return summary


COLUMNS = ("shape", "size_m", "mass_kg", "friction", "index", "status", "success", "failed_phase",
           "peak_total_force_N", "grasp_time_s", "lift_height_m", "max_slip_m", "warnings")


def write_table(records: list[dict], path: Path) -> None:
    """Tidy CSV: one row per trial."""
    write_csv_atomic(path, COLUMNS, ([r.get(c) for c in COLUMNS] for r in records))


def held_fractions(records: list[dict]) -> dict[int, float | None]:
    """Per point: the success fraction of its trials that ran to their end (None if none did:
    all unstable or no object seen)."""
    ok: dict[int, list[bool]] = {}
    for r in records:
        ok.setdefault(r["point"], [])
        if r["status"] == "ok":
            ok[r["point"]].append(bool(r["success"]))
    return {k: sum(v) / len(v) if v else None for k, v in ok.items()}


def summarize(records: list[dict], env: Envelope) -> dict:
    """Per shape and friction: the success map, the gripping range and the payload."""
    from gripper.bench.execution import check_same_run

    check_same_run(records, env.hash(), "summary")
    pts = env.points()
    frac_of = held_fractions(records)
    out: dict = {"grip_tension_N": env.grip_tension, "held_fraction": HELD_FRACTION, "shapes": {},
                 "actuation": env.params.actuation.kind, "grip_pressure_Pa": env.grip_pressure,
                 "errors": sum(r["status"] == "error" for r in records),
                 "no_object": sum(r["status"] == "no_object" for r in records),
                 "warnings": sum(r["warnings"] for r in records), "envelope_hash": env.hash()}
    for shape in env.shapes:
        for mu in env.frictions:
            grid = {}
            for k, (s, w, m, f) in enumerate(pts):
                if s == shape and f == mu:
                    grid[(w, m)] = frac_of.get(k)
            held = {wm for wm, frac in grid.items() if point_held(frac)}
            light = min(env.masses)
            sizes = sorted(w for w, m in held if m == light)
            key = shape if len(env.frictions) == 1 else f"{shape}@mu{mu:g}"
            out["shapes"][key] = {
                "friction": mu,
                "gripping_range_m": [sizes[0], sizes[-1]] if sizes else None,
                "payload_kg": max((m for _, m in held), default=None),
                "map": [{"size_m": w, "mass_kg": m, "success": frac} for (w, m), frac in sorted(grid.items())],
            }
    return out


def write_maps(records: list[dict], env: Envelope, out: Path) -> list[Path]:
    """One PNG per shape and friction: success fraction over size × mass (``map_<shape>.png``
    with one friction, ``map_<shape>_mu<friction>.png`` with several)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    pts = env.points()
    frac_of = held_fractions(records)
    files = []
    for shape, mu in ((s, f) for s in env.shapes for f in env.frictions):
        z = np.full((len(env.masses), len(env.sizes)), np.nan)
        for k, (s, w, m, f) in enumerate(pts):
            if s == shape and f == mu:
                frac = frac_of.get(k)
                z[env.masses.index(m), env.sizes.index(w)] = np.nan if frac is None else frac
        fig, ax = plt.subplots(figsize=(6.0, 3.6))
        im = ax.imshow(z, origin="lower", cmap="RdYlGn", vmin=0, vmax=1, aspect="auto")
        ax.set_xticks(range(len(env.sizes)), [f"{w * 1e3:g}" for w in env.sizes])
        ax.set_yticks(range(len(env.masses)), [f"{m:g}" for m in env.masses])
        ax.set_xlabel("width [mm] (sphere: diameter)")
        ax.set_ylabel("mass [kg]")
        ax.set_title(f"{shape}: success over {env.trials} trials, grip {env.grip_tension:g} N, μ = {mu:g}")
        for (i, j), v in np.ndenumerate(z):
            if np.isfinite(v):
                ax.text(j, i, f"{v:.2f}", ha="center", va="center", fontsize=7)
        fig.colorbar(im, ax=ax, label="success fraction")
        fig.tight_layout()
        path = out / (f"map_{shape}.png" if len(env.frictions) == 1 else f"map_{shape}_mu{mu:g}.png")

        def save(tmp: str, fig=fig) -> None:
            fig.savefig(tmp, dpi=110, format="png")

        write_atomic(path, save)
        plt.close(fig)
        files.append(path)
    return files
