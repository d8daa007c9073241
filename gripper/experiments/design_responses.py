"""The responses a design study measures on one design (paper 001's outputs, on this finger):
the bending curve and its figures, the cable tension for a bending angle, the blocked tip force
(:func:`gripper.experiments.blocked_tip.blocked_tip_force`: a stop at the tip), grasp success,
the capability envelope's gripping range, the payload and the everyday parts. Pure functions of
the parameters: the study layer (:mod:`gripper.studies.study`) decides which designs to run.

Example:
    >>> from gripper.core.params import GripperParams
    >>> from gripper.experiments.design_responses import measure_responses
    >>> metrics, curves = measure_responses(GripperParams(), {"blocked_force": {"r": 0.1}})  # doctest: +SKIP
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from gripper.core.params import GripperParams
from gripper.drives import drive_for
from gripper.experiments.blocked_tip import blocked_tip_force
from gripper.experiments.protocol import GraspProtocol, TrialNoise
from gripper.experiments.pullout import run_pullout
from gripper.experiments.trial import run_trial, sample_placement
from gripper.objects.envelope_objects import SHAPES, envelope_object, point_held
from gripper.objects.library import get_object
from gripper.objects.scene_objects import Placement

# Samples of the bending curve kept per point (r from 0 to r_max).
BEND_CURVE_POINTS = 21


def _bending(p: GripperParams, opts: dict):
    from gripper.experiments.bending import BendingConfig, run_bending_test

    cfg = BendingConfig(r_max=float(opts.get("r_max", 0.45)), duration=float(opts.get("duration", 2.0)),
                        n_points=BEND_CURVE_POINTS)
    return run_bending_test(cfg, p)


def success_rate(obj, p: GripperParams, seed: int, protocol: GraspProtocol, trials: int) -> float | None:
    """The fraction of trials 0..``trials``-1 of ``obj`` that succeeded, among those that ended
    (None: none ended)."""
    ok = [bool(r["success"]) for r in (run_trial(obj, seed, i, params=p, protocol=protocol) for i in range(trials))
          if r["status"] == "ok"]
    return sum(ok) / len(ok) if ok else None


def envelope_response(p: GripperParams, opts: dict, seed: int, protocol: GraspProtocol) -> dict[str, float | None]:
    """Per shape, the smallest and largest width [m] held in ``trials`` grasps (the envelope's rule:
    :func:`gripper.objects.envelope_objects.point_held`; None: none held), on the grid ``sizes`` at
    one ``mass`` [kg] and ``friction`` (the envelope's defaults: 50 g, 0.6), as ``gripper envelope``
    finds its gripping range."""
    out: dict[str, float | None] = {}
    mass, mu, trials = float(opts.get("mass", 0.05)), float(opts.get("friction", 0.6)), int(opts.get("trials", 3))
    for shape in opts.get("shapes", list(SHAPES)):
        held = []
        for size in sorted(float(w) for w in opts.get("sizes", [0.03, 0.06, 0.09])):
            if point_held(success_rate(envelope_object(shape, size, mass, mu), p, seed, protocol, trials)):
                held.append(size)
        out[f"envelope_{shape}_smallest_m"] = held[0] if held else None
        out[f"envelope_{shape}_largest_m"] = held[-1] if held else None
    return out


def payload_response(p: GripperParams, opts: dict, seed: int, protocol: GraspProtocol) -> dict[str, float | None]:
    """The heaviest of ``masses`` [kg] held in ``trials`` grasps (the envelope's rule) of one
    ``shape`` and ``size`` [m] at ``friction``, as the envelope finds its payload (a lighter mass
    that fails does not stop the sweep: each mass is a point of its own)."""
    shape, size = str(opts.get("shape", "box")), float(opts.get("size", 0.06))
    mu, trials = float(opts.get("friction", 0.6)), int(opts.get("trials", 3))
    held = []
    for mass in sorted(float(m) for m in opts.get("masses", [0.2, 0.5, 1.0])):
        if point_held(success_rate(envelope_object(shape, size, mass, mu), p, seed, protocol, trials)):
            held.append(mass)
    return {payload_metric(opts): held[-1] if held else None}


def payload_metric(opts: dict) -> str:
    """The payload response's metric name: ``payload_<shape>_<size in mm>mm_kg``."""
    return f"payload_{opts.get('shape', 'box')}_{float(opts.get('size', 0.06)) * 1e3:g}mm_kg"


def parts_response(p: GripperParams, opts: dict, seed: int, protocol: GraspProtocol) -> dict[str, float | None]:
    """Per everyday part (:mod:`gripper.objects.everyday_parts`, its mesh built in a scratch
    folder), the fraction of ``trials`` grasps that succeeded (None: none ended)."""
    import tempfile

    from gripper.objects.everyday_parts import PARTS, everyday_part

    out: dict[str, float | None] = {}
    with tempfile.TemporaryDirectory(prefix="gripper-parts-") as tmp:
        for name in opts.get("parts", list(PARTS)):
            out[f"part_{name}_success_rate"] = success_rate(everyday_part(name, tmp), p, seed, protocol,
                                                            int(opts.get("trials", 5)))
    return out


def envelope_range(metrics: dict[str, float | None], shapes) -> float | None:
    """The envelope's total range [m]: per shape, its largest width held less its smallest,
    summed (None when a shape holds nothing: no range to compare)."""
    total = 0.0
    for shape in shapes:
        lo, hi = metrics.get(f"envelope_{shape}_smallest_m"), metrics.get(f"envelope_{shape}_largest_m")
        if lo is None or hi is None:
            return None
        total += hi - lo
    return total


def measure_responses(p: GripperParams, responses: dict, seed: int = 0, *, protocol: GraspProtocol | None = None,
                      placement: dict | None = None) -> tuple[dict[str, float | None], dict]:
    """(metrics, curves) of design ``p`` for the study file's ``[responses]`` table; grasp
    trials and pulls use ``seed``, ``protocol`` (default: the benchmark's) and each trial's
    sampled placement with ``placement``'s scales in place of the sampled ones
    (``{"friction_scale": 0.5}``). Raises whatever a response raises (the study records it)."""
    proto = protocol or GraspProtocol()
    scales = dict(placement or {})
    mesh_points = scales.pop("mesh_points", None)

    def placed(obj, i: int) -> Placement:
        return sample_placement(obj, TrialNoise(), seed, i).replace(**scales)

    def get(spec: str):
        obj = get_object(spec)
        return dataclasses.replace(obj, mesh_points=tuple(mesh_points)).validate() if mesh_points and obj.is_flex \
            else obj

    met: dict[str, float | None] = {}
    curves: dict[str, Any] = {}
    resp = responses
    if "bending" in resp or "tension_for_angle" in resp:
        res = _bending(p, resp.get("bending", {}))
        curves = {"r": res.r_command.tolist(), "bending_angle_deg": res.bending_angle_deg.tolist(),
                  "tension_N": res.tension_N.tolist()}
        if "bending" in resp:
            met["bending_angle_max_deg"] = float(res.bending_angle_deg.max())
            met["bending_angle_at_half_r_deg"] = float(np.interp(0.5 * res.r_command[-1], res.r_command,
                                                                 res.bending_angle_deg))
            met["tension_at_r_max_N"] = float(res.tension_N[-1])
        if "tension_for_angle" in resp:
            goal = float(resp["tension_for_angle"].get("angle_deg", 90.0))
            ang = np.maximum.accumulate(res.bending_angle_deg)
            met["tension_for_angle_N"] = (float(np.interp(goal, ang, res.tension_N))
                                          if ang[-1] >= goal else None)
    if "blocked_force" in resp:  # r: cable shortening as a fraction of finger length
        command = drive_for(p).shortening_command(float(resp["blocked_force"].get("r", 0.15)))
        met["blocked_tip_force_N"] = float(blocked_tip_force(p, [command])[0])
    if "grasp" in resp:
        g = resp["grasp"]
        for spec in g.get("objects", ["block"]):
            obj = get(spec)
            recs = [run_trial(obj, seed, i, params=p, protocol=proto, placement=placed(obj, i) if scales else None)
                    for i in range(int(g.get("trials", 5)))]
            o = recs[0].object
            ok = [r for r in recs if r["status"] == "ok"]
            met[f"grasp_{o}_success_rate"] = (sum(bool(r["success"]) for r in ok) / len(ok)) if ok else None
            met[f"grasp_{o}_median_peak_force_N"] = float(np.median([r["peak_total_force_N"] for r in recs]))
    if "envelope" in resp:
        met.update(envelope_response(p, resp["envelope"], seed, proto))
        met["envelope_range_m"] = envelope_range(met, resp["envelope"].get("shapes", list(SHAPES)))
    if "payload" in resp:
        met.update(payload_response(p, resp["payload"], seed, proto))
    if "parts" in resp:
        met.update(parts_response(p, resp["parts"], seed, proto))
    if "holding_force" in resp:
        h = resp["holding_force"]
        for spec in h.get("objects", ["block"]):
            obj = get(spec)
            pulls = [run_pullout(obj, params=p, protocol=proto, placement=placed(obj, i))["holding_force_N"]
                     for i in range(int(h.get("trials", 3)))]
            met[f"holding_{obj.name}_median_force_N"] = float(np.median(pulls))
    return met, curves
