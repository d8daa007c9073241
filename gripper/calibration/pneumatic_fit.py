"""Fit the pneumatic finger (:mod:`gripper.drives.pneumatic.chamber`) to paper 001's actuator in finite
elements (:mod:`gripper.references.actuator_bending`), and write its calibration.

The hinge chain is compared with the reference as the reference was loaded: one finger in the
record's neutral frame, hanging (gravity along it) at every inflation pressure, and lying on its
back under its own weight at no pressure (the sag). Each point is the chain **at rest**: a static
solve of MuJoCo's own force balance (passive springs, the chamber's moment, gravity; Newton's
method on the hinge angles), so the fit and its check compare equilibria with equilibria.

Free parameters, in log space and bounded: the bending stiffness EI, the stiffening EI past the
knee, the knee curvature, the pressure's moment per pascal and the root hinge's spring. The inflation alone cannot tell
the moment from the stiffness (both scale the bend alike); the sag fixes the stiffness.
Residuals: the tip point (x, z) in units of ``TIP_SIGMA`` at each fitted pressure and in the sag.
The ``held_out`` pressures are left out and scored afterwards. Solver:
:func:`mujoco.minimize.least_squares`.

Example:
    >>> from gripper.calibration.pneumatic_fit import fit_pneumatic
    >>> from gripper.references.actuator_bending import run_actuator_reference
    >>> fit = fit_pneumatic(run_actuator_reference())      # doctest: +SKIP
    >>> fit.metrics["tip_rms_frac"]                        # doctest: +SKIP
"""

from __future__ import annotations

import io
import json
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import mujoco
import numpy as np
from mujoco import minimize
from scipy.optimize import root

from gripper.core.hashing import stable_hash
from gripper.core.params import PNEUMATIC_CALIBRATION_FILE, GripperParams
from gripper.core.provenance import versions
from gripper.drives.pneumatic.chamber import add_pneumatic_finger, add_segment_meshes
from gripper.drives.pneumatic.drive import PneumaticDrive
from gripper.parts.defaults import add_defaults, set_options
from gripper.references.actuator_bending import ActuatorRecord
from gripper.references.pneumatic_params import PneumaticActuator

SCHEMA = "gripper.pneumatic_calibration/1"
TIP_SIGMA = 1.0e-3  # m, scale of the tip residuals (as the cable fit's)
HELD_OUT_KPA = (125.0,)  # the middle of the 0-250 kPa sweep
FIT_PARAMETERS = ("bending_stiffness", "stiffening", "knee_curvature", "moment_per_pascal", "root_stiffness")
# Bounds [SI]: EI from a silicone strip to a plastic one; the knee within the sweep's curvature
# (91° over 140 mm is 11 1/m); the moment per pascal of a duct 1-50 mm across.
BOUNDS = {"bending_stiffness": (1e-5, 1.0), "stiffening": (1e-6, 1.0), "knee_curvature": (1e-3, 20.0),
          "moment_per_pascal": (1e-9, 1e-5), "root_stiffness": (1e-4, 100.0)}
REST_TOL = 1e-10  # N·m, the static solve's force-balance tolerance per hinge


def design_hash(actuator: PneumaticActuator, refinement: int) -> str:
    """Hash of what the calibration stands for: the actuator design, the reference model's
    formulation (``REFERENCE_MODEL``) and its mesh."""
    from gripper.references.actuator_fe import REFERENCE_MODEL

    return stable_hash([asdict(actuator), REFERENCE_MODEL, refinement])


def design_block(actuator: PneumaticActuator, record: ActuatorRecord) -> dict[str, float]:
    """The finger's shape as the chain's bodies take it [m, kg]: the length, the cross-section's
    width and height (the body's half-round back on the neutral layer, fibre and cladding; from
    the finite-element cross-section's levels) and the neutral layer's mid-plane above the
    grasping face; the mass as the reference weighs it."""
    from gripper.references.actuator_mesh import Geometry

    g = Geometry(actuator)
    return {"length": actuator.length, "width": 2.0 * g.r_out, "height": g.y_centre + g.r_out - g.y_bottom,
            "neutral_height": -g.y_bottom, "mass": record.mass}


class ChainStatics:
    """One pneumatic finger in the record's neutral frame, solved for rest."""

    def __init__(self, p: GripperParams):
        self.p = p
        spec = mujoco.MjSpec()
        drive = PneumaticDrive(p)
        set_options(spec, p)
        drive.configure(spec)
        spec.modelname = "pneumatic_calibration"
        defaults = add_defaults(spec, p)
        add_segment_meshes(spec, p)
        self.names = drive.names(0)
        add_pneumatic_finger(spec, spec.worldbody, p, self.names, [0, 0, 0], [1, 0, 0, 0], defaults)
        spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT
        self.model = spec.compile()
        self.data = mujoco.MjData(self.model)
        m = self.model
        self.hinges = np.array([m.joint(h).id for h in self.names.hinges[1:]])
        self.root = m.joint(self.names.hinges[0]).id
        self.stiff_tendons = np.array([m.tendon(f"{h}_stiffening").id for h in self.names.hinges[1:]])
        self.act = m.actuator(self.names.drive).id
        self.tip = m.site(self.names.tip).id
        self.hinge_z = p.pneumatic.hinge_z

    def set_parameters(self, values: dict[str, float]) -> None:
        """Put fitted values (``FIT_PARAMETERS``, continuum form) into the compiled model."""
        m, pf = self.model, self.p.pneumatic
        pitch = pf.pitch
        m.jnt_stiffness[self.hinges] = values["bending_stiffness"] / pitch
        m.tendon_stiffness[self.stiff_tendons] = values["stiffening"] / pitch
        m.tendon_lengthspring[self.stiff_tendons, 1] = values["knee_curvature"] * pitch
        m.actuator_gainprm[self.act, 0] = values["moment_per_pascal"]
        m.jnt_stiffness[self.root] = values["root_stiffness"]

    def rest(self, pressure: float, gravity: np.ndarray, q0: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """The hinge angles at rest and the tip (x, z) in the neutral frame [rad, m].

        Raises:
            RuntimeError: Newton's method found no rest within ``REST_TOL``.
        """
        m, d = self.model, self.data
        m.opt.gravity[:] = gravity
        d.qvel[:] = 0.0
        d.act[self.act] = pressure
        d.ctrl[self.act] = pressure

        def balance(q):
            d.qpos[:] = q
            mujoco.mj_forward(m, d)
            return d.qfrc_passive + d.qfrc_actuator - d.qfrc_bias

        sol = root(balance, np.zeros(m.nq) if q0 is None else q0, method="hybr", options={"xtol": 1e-12})
        f = balance(sol.x)
        if not np.all(np.abs(f) < REST_TOL):
            raise RuntimeError(f"pneumatic fit: no rest at {pressure:g} Pa (force balance {np.abs(f).max():.2g} N·m)")
        tip = d.site_xpos[self.tip]
        return sol.x.copy(), np.array([tip[0], tip[2] - self.hinge_z])


@dataclass
class PneumaticFit:
    """Fitted values (continuum form, ``FIT_PARAMETERS``), the chain's tips at rest at the
    reference's pressures and in the sag, and the fit's metrics."""

    values: dict[str, float]
    tips: np.ndarray
    sag_tip: np.ndarray
    metrics: dict
    wall_time_s: float


def _finger_params(p: GripperParams, actuator: PneumaticActuator, record: ActuatorRecord) -> GripperParams:
    shape = design_block(actuator, record)
    return p.replace(actuation=p.actuation.replace(kind="pneumatic"),
                     pneumatic=p.pneumatic.replace(**shape))


def chain_tips(statics: ChainStatics, values: dict[str, float], record: ActuatorRecord
               ) -> tuple[np.ndarray, np.ndarray]:
    """The chain's tip at rest at every reference pressure (hanging) and in the sag [m]."""
    statics.set_parameters(values)
    g = record.gravity
    tips, q = [], None
    for pressure in record.pressures:
        q, tip = statics.rest(float(pressure), np.array([g, 0.0, 0.0]), q)
        tips.append(tip)
    _, sag = statics.rest(0.0, np.array([0.0, 0.0, g]))
    return np.array(tips), sag


def fit_pneumatic(record: ActuatorRecord, actuator: PneumaticActuator | None = None,
                  params: GripperParams | None = None, *, held_out_kpa: tuple[float, ...] = HELD_OUT_KPA,
                  max_iter: int = 100) -> PneumaticFit:
    """Fit ``FIT_PARAMETERS`` to ``record`` (module docstring).

    Raises:
        ValueError: a held-out pressure the record does not have.
    """
    a = (actuator or PneumaticActuator()).validate()
    p = _finger_params(params or GripperParams(), a, record)
    kpa = record.pressures / 1e3
    held = np.zeros(len(kpa), dtype=bool)
    for h in held_out_kpa:
        hit = np.isclose(kpa, h)
        if not hit.any():
            raise ValueError(f"--held-out: {h:g} kPa is not one of the reference's pressures "
                             f"({', '.join(f'{v:g}' for v in kpa)} kPa)")
        held |= hit
    fitted = ~held
    statics = ChainStatics(p)
    lo = np.log([BOUNDS[k][0] for k in FIT_PARAMETERS])
    hi = np.log([BOUNDS[k][1] for k in FIT_PARAMETERS])

    def values_of(x: np.ndarray) -> dict[str, float]:
        return dict(zip(FIT_PARAMETERS, np.exp(x).tolist(), strict=True))

    def residual(x: np.ndarray) -> np.ndarray:
        cols = []
        for xi in (x.T if x.ndim == 2 else [x]):
            try:
                tips, sag = chain_tips(statics, values_of(xi), record)
                r = np.concatenate([((tips - record.tip)[fitted]).ravel(), sag - record.sag_tip]) / TIP_SIGMA
            except RuntimeError:
                r = np.full(2 * int(fitted.sum()) + 2, 1e3)  # no rest: a huge residual, the solver steps away
            cols.append(r)
        out = np.array(cols).T
        return out if x.ndim == 2 else out[:, 0]

    x0 = np.log([p.pneumatic.bending_stiffness, p.pneumatic.stiffening, max(p.pneumatic.knee_curvature, 0.01),
                 p.pneumatic.moment_per_pascal, p.pneumatic.root_stiffness])
    x0 = np.clip(x0, lo + 0.01, hi - 0.01)
    t0 = time.perf_counter()
    x, _ = minimize.least_squares(x0, residual, bounds=(lo, hi), max_iter=max_iter, verbose=0, output=io.StringIO())
    wall = time.perf_counter() - t0
    values = values_of(x)
    tips, sag = chain_tips(statics, values, record)
    L = record.length
    err = np.linalg.norm(tips - record.tip, axis=1) / L
    metrics = {
        "tip_rms_frac": float(np.sqrt(np.mean(err[fitted] ** 2))),
        "tip_max_frac": float(err[fitted].max()),
        "held_out": [{"pressure_kPa": float(k), "tip_error_frac": float(e)} for k, e in zip(kpa[held], err[held],
                                                                                             strict=True)],
        "sag_tip_error_frac": float(np.linalg.norm(sag - record.sag_tip) / L),
        "per_pressure": [{"pressure_kPa": float(k), "tip_error_frac": float(e)} for k, e in zip(kpa, err, strict=True)],
        "at_bounds": [k for k, v, a, b in zip(FIT_PARAMETERS, x, lo, hi, strict=True)
                      if min(v - a, b - v) < 1e-6],
        "n_segments": p.pneumatic.n_segments,
        "fit_wall_time_s": wall,
    }
    return PneumaticFit(values=values, tips=tips, sag_tip=sag, metrics=metrics, wall_time_s=wall)


def calibration_dict(fit: PneumaticFit, record: ActuatorRecord, actuator: PneumaticActuator) -> dict:
    """The calibration file's content (``calibration.json``)."""
    return {"schema": SCHEMA, "design_hash": design_hash(actuator, record.refinement), "source": "actuator_fe",
            "design": design_block(actuator, record), "fitted": fit.values, "metrics": fit.metrics,
            "reference": {"refinement": record.refinement, "wall_time_s": record.wall_time_s},
            "versions": versions()}


def stale_reasons(data: dict | None = None) -> list[str]:
    """Why the committed pneumatic calibration no longer stands for paper 001's default actuator
    (empty when fresh): a changed design or mesh, or a fit that no longer reproduces its own
    reference record within the bound it was written with."""
    from gripper.references.actuator_bending import STUDY_REFINEMENT

    data = data or json.loads(PNEUMATIC_CALIBRATION_FILE.read_text())
    want = design_hash(PneumaticActuator(), STUDY_REFINEMENT)
    reasons = []
    if data.get("schema") != SCHEMA:
        reasons.append(f"schema {data.get('schema')!r} != {SCHEMA!r}")
    if data.get("design_hash") != want:
        reasons.append(f"design hash {data.get('design_hash')} != {want} (the actuator's defaults or the "
                       "reference mesh changed); run 'gripper calibrate --reference actuator --write-default'")
    return reasons


def write_pneumatic_calibration(out_dir: str | Path, record: ActuatorRecord, fit: PneumaticFit,
                                actuator: PneumaticActuator) -> Path:
    """``calibration.json``, ``reference.json`` and ``report.png`` into ``out_dir``, each written
    whole (a temporary file renamed)."""
    from gripper.core.atomic import write_text_atomic

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    write_text_atomic(out / "reference.json", json.dumps(record.to_json_dict()) + "\n")
    write_pneumatic_report(out / "report.png", record, fit)
    return write_text_atomic(out / "calibration.json",
                             json.dumps(calibration_dict(fit, record, actuator), indent=2) + "\n")


def write_pneumatic_report(path: Path, record: ActuatorRecord, fit: PneumaticFit) -> None:
    """The neutral layer's line in finite elements and the chain's tips, per pressure."""
    import matplotlib

    from gripper.core.atomic import write_atomic

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.0, 5.0))
    for i, pa in enumerate(record.pressures):
        ax.plot(record.line[i, :, 0] * 1e3, record.line[i, :, 1] * 1e3, color="0.6", lw=1)
        ax.plot(*(record.tip[i] * 1e3), "o", color="C0", ms=4, label="finite elements" if i == 0 else None)
        ax.plot(*(fit.tips[i] * 1e3), "x", color="C3", ms=6, label="hinge chain at rest" if i == 0 else None)
        ax.annotate(f"{pa / 1e3:.0f}", record.tip[i] * 1e3, textcoords="offset points", xytext=(4, -10), fontsize=7)
    ax.plot(*(record.sag_tip * 1e3), "s", color="C0", mfc="none", label="sag (lying, 0 kPa), FE")
    ax.plot(*(fit.sag_tip * 1e3), "+", color="C3", ms=8, label="sag, chain")
    ax.set_xlabel("x along the actuator [mm]")
    ax.set_ylabel("z towards the neutral layer [mm]")
    ax.invert_yaxis()
    ax.set_aspect("equal")
    ax.legend(fontsize=8, loc="lower left")
    ax.set_title(f"pneumatic finger vs paper 001's actuator: tip RMS {100 * fit.metrics['tip_rms_frac']:.2f} % of L",
                 fontsize=9)
    fig.tight_layout()
    write_atomic(path, lambda tmp: fig.savefig(tmp, dpi=110, format="png"))
    plt.close(fig)




PNEUMATIC_FILES = ("calibration.json", "reference.json", "report.png")
# The docs' copy of the committed report (written by --write-default in a source checkout).
DOCS_REPORT = PNEUMATIC_CALIBRATION_FILE.parents[4] / "docs" / "pneumatic_calibration.png"


def calibrate_pneumatic(out_dir: str | Path, params: GripperParams | None = None, *,
                        on_progress=None) -> tuple[dict, PneumaticFit, ActuatorRecord]:
    """``gripper calibrate --reference actuator``: the finite-element reference of paper 001's
    default actuator (about 4 minutes on 2 cores), the fit (under a second), and the files
    ``PNEUMATIC_FILES`` in ``out_dir``. ``params``: the chain's segment count and the regulator
    (the design's shape is the actuator's).

    Raises:
        RuntimeError: the reference did not converge.
    """
    from gripper.references.actuator_bending import run_actuator_reference

    say = on_progress or (lambda msg: None)
    actuator = PneumaticActuator()
    say("finite-element reference: paper 001's actuator inflated to 250 kPa, and lying under its own weight ...")
    record = run_actuator_reference(actuator)
    say(f"reference: {record.wall_time_s:.1f} s wall; fitting the pneumatic finger ...")
    fit = fit_pneumatic(record, actuator, params)
    write_pneumatic_calibration(out_dir, record, fit, actuator)
    return calibration_dict(fit, record, actuator), fit, record


def write_default_pneumatic_calibration(on_progress=None) -> dict:
    """Regenerate the committed calibration of the default pneumatic finger
    (``gripper calibrate --reference actuator --write-default``), from the default parameters'
    segment count, into ``gripper/data/calibration/pneumatic/``."""
    cal, _, _ = calibrate_pneumatic(PNEUMATIC_CALIBRATION_FILE.parent, GripperParams(), on_progress=on_progress)
    docs = DOCS_REPORT
    if docs.parent.is_dir():  # a source checkout: the docs show the report (a test compares the two)
        from gripper.core.atomic import write_atomic

        report = (PNEUMATIC_CALIBRATION_FILE.parent / "report.png").read_bytes()
        write_atomic(docs, lambda tmp: Path(tmp).write_bytes(report))
    return cal


__all__ = ["FIT_PARAMETERS", "HELD_OUT_KPA", "PNEUMATIC_FILES", "SCHEMA", "ChainStatics", "PneumaticFit",
           "calibrate_pneumatic", "calibration_dict", "chain_tips", "design_block", "design_hash", "fit_pneumatic",
           "stale_reasons", "write_default_pneumatic_calibration", "write_pneumatic_calibration",
           "write_pneumatic_report"]
