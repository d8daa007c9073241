"""The hinge-chain finger in contact, checked against the continuum body (issue 44, item 3).

Two tests, each run on the hinge chain (:func:`gripper.model.builders.build_bending_spec`: one
finger clamped at B1, bending in the horizontal plane, grasping face towards world +y) and on
the continuum reference's discretisation of the same body
(:func:`gripper.references.finger_mesh.finger_mesh`, clamped over ``clamp_length`` as in
:func:`gripper.references.convergence.linear_compliance`):

* **Blocked tip.** The finger straight, a rigid frictionless stop touching the tip element's
  distal edge on the grasping side (the line x = L, z = height of the finger frame, across the
  width); the cable pulled with tension T; the stop's reaction.

  - Continuum (:func:`blocked_tip_force_continuum`): the linear scikit-fem model of
    ``linear_compliance`` (same mesh, knot load and clamp) with the displacement normal to the
    stop (finger z) of the distal edge's nodes held at zero, a Dirichlet condition; the
    reaction is ``K u - f`` at those dofs, summed, times 2 for the symmetric half mesh. The
    finger straight, every via point of the cable is on one line, so the cable's only load is
    the knot's ``-T`` along x, as in ``linear_compliance``.
  - Chain (:func:`blocked_tip_force_chain`): a world-fixed box on the grasping side whose face
    touches the tip element's grasping face over its distal part (frictionless: ``condim`` 1 at
    a higher priority), the servo switched off (MuJoCo's actuation disabled) and the reel's
    slide joint pulled with a constant generalised force T, which the cable's tendon limit
    carries to the finger as tension T (the tension sensor reads T at rest); run to rest, the
    stop's contact normal forces summed (``mj_contactForce``).

* **Cylinder.** The finger closes on a rigid world-fixed cylinder (axis along the hinge axes)
  that touches the two edges of the middle cut's opening on the grasping face (the cut between
  B3 and B4 at x = L/2): :func:`cylinder_contact_chain` and, on the MuJoCo flex reference with
  the cylinder in its scene, :func:`cylinder_contact_continuum`.

Where each holds, and the measured numbers: ``docs/calibration.md``, "The finger in contact".

Example:
    >>> from gripper.calibration.contact_check import blocked_tip_linear
    >>> blocked_tip_linear().force_per_newton        # doctest: +SKIP
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass

import mujoco
import numpy as np

from gripper.core.params import GripperParams
from gripper.core.resources import DEFAULT_CALIBRATION_DIR
from gripper.model.builders import build_bending_spec
from gripper.model.names import FingerNames
from gripper.references.convergence import MEASURE_SCALE, solve_clamped
from gripper.references.finger_mesh import MeshResolution, finger_mesh

CLAMP_LENGTH = 0.008  # m, the reference's clamp (ReferenceConfig.clamp_length)
# Tensions of the blocked-tip comparison [N]: the small-load range where both models stay
# near straight (largest hinge angle under about 6°, see SMALL_ROTATION_DEG).
LINEAR_TENSIONS = (0.002, 0.005, 0.01, 0.015, 0.02)
# The grasp controller's range of cable tensions [N] (GRIP_TENSION is 5 N).
SET_POINT_TENSIONS = (0.5, 1.0, 2.0, 3.5, 5.0)
# deg: the largest hinge angle up to which the linear model counts as small-rotation
SMALL_ROTATION_DEG = 6.0
CYLINDER_DIAMETERS = (0.020, 0.040, 0.060)  # m


def committed_modulus_factor() -> float:
    """The default design's stiffness correction (the committed convergence study's
    ``stiffness_correction``): the factor on Young's modulus that gives the default mesh the
    converged compliance [-]. It scales every displacement of the linear model and none of its
    reactions."""
    conv = json.loads((DEFAULT_CALIBRATION_DIR / "convergence.json").read_text())
    return float(conv["stiffness_correction"])


@dataclass(frozen=True)
class BlockedTipLinear:
    """The blocked-tip test on the continuum body, linear (per newton of cable tension).

    Attributes:
        force_per_newton: the stop's reaction per newton of tension [N/N].
        edge_reactions_per_newton: each distal-edge node's share of it (the whole body's: a
            node off the symmetry plane counts with its mirror image), finger y from 0 to
            the side [N/N]; all positive when the whole edge presses on the stop.
        hinge_deg_per_newton: each hinge's angle (B(j+1) against Bj, positive closing the
            cut) per newton [deg/N], with ``modulus_factor``.
        free_hinge_deg_per_newton: the same without the stop [deg/N].
        cut_closing_tension: the tension at which the first cut's faces meet at the grasping
            face, from the displacement of its two corners across the width [N].
        small_rotation_tension: the tension at which the largest hinge angle reaches
            ``SMALL_ROTATION_DEG`` [N].
        modulus_factor: factor on Young's modulus [-] (sets the angles, not the force).
        nodes: mesh nodes [-].
        wall_time_s: [s].
    """

    force_per_newton: float
    edge_reactions_per_newton: tuple[float, ...]
    hinge_deg_per_newton: tuple[float, ...]
    free_hinge_deg_per_newton: tuple[float, ...]
    cut_closing_tension: float
    small_rotation_tension: float
    modulus_factor: float
    nodes: int
    wall_time_s: float


def blocked_tip_linear(params: GripperParams | None = None, mesh: MeshResolution | None = None, *,
                       clamp_length: float = CLAMP_LENGTH,
                       modulus_factor: float | None = None) -> BlockedTipLinear:
    """The blocked-tip test on the continuum body's linear model (see the module docstring).

    Args:
        mesh: the mesh (default: the reference's).
        clamp_length: length of B1 held by the mount [m].
        modulus_factor: factor on Young's modulus; default :func:`committed_modulus_factor`
            (the default design's; it scales the angles and limits, never the force).
    """
    import skfem
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    from gripper.references.continuum import kabsch_angles

    t0 = time.perf_counter()
    p = (params or GripperParams()).validate()
    g = p.finger
    factor = committed_modulus_factor() if modulus_factor is None else float(modulus_factor)
    fm = finger_mesh(g, mesh or MeshResolution())
    pts = fm.points
    skmesh = skfem.MeshTet(np.ascontiguousarray(pts.T), np.ascontiguousarray(fm.tets.T))
    basis = skfem.Basis(skmesh, skfem.ElementVector(skfem.ElementTetP1()))
    lam, mu = lame_parameters(p.material.youngs_modulus * factor, p.material.poisson_ratio)
    K = skfem.asm(linear_elasticity(lam, mu), basis)
    nd = basis.nodal_dofs
    share = 0.5 if fm.symmetric else 1.0
    f = np.zeros(basis.N)  # 1 N of tension: the knot's -T along x, spread as the reference does
    w = fm.node_weight[fm.anchor_nodes]
    f[nd[0, fm.anchor_nodes]] = -share * w / w.sum()
    clamp = [nd[:, pts[:, 0] <= clamp_length + 1e-9].ravel()]
    if fm.symmetric:
        clamp.append(nd[1, fm.plane_nodes])
    edge = np.flatnonzero(np.isclose(pts[:, 0], g.length) & np.isclose(pts[:, 2], g.height))
    edge = edge[np.argsort(pts[edge, 1])]
    hinges = []
    u_blocked = None
    for blocked in (False, True):
        fixed = np.unique(np.concatenate(clamp + ([nd[2, edge]] if blocked else [])))
        u = solve_clamped(K, f, fixed, basis.doflocs)
        # Read the rotations of the linear field scaled to microradians (linear_compliance).
        cur = pts + MEASURE_SCALE * u[nd].T
        angles, _ = kabsch_angles(fm, cur, list(fm.nodes_of_element), list(fm.element_volume_weights))
        hinges.append(np.degrees(np.diff(angles)) / MEASURE_SCALE)
        u_blocked = u
    assert u_blocked is not None
    reaction = (K @ u_blocked - f)[nd[2, edge]]  # on the finger, along z: the stop pushes back
    edge_force = -reaction / share
    hinge_blocked = hinges[1]
    opening_rate = _cut_closing_rates(fm, g, u_blocked[nd].T)
    closing = opening_rate > 0
    gap = 2.0 * g.cut_half_width
    cut_closing = float(gap / opening_rate[closing].max()) if closing.any() else math.inf
    return BlockedTipLinear(
        force_per_newton=float(edge_force.sum()),
        edge_reactions_per_newton=tuple(float(x) for x in edge_force),
        hinge_deg_per_newton=tuple(float(x) for x in hinge_blocked),
        free_hinge_deg_per_newton=tuple(float(x) for x in hinges[0]),
        cut_closing_tension=cut_closing,
        small_rotation_tension=float(SMALL_ROTATION_DEG / np.abs(hinge_blocked).max()),
        modulus_factor=factor, nodes=fm.n_nodes, wall_time_s=time.perf_counter() - t0)


def _cut_closing_rates(fm, g, disp: np.ndarray) -> np.ndarray:
    """Per cut, how fast its opening at the grasping face closes [m per newton]: the x
    displacement of the distal element's proximal top corner less the proximal element's
    distal top corner, each averaged over the width (positive closes the cut)."""
    pts = fm.points
    top = np.isclose(pts[:, 2], g.height)
    rates = []
    for j in range(1, g.n_segments):
        x_cut = j * g.pitch
        prox = np.intersect1d(fm.nodes_of_element[j - 1], np.flatnonzero(top))
        dist = np.intersect1d(fm.nodes_of_element[j], np.flatnonzero(top))
        a = prox[np.isclose(pts[prox, 0], x_cut - g.cut_half_width)]
        b = dist[np.isclose(pts[dist, 0], x_cut + g.cut_half_width)]
        ua = np.average(disp[a, 0], weights=fm.node_weight[a])
        ub = np.average(disp[b, 0], weights=fm.node_weight[b])
        rates.append(ua - ub)
    return np.asarray(rates)


def blocked_tip_force_continuum(params: GripperParams | None, tensions, *,
                                mesh: MeshResolution | None = None,
                                max_hinge_deg: float = SMALL_ROTATION_DEG) -> np.ndarray:
    """The stop's reaction on the continuum body's blocked tip [N], one per tension [N].

    Linear in the tension (:func:`blocked_tip_linear`, solved once per newton and scaled).

    Raises:
        ValueError: a tension at which the linear model's largest hinge angle passes
            ``max_hinge_deg`` (default ``SMALL_ROTATION_DEG``), or at which a cut would close:
            there the finger is no longer near straight, and the linear model (no large
            rotations, no contact between cut faces) does not describe it.
    """
    t = np.asarray(tensions, dtype=float)
    lin = blocked_tip_linear(params, mesh)
    limit = min(lin.small_rotation_tension * max_hinge_deg / SMALL_ROTATION_DEG, lin.cut_closing_tension)
    if np.any(t < 0) or np.any(t > limit):
        raise ValueError(f"blocked tip, continuum: tensions must be in [0, {limit:.3g}] N, where the "
                         f"linear model's hinges stay under {max_hinge_deg:g}° and its cuts open "
                         f"({np.abs(lin.hinge_deg_per_newton).max():.0f}°/N blocked; the first cut "
                         f"closes at {lin.cut_closing_tension:.3g} N); got {t.max():g} N")
    return lin.force_per_newton * t
