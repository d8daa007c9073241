"""Checks of the continuum reference against things it did not compute itself: a uniform bar
meshed the same way against the closed-form end-moment curvature (linear tetrahedra lock in
bending; the default split keeps that small), and the static bend of the finger relaxed to rest
(the mesh-convergence figure). Measured in ``scripts/benchmarks/bench_calibration.py``.

Example:
    >>> from gripper.references.continuum_checks import beam_end_moment_check
    >>> beam_end_moment_check(theta=1.0)["error"]   # doctest: +SKIP
"""

from __future__ import annotations

import math
import time
from dataclasses import replace

import mujoco
import numpy as np

from gripper.core.params import GripperParams
from gripper.references.continuum import ReferenceFinger, rest_config
from gripper.references.finger_mesh import MeshResolution
from gripper.references.relaxation import relax_to_rest
from gripper.sim.stability import check_stable


def beam_end_moment_check(params: GripperParams | None = None,
                          mesh: MeshResolution | None = None, *, theta: float = 1.0,
                          settle_time: float = 2.0, material=None) -> dict:
    """The uniform-beam check: a bar of the finger's size, meshed the same way without cuts
    or channel, clamped like the reference and loaded by a pure end moment.

    The moment ``M = theta·EI/L_free`` (closed form: uniform curvature ``M/EI``, tip rotation
    ``theta``) is applied as a follower couple: nodal forces on the tip face, linear in the
    height and turned with the face at every step. Solved quasi-statically (5 ms implicit steps,
    heavily damped, until at rest).

    Measures, each against the closed form:

    * ``curvature_ratio``: curvature of the neutral axis (the node line at mid-height, averaged
      across the width) fitted over the free span less one bar height at each end, where the
      clamp and the concentrated end load disturb the field (Saint-Venant), times ``EI/M``.
      This is the measure the acceptance line is checked on.
    * ``ratio``: rotation of the loaded face (best-fit line) over ``theta``; it includes the
      local distortion under the nodal loads.
    * ``tip_error_frac``: neutral-axis tip position error over the free length, against the
      circular arc of radius ``EI/M``.

    Args:
        material: optional :class:`~gripper.core.params.Material` to use instead of the params'
            (e.g. another Poisson's ratio, to separate volumetric from shear locking).

    Returns:
        dict with the three measures, ``tip_angle_rad``, ``closed_form_rad``, ``nodes``,
        ``wall_time_s`` and ``max_speed`` (m/s, rest check).
    """
    p = (params or GripperParams()).validate()
    if material is not None:
        p = replace(p, material=material.validate())
    res = replace(mesh or MeshResolution(), uniform=True)
    cfg = rest_config(res)
    ref = ReferenceFinger(p, cfg)
    m, d = ref.model, ref.data
    g, mat = p.finger, p.material
    pts = ref.mesh.points
    tip = np.flatnonzero(np.isclose(pts[:, 0], g.length))
    tip_bodies = ref.body_of_node[tip]
    w = ref.weight[tip]
    s = pts[tip, 2] - np.average(pts[tip, 2], weights=w)
    L_free = g.length - cfg.clamp_length
    EI = mat.youngs_modulus * g.width * g.height ** 3 / 12.0
    M = theta * EI / L_free
    f = -M * ref.load_share * w * s / np.sum(w * s ** 2)
    t0 = time.perf_counter()
    _settle_under_follower_couple(ref, tip_bodies, s, f, settle_time, cfg.timestep)
    check_stable(m, d, "beam check")
    pos = ref.node_positions()
    ang = _face_rotation(s, pos[tip])
    z_axis, xs, line = _neutral_axis(ref, pos, 0.5 * g.height)
    kappa = _curvature(xs, line, cfg.clamp_length + g.height, g.length - g.height)
    # Closed-form tip of the neutral axis: a circular arc of radius EI/M from the clamp.
    rad = EI / M
    exact = np.array([cfg.clamp_length + rad * math.sin(theta),
                      z_axis + rad * (1 - math.cos(theta))])
    return {
        "curvature_ratio": float(kappa * EI / M),
        "tip_angle_rad": ang, "closed_form_rad": theta, "ratio": ang / theta,
        "tip_error_frac": float(np.linalg.norm(line[-1][[0, 2]] - exact) / L_free),
        "nodes": int(len(pts)), "wall_time_s": time.perf_counter() - t0,
        "max_speed": float(np.abs(d.qvel).max()),
    }


def _face_rotation(s: np.ndarray, cur: np.ndarray) -> float:
    """Rotation about -y of the loaded face [rad]: of the best-fit line through its nodes at
    positions ``cur`` [m], ``s`` [m] being their heights on the straight face."""
    return math.atan2(-np.polyfit(s, cur[:, 0], 1)[0], np.polyfit(s, cur[:, 2], 1)[0])


def _settle_under_follower_couple(ref: ReferenceFinger, tip_bodies: np.ndarray, s: np.ndarray,
                                  f: np.ndarray, settle_time: float, timestep: float) -> None:
    """Step ``ref`` for ``settle_time`` [s] under the end couple: nodal forces ``f`` [N] on the
    tip face's bodies (at heights ``s`` [m]), turned with the face at every step and ramped in
    over the first half."""
    m, d = ref.model, ref.data
    n = int(round(settle_time / timestep))
    ramp = 0.5 * settle_time
    for _ in range(n):
        ang = _face_rotation(s, d.xpos[tip_bodies])
        scale = min(1.0, d.time / ramp)
        d.xfrc_applied[tip_bodies, 0] = scale * f * math.cos(ang)
        d.xfrc_applied[tip_bodies, 2] = scale * f * math.sin(ang)
        mujoco.mj_step(m, d)


def _neutral_axis(ref: ReferenceFinger, pos: np.ndarray, z_mid: float
                  ) -> tuple[float, np.ndarray, np.ndarray]:
    """The neutral axis: the node level nearest mid-height ``z_mid`` [m], averaged across the
    width per station. Its height [m], the stations' x [m] and the axis points at ``pos`` [m]."""
    pts = ref.mesh.points
    levels = np.unique(np.round(pts[:, 2], 12))
    z_axis = levels[np.argmin(np.abs(levels - z_mid))]
    on_axis = np.flatnonzero(np.isclose(pts[:, 2], z_axis))
    xs = np.unique(np.round(pts[on_axis, 0], 12))
    line = np.array([ref.centroid(on_axis[np.isclose(pts[on_axis, 0], x)], pos) for x in xs])
    return z_axis, xs, line


def _curvature(xs: np.ndarray, line: np.ndarray, lo: float, hi: float) -> float:
    """Curvature [1/m] of the axis ``line`` (points at stations ``xs`` [m]): the slope of its
    segments' angle along x, fitted over the stations in [``lo``, ``hi``]."""
    phi = np.unwrap(np.arctan2(np.diff(line[:, 2]), np.diff(line[:, 0])))
    s_mid = 0.5 * (xs[1:] + xs[:-1])
    inner = (s_mid >= lo) & (s_mid <= hi)
    return np.polyfit(s_mid[inner], phi[inner], 1)[0]


def static_bend(params: GripperParams | None = None, mesh: MeshResolution | None = None, *,
                tension: float = 0.15, ramp_time: float = 1.0, rest_tol_deg: float = 0.02,
                max_time: float = 20.0, damping_ratio: float = 0.5) -> dict:
    """The reference finger at rest under a constant cable ``tension`` [N] (mesh convergence).

    Quasi-static: 5 ms implicit steps, the tension ramped over ``ramp_time`` [s], the first
    mode damped with ``damping_ratio``; then held in 0.5 s chunks until the bending angle moves
    less than ``rest_tol_deg`` [deg] over a chunk (at most ``max_time`` [s] in all). A fixed
    2 s (1 s ramp, 1 s hold) stopped the default mesh 1.2° short of rest: the bent finger's
    slowest mode creeps under the heavy damping.

    Returns:
        dict with ``bending_angle_deg`` (B1 to the tip element), ``element_angles_deg``,
        ``tip_xz_m``, ``nodes``, ``settle_time_s`` (simulated), ``wall_time_s`` and
        ``max_speed`` (m/s, rest check).

    Raises:
        SimulationUnstable: MuJoCo warned or the state became non-finite, or the finger did
            not come to rest within ``max_time``.
    """
    cfg = replace(rest_config(mesh or MeshResolution()), damping_ratio=damping_ratio)
    ref = ReferenceFinger(params, cfg)
    t0 = time.perf_counter()
    angles, tip, _ = relax_to_rest(ref, tension, ramp_time=ramp_time, rest_tol_deg=rest_tol_deg,
                                   max_time=max_time, what="static bend")
    d = ref.data
    deg = np.degrees(angles)
    return {"bending_angle_deg": float(deg[-1] - deg[0]), "element_angles_deg": deg.tolist(),
            "tip_xz_m": tip.tolist(), "nodes": ref.mesh.n_nodes, "settle_time_s": float(d.time),
            "wall_time_s": time.perf_counter() - t0, "max_speed": float(np.abs(d.qvel).max())}


__all__ = ["beam_end_moment_check", "static_bend"]
