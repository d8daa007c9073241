"""Surrogate of the continuum reference's hinge stiffness over a design study's ranges.

A design study's point gets the committed calibration's springs times the continuum reference's
equivalent-stiffness ratio between the point and the default design, read from a quadratic fit
over the study's ranges (built once, committed, checked by leave-one-out). How and why:
``docs/calibration.md``, "The stiffness surrogate".

Example:
    >>> from gripper.calibration.surrogate import StiffnessSurrogate
    >>> s = StiffnessSurrogate.load_default()                       # doctest: +SKIP
    >>> s.ratio({"finger.bridge_thickness": 0.0025})                 # doctest: +SKIP
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from gripper.core.atomic import write_text_atomic
from gripper.core.params import GripperParams
from gripper.core.resources import STUDIES_DIR

DIMENSIONS = ("finger.cut_angle_deg", "finger.bridge_thickness", "finger.hole_height",
              "finger.pitch")
# The default studies' ranges (gripper/data/studies/*.toml), widened to whole design values.
DEFAULT_RANGES = {"finger.cut_angle_deg": (30.0, 52.0), "finger.bridge_thickness": (0.0019, 0.004),
                  "finger.hole_height": (0.010, 0.014), "finger.pitch": (0.0137, 0.032)}
DEFAULT_POINTS = 40
SURROGATE_FILE = STUDIES_DIR / "stiffness_surrogate.json"
SCHEMA = "gripper.stiffness_surrogate/1"


def _features(x: np.ndarray) -> np.ndarray:
    """Quadratic features of (cut angle [deg], ln t, hole height [m], ln pitch), scaled."""
    a = (x[:, 0] - 45.0) / 10.0
    t = np.log(x[:, 1] / 0.003)
    h = (x[:, 2] - 0.012) / 0.002
    q = np.log(x[:, 3] / 0.016)
    cols = [np.ones_like(a), a, t, h, q]
    lin = cols[1:]
    for i in range(4):
        for j in range(i, 4):
            cols.append(lin[i] * lin[j])
    return np.stack(cols, axis=1)


def _design(p: GripperParams, values: dict) -> GripperParams:
    return p.replace(finger=p.finger.replace(**{k.split(".")[1]: v for k, v in values.items()}))


def equivalent_stiffness_raw(p: GripperParams) -> float:
    """K_eq on the default mesh [N·m/rad] (no convergence correction: used as a ratio)."""
    from gripper.references.convergence import linear_compliance

    g = p.finger
    comp = math.radians(linear_compliance(p)["compliance_deg_per_N"])
    return g.n_hinges * (g.hole_height - g.hinge_z) / comp


@dataclass(frozen=True)
class StiffnessSurrogate:
    """ln K_eq as a quadratic polynomial of the design (see the module docstring).

    Attributes:
        ranges: the bounds of each dimension it was built over.
        samples: the design points, shape (n, 4), columns as :data:`DIMENSIONS`.
        stiffness: K_eq at each sample [N·m/rad].
        default_stiffness: K_eq of the default design [N·m/rad].
        coefficients: of the polynomial features.
        loo_error: leave-one-out relative errors of K_eq at each sample [-].
        correction: the mesh-convergence correction (see :func:`correction_model`):
            ``points`` (bridge thickness [m], correction factor [-]), the fitted ``slope`` and
            ``intercept`` of ln(factor) against ln(t / 3 mm), and ``checks`` (designs off the
            bridge axis with their measured and modelled factors).
    """

    ranges: dict
    samples: np.ndarray
    stiffness: np.ndarray
    default_stiffness: float
    coefficients: np.ndarray
    loo_error: np.ndarray
    correction: dict

    @classmethod
    def build(cls, params: GripperParams | None = None, ranges: dict | None = None,
              points: int = DEFAULT_POINTS, seed: int = 0, correction: dict | None = None,
              on_progress=None) -> StiffnessSurrogate:
        """Solve the reference at a Latin hypercube of ``points`` designs and the centre; fit.

        ``correction``: a :func:`correction_model` result (none: ratios of the default mesh's
        raw solves)."""
        from scipy.stats import qmc

        p = (params or GripperParams()).validate()
        rng = ranges or DEFAULT_RANGES
        lo = np.array([rng[d][0] for d in DIMENSIONS])
        hi = np.array([rng[d][1] for d in DIMENSIONS])
        unit = qmc.LatinHypercube(d=len(DIMENSIONS), seed=seed).random(points)
        x = np.vstack([0.5 * (lo + hi), qmc.scale(unit, lo, hi)])
        say = on_progress or (lambda msg: None)
        k, kept = [], []
        for i, row in enumerate(x):
            try:  # a sample whose cuts would meet is no design: left out
                q = _design(p, dict(zip(DIMENSIONS, row.tolist(), strict=True))).validate()
            except ValueError as e:
                say(f"surrogate point {i + 1}/{len(x)}: skipped ({e})")
                continue
            k.append(equivalent_stiffness_raw(q))
            kept.append(i)
            say(f"surrogate point {i + 1}/{len(x)}: K_eq {k[-1]:.4g} N·m/rad")
        stiffness = np.asarray(k)
        x = x[kept]
        k0 = equivalent_stiffness_raw(p)
        F = _features(x)
        y = np.log(stiffness)
        coef = np.linalg.lstsq(F, y, rcond=None)[0]
        # Leave-one-out residuals of a linear least-squares fit, exactly: e_i / (1 - h_ii).
        H = F @ np.linalg.pinv(F)
        loo = (y - F @ coef) / (1.0 - np.diag(H))
        return cls(ranges={d: list(rng[d]) for d in DIMENSIONS}, samples=x, stiffness=stiffness,
                   default_stiffness=float(k0), coefficients=coef,
                   loo_error=np.expm1(np.abs(loo)), correction=correction or {})

    def predict(self, values: dict, base: GripperParams | None = None) -> float:
        """K_eq [N·m/rad] of the base design with ``values`` (dotted keys) changed.

        Raises:
            ValueError: a value outside the surrogate's ranges or not one of its dimensions.
        """
        b = (base or GripperParams()).finger
        x = []
        for d in DIMENSIONS:
            v = values.get(d, getattr(b, d.split(".")[1]))
            lo, hi = self.ranges[d]
            if not lo - 1e-12 <= v <= hi + 1e-12:
                raise ValueError(f"{d}: {v:g} is outside the stiffness surrogate's range "
                                 f"[{lo:g}, {hi:g}]")
            x.append(v)
        for key in values:
            if key not in DIMENSIONS:
                raise ValueError(f"{key}: not a dimension of the stiffness surrogate "
                                 f"({', '.join(DIMENSIONS)})")
        raw = float(np.exp(_features(np.array([x])) @ self.coefficients)[0])
        return raw * self.correction_factor(x[1])

    def correction_factor(self, bridge_thickness: float) -> float:
        """The default mesh's stiffness correction at this bridge [-] (1 without a model)."""
        if not self.correction:
            return 1.0
        c = self.correction
        return math.exp(c["intercept"] + c["slope"] * math.log(bridge_thickness / 0.003))

    def ratio(self, values: dict, base: GripperParams | None = None) -> float:
        """K_eq at the changed design over K_eq at the base design [-]."""
        return self.predict(values, base) / self.predict({}, base)

    def to_json_dict(self) -> dict:
        return {"schema": SCHEMA, "dimensions": list(DIMENSIONS), "ranges": self.ranges,
                "samples": self.samples.tolist(), "stiffness_Nm_per_rad": self.stiffness.tolist(),
                "default_stiffness_Nm_per_rad": self.default_stiffness,
                "coefficients": self.coefficients.tolist(),
                "loo_error": self.loo_error.tolist(),
                "loo_error_max": float(self.loo_error.max()), "correction": self.correction}

    def save(self, path: str | Path = SURROGATE_FILE) -> Path:
        return write_text_atomic(path, json.dumps(self.to_json_dict(), indent=1) + "\n")

    @classmethod
    def load(cls, path: str | Path) -> StiffnessSurrogate:
        try:
            d = json.loads(Path(path).read_text())
        except (OSError, json.JSONDecodeError) as e:
            raise ValueError(f"stiffness surrogate: cannot read {str(path)!r}: {e}") from None
        if d.get("schema") != SCHEMA or d.get("dimensions") != list(DIMENSIONS):
            raise ValueError(f"stiffness surrogate: {path} is not a {SCHEMA} file of "
                             f"{', '.join(DIMENSIONS)}")
        return cls(ranges=d["ranges"], samples=np.asarray(d["samples"]),
                   stiffness=np.asarray(d["stiffness_Nm_per_rad"]),
                   default_stiffness=float(d["default_stiffness_Nm_per_rad"]),
                   coefficients=np.asarray(d["coefficients"]),
                   loo_error=np.asarray(d["loo_error"]), correction=d.get("correction") or {})

    @classmethod
    def load_default(cls) -> StiffnessSurrogate:
        return cls.load(SURROGATE_FILE)


def correction_model(params: GripperParams | None = None,
                     bridges: tuple[float, ...] = (0.0019, 0.0025, 0.003, 0.004),
                     checks: tuple[dict, ...] = ({"finger.cut_angle_deg": 30.0},
                                                 {"finger.cut_angle_deg": 55.0}),
                     known: dict | None = None, on_progress=None) -> dict:
    """The default mesh's stiffness correction (``f_default / f_extrapolated`` of a full
    convergence study, :func:`~gripper.references.convergence.mesh_convergence`) as a power
    law of the bridge thickness, the dimension it depends on most (the cells along x stay
    2.3 mm while the singular apex's bridge thins), fitted through full studies at ``bridges``;
    ``checks`` are designs off that axis, reported with the law's error there.
    Each study takes about 3.5 minutes on one core; ``known`` maps bridge thicknesses already
    studied to their factors."""
    from gripper.references.convergence import mesh_convergence

    p = (params or GripperParams()).validate()
    say = on_progress or (lambda msg: None)

    def factor(values: dict) -> float:
        c = mesh_convergence(_design(p, values).validate()).stiffness_correction
        say(f"correction at {values}: {c:.4f}")
        return c

    known = known or {}
    pts = [(t, known[t] if t in known else factor({"finger.bridge_thickness": t}))
           for t in bridges]
    lt = np.log(np.array([t for t, _ in pts]) / 0.003)
    lc = np.log(np.array([c for _, c in pts]))
    slope, intercept = np.polyfit(lt, lc, 1)
    model_checks: list[dict] = []
    model = {"points": [list(q) for q in pts], "slope": float(slope),
             "intercept": float(intercept), "checks": model_checks}
    for values in checks:
        t = values.get("finger.bridge_thickness", p.finger.bridge_thickness)
        measured = factor(values)
        modelled = math.exp(intercept + slope * math.log(t / 0.003))
        model_checks.append({"design": values, "measured": measured, "modelled": modelled,
                                "error": modelled / measured - 1.0})
    return model


__all__ = ["correction_model", "DEFAULT_RANGES", "DIMENSIONS", "SURROGATE_FILE", "StiffnessSurrogate",
           "equivalent_stiffness_raw"]
