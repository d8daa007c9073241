"""Mesh convergence of the continuum reference: Richardson extrapolation, grid convergence index
and the stiffness correction the default mesh needs.

The bending compliance at a small check load is one sparse linear solve on each mesh
(scikit-fem on the reference's own tetrahedra), so meshes refined systematically give a
Richardson extrapolation, a grid convergence index and the stiffness correction the default
mesh needs. Method and figures: ``docs/calibration.md``, "How convergence is measured".

Example:
    >>> from gripper.references.convergence import mesh_convergence
    >>> conv = mesh_convergence()                      # doctest: +SKIP
    >>> conv.stiffness_correction                      # doctest: +SKIP
"""

from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass, replace
from typing import Any

import numpy as np

from gripper.core.params import GripperParams
from gripper.references.finger_mesh import FingerMesh, MeshResolution, finger_mesh

CHECK_TENSION = 0.01  # N: the small check load (the solve is linear; results are per newton)
DIRECT_SOLVE_MAX_DOFS = 60000  # reduced flexible multibody systems up to this size: sparse LU
MEASURE_SCALE = 1e-4  # -, the linear solution is read at this fraction of the check load
CONVERGED_RTOL = 1e-5  # -, changes below this fraction between meshes count as converged
GCI_SAFETY_FACTOR = 1.25  # -, Celik et al. (2008) for three or more grids
DEFAULT_SCALES = (1, 2, 3, 4)  # the default mesh and three systematically refined ones


def rigid_body_modes(doflocs: np.ndarray) -> np.ndarray:
    """The six rigid-body modes (three translations, three rotations about the origin) of a 3D
    elasticity dof layout that interleaves x, y, z, from each dof's location (shape (3, ndofs)):
    the near-null space smoothed aggregation needs. Shape (ndofs, 6)."""
    n = doflocs.shape[1]
    comp = np.arange(n) % 3
    x, y, z = doflocs
    B = np.zeros((n, 6))
    for c in range(3):
        B[comp == c, c] = 1.0
    for k, (c1, v1, c2, v2) in enumerate(((0, -y, 1, x), (1, -z, 2, y), (2, -x, 0, z))):
        B[comp == c1, 3 + k] = v1[comp == c1]
        B[comp == c2, 3 + k] = v2[comp == c2]
    return B


def solve_clamped(K, f: np.ndarray, fixed: np.ndarray, doflocs: np.ndarray,
                  rtol: float = 1e-10) -> np.ndarray:
    """``K u = f`` with ``u = 0`` on the dofs ``fixed``, for a 3D elasticity matrix whose dofs
    interleave x, y, z: conjugate gradients preconditioned by smoothed aggregation (pyamg) with
    the six rigid-body modes (from ``doflocs``, shape (3, ndofs)) as its near-null space."""
    import pyamg
    from scipy.sparse.linalg import cg

    n = K.shape[0]
    free = np.setdiff1d(np.arange(n), fixed)
    A = K[free][:, free].tocsr()
    ml = pyamg.smoothed_aggregation_solver(A, B=rigid_body_modes(doflocs)[free])
    sol, info = cg(A, f[free], rtol=rtol, maxiter=5000, M=ml.aspreconditioner())
    if info != 0:
        raise RuntimeError(f"linear solve: conjugate gradients did not converge (info {info})")
    u = np.zeros(n)
    u[free] = sol
    return u


@dataclass(frozen=True)
class LinearFinger:
    """The continuum finger's linear elastic model: the mesh, its scikit-fem vector basis,
    stiffness ``K``, the cable's load at 1 N of tension (the knot's -T along x, spread over the
    anchor nodes as the reference does; halved on a symmetric half mesh, ``share``) and the
    clamped dofs (B1's clamped length, and the symmetry plane's normal dofs)."""

    mesh: FingerMesh
    basis: Any  # skfem.Basis (scikit-fem is imported where it is used)
    K: Any  # scipy.sparse matrix
    load_per_newton: np.ndarray
    fixed: np.ndarray
    share: float


def linear_finger(p: GripperParams, res: MeshResolution, *, clamp_length: float,
                  youngs_modulus: float | None = None, poisson_ratio: float | None = None) -> LinearFinger:
    """Assemble :class:`LinearFinger` for ``p`` on mesh ``res`` (the material's E and nu unless
    given)."""
    import skfem
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    fm = finger_mesh(p.finger, res)
    skmesh = skfem.MeshTet(np.ascontiguousarray(fm.points.T), np.ascontiguousarray(fm.tets.T))
    basis = skfem.Basis(skmesh, skfem.ElementVector(skfem.ElementTetP1()))
    e = p.material.youngs_modulus if youngs_modulus is None else youngs_modulus
    nu = p.material.poisson_ratio if poisson_ratio is None else poisson_ratio
    K = skfem.asm(linear_elasticity(*lame_parameters(e, nu)), basis)
    f = np.zeros(basis.N)
    share = 0.5 if fm.symmetric else 1.0
    w = fm.node_weight[fm.anchor_nodes]
    f[basis.nodal_dofs[0, fm.anchor_nodes]] = -share * w / w.sum()
    fixed_parts = [basis.nodal_dofs[:, fm.points[:, 0] <= clamp_length + 1e-9].ravel()]
    if fm.symmetric:
        fixed_parts.append(basis.nodal_dofs[1, fm.plane_nodes])
    return LinearFinger(mesh=fm, basis=basis, K=K, load_per_newton=f,
                        fixed=np.unique(np.concatenate(fixed_parts)), share=share)


def linear_compliance(params: GripperParams | None = None, mesh: MeshResolution | None = None,
                      *, clamp_length: float = 0.008, poisson_ratio: float | None = None,
                      fmbs=None) -> dict:
    """Small-load bending compliance of a reference's discretisation on ``mesh`` [deg/N].

    Args:
        clamp_length: length of B1 held by the mount [m] (``ReferenceConfig.clamp_length``).
        poisson_ratio: override the material's (to separate volumetric locking).
        fmbs: a :class:`~gripper.references.fmbs.FmbsConfig` to solve paper 000's flexible
            multibody model instead of the continuum body: the elements' meshes with split
            bridges, the bridge zones and the knot zone rigid (each node's displacement a
            rigid motion of its zone, planar), each bridge's two zones pinned at the hinge axis
            with the torsion spring on their relative rotation (:mod:`gripper.references.fmbs`).

    Returns:
        dict with ``compliance_deg_per_N`` (bending B1 to B6 per newton of cable tension),
        ``element_compliance_deg_per_N`` (each element's angle per newton), ``nodes``,
        ``tets`` and ``wall_time_s``.
    """
    from gripper.references.continuum import kabsch_angles

    p = (params or GripperParams()).validate()
    t0 = time.perf_counter()
    res = mesh or MeshResolution()
    if fmbs is not None:
        res = replace(res, split_bridges=True)
    lf = linear_finger(p, res, clamp_length=clamp_length, poisson_ratio=poisson_ratio)
    fm, basis, K, fixed, share = lf.mesh, lf.basis, lf.K, lf.fixed, lf.share
    f = CHECK_TENSION * lf.load_per_newton
    if fmbs is None:
        u = solve_clamped(K, f, fixed, basis.doflocs)
    else:
        u = _solve_fmbs(p, fm, K, f, fixed, basis, fmbs.hinge_stiffness * share, clamp_length)
    # A linear displacement field is a rotation only to first order: measure it scaled down to
    # microradians, where the best fit reads it exactly (at full scale, 16° of bending read
    # 2.5 % low: the best fit of a linearised rotation theta turns by atan(theta)).
    cur = fm.points + MEASURE_SCALE * u[basis.nodal_dofs].T
    angles, _ = kabsch_angles(fm, cur, list(fm.nodes_of_element), list(fm.element_volume_weights))
    deg = np.degrees(angles - angles[0]) / (MEASURE_SCALE * CHECK_TENSION)
    return {"compliance_deg_per_N": float(deg[-1]), "element_compliance_deg_per_N": deg.tolist(),
            "nodes": fm.n_nodes, "tets": int(len(fm.tets)), "wall_time_s": time.perf_counter() - t0}


def _solve_fmbs(p: GripperParams, fm, K, f: np.ndarray, fixed: np.ndarray, basis,
                k_hinge: float, clamp_length: float) -> np.ndarray:
    """The flexible multibody model's linear solve: u = P q, with q the free nodes' own dofs and
    the rigid zones' planar dofs (see :func:`linear_compliance`)."""
    import scipy.sparse as sp
    from scipy.sparse.linalg import spsolve

    pts = fm.points
    n = basis.N
    nd = basis.nodal_dofs  # (3, nodes)
    from gripper.references.fmbs import rigid_zones

    bodies = rigid_zones(p, fm, exclude=np.flatnonzero(fm.points[:, 0] <= clamp_length + 1e-9))
    in_body = np.zeros(len(pts), dtype=bool)
    for nodes, _, _ in bodies:
        in_body[nodes] = True
    fixed_mask = np.zeros(n, dtype=bool)
    fixed_mask[fixed] = True
    own = [d for d in range(n) if not fixed_mask[d] and not in_body[d // 3]]
    rows, cols, vals = list(own), list(range(len(own))), [1.0] * len(own)
    col = len(own)
    body_cols: list[tuple[int, int, list[tuple[int, float]]]] = []
    for nodes, origin, parent in bodies:
        if parent < 0:  # x and z slides and a rotation of its own
            ux, uz, th = col, col + 1, col + 2
            col += 3
            rot = [(th, 1.0)]
        else:  # the parent's slides, the parent's rotation plus the hinge angle
            ux, uz, th_p = body_cols[parent]
            phi = col
            col += 1
            rot = [(th_p[0][0], 1.0), (phi, 1.0)]
        body_cols.append((ux, uz, rot))
        r = pts[nodes] - origin
        for i, (rx, rz) in zip(nodes, r[:, [0, 2]], strict=True):
            dx, dz = nd[0, i], nd[2, i]
            rows += [dx, dz]
            cols += [ux, uz]
            vals += [1.0, 1.0]
            for c, s in rot:  # rotation about -y by theta: (dx, dz) = theta (-rz, rx)
                rows += [dx, dz]
                cols += [c, c]
                vals += [-s * rz, s * rx]
    P = sp.csr_matrix((vals, (rows, cols)), shape=(n, col))
    Kr = (P.T @ K @ P).tolil()
    hinge_cols = [body_cols[b][2][1][0] for b in range(len(bodies)) if bodies[b][2] >= 0]
    for c in hinge_cols:
        Kr[c, c] += k_hinge
    Kr = Kr.tocsr()
    fr = P.T @ f
    if Kr.shape[0] < DIRECT_SOLVE_MAX_DOFS:
        return P @ spsolve(Kr.tocsc(), fr)
    # Large meshes: conjugate gradients on the reduced system, preconditioned by smoothed
    # aggregation with the rigid-body modes projected onto the reduced dofs.
    import pyamg
    from scipy.sparse.linalg import cg

    B = rigid_body_modes(basis.doflocs)
    PtP = (P.T @ P).tocsc()
    Br = np.column_stack([spsolve(PtP, P.T @ B[:, i]) for i in range(6)])
    ml = pyamg.smoothed_aggregation_solver(Kr, B=Br)
    q, info = cg(Kr, fr, rtol=1e-10, maxiter=5000, M=ml.aspreconditioner())
    if info != 0:
        raise RuntimeError(f"linear solve: conjugate gradients did not converge (info {info})")
    return P @ q


@dataclass(frozen=True)
class Richardson:
    """Richardson extrapolation of three solutions on systematically refined meshes.

    Attributes:
        h: relative cell sizes, coarse to fine [-].
        f: the solutions on them.
        order: observed order of convergence p [-].
        extrapolated: the extrapolated solution f(h -> 0).
        gci_fine: grid convergence index of the finest solution [-] (relative).
        asymptotic_ratio: GCI_coarse / (r^p GCI_fine), near 1 in the asymptotic range [-].
    """

    h: tuple[float, float, float]
    f: tuple[float, float, float]
    order: float
    extrapolated: float
    gci_fine: float
    asymptotic_ratio: float


def richardson(h: tuple[float, ...], f: tuple[float, ...]) -> Richardson:
    """Extrapolate ``f(h)`` from three meshes (``h`` coarse to fine, any refinement ratios).

    Solves ``f = f0 + C h^p`` through the three points for the observed order ``p``.

    Raises:
        ValueError: not three meshes, not refined monotonically, or oscillatory convergence
            (no observed order exists).
    """
    from scipy.optimize import brentq

    if len(h) != 3 or len(f) != 3:
        raise ValueError("richardson: needs exactly three meshes")
    h3, f3 = np.asarray(h, float), np.asarray(f, float)
    if not (h3[0] > h3[1] > h3[2] > 0):
        raise ValueError(f"richardson: cell sizes must decrease, got {h}")
    e21, e32 = f3[1] - f3[0], f3[2] - f3[1]
    if max(abs(e21), abs(e32)) <= CONVERGED_RTOL * abs(f3[2]):
        # Already converged to the solver's precision: no order to observe; the finest stands.
        return Richardson(h=tuple(h3), f=tuple(f3), order=float("inf"), extrapolated=float(f3[2]),
                          gci_fine=float(abs(e32 / f3[2])), asymptotic_ratio=1.0)
    if e21 == 0 or e32 / e21 <= 0:
        raise ValueError(f"richardson: oscillatory or converged solutions {f}: no observed order")

    def resid(p: float) -> float:
        return e21 / e32 - (h3[0] ** p - h3[1] ** p) / (h3[1] ** p - h3[2] ** p)

    p = brentq(resid, 0.05, 10.0)
    c = e32 / (h3[2] ** p - h3[1] ** p)
    f0 = f3[2] - c * h3[2] ** p
    r21, r32 = h3[1] / h3[2], h3[0] / h3[1]
    gci_fine = GCI_SAFETY_FACTOR * abs(e32 / f3[2]) / (r21 ** p - 1.0)
    gci_coarse = GCI_SAFETY_FACTOR * abs(e21 / f3[1]) / (r32 ** p - 1.0)
    return Richardson(h=tuple(h3), f=tuple(f3), order=float(p), extrapolated=float(f0),
                      gci_fine=float(gci_fine),
                      asymptotic_ratio=float(gci_coarse / (r21 ** p * gci_fine)))


@dataclass(frozen=True)
class MeshConvergence:
    """The continuum reference's mesh convergence at the small check load.

    Attributes:
        scales: refinement factors solved (the first is the default mesh) [-].
        nodes: node count of each mesh [-].
        compliance_deg_per_N: bending compliance on each mesh [deg/N].
        richardson: extrapolation from the three finest meshes.
        default_error: default mesh's compliance over the extrapolated, minus 1 [-].
        stiffness_correction: factor on Young's modulus that gives the default mesh the
            extrapolated compliance, ``f_default / f_extrapolated`` [-].
        wall_time_s: time of all the solves [s].
    """

    scales: tuple[int, ...]
    nodes: tuple[int, ...]
    compliance_deg_per_N: tuple[float, ...]
    richardson: Richardson
    default_error: float
    stiffness_correction: float
    wall_time_s: float

    def to_dict(self) -> dict:
        return asdict(self)


def mesh_convergence(params: GripperParams | None = None, mesh: MeshResolution | None = None,
                     *, scales: tuple[int, ...] = DEFAULT_SCALES, clamp_length: float = 0.008,
                     fmbs=None, on_progress=None) -> MeshConvergence:
    """Solve the reference's small-load bending on ``scales`` (the first the default) and
    extrapolate from the three finest (see the module docstring).

    With ``fmbs`` (a :class:`~gripper.references.fmbs.FmbsConfig`) the flexible multibody
    model is solved instead. Its hinges' share of the compliance, ``n·lever/K``, is exact on
    every mesh, so the stiffness correction applies to the elements' share alone:
    ``(f_default - f_hinges) / (f_extrapolated - f_hinges)``.

    Raises:
        ValueError: fewer than four scales, or scales not increasing.
    """
    if len(scales) < 4 or list(scales) != sorted(set(scales)):
        raise ValueError(f"convergence scales: need at least four increasing values, got {scales}")
    base = mesh or MeshResolution()
    say = on_progress or (lambda msg: None)
    t0 = time.perf_counter()
    nodes, comp = [], []
    for s in scales:
        res = linear_compliance(params, replace(base, scale=base.scale * s),
                                clamp_length=clamp_length, fmbs=fmbs)
        nodes.append(res["nodes"])
        comp.append(res["compliance_deg_per_N"])
        say(f"mesh x{s}: {res['nodes']} nodes, {comp[-1]:.1f} deg/N ({res['wall_time_s']:.0f} s)")
    fine = scales[-3:]
    rich = richardson(tuple(1.0 / s for s in fine), tuple(comp[-3:]))
    hinges = 0.0
    if fmbs is not None:
        g = (params or GripperParams()).finger
        hinges = math.degrees(g.n_hinges * (g.hole_height - g.hinge_z) / fmbs.hinge_stiffness)
    return MeshConvergence(scales=tuple(scales), nodes=tuple(nodes),
                           compliance_deg_per_N=tuple(comp), richardson=rich,
                           default_error=comp[0] / rich.extrapolated - 1.0,
                           stiffness_correction=_element_correction(comp[0], rich.extrapolated,
                                                                    hinges),
                           wall_time_s=time.perf_counter() - t0)


def _element_correction(f_default: float, f_extrapolated: float, hinges: float) -> float:
    """``(f_default - hinges) / (f_extrapolated - hinges)``: the modulus factor that gives the
    default mesh's elements the extrapolated compliance. 1 when the elements' share is below
    1 % of the whole (their mesh error is then immaterial, and the ratio of two small
    differences is noise)."""
    elem0, elem1 = f_extrapolated - hinges, f_default - hinges
    if abs(elem0) < 0.01 * abs(f_extrapolated) or elem1 / elem0 <= 0:
        return 1.0
    return elem1 / elem0


def format_convergence(conv: MeshConvergence) -> str:
    """The convergence table as Markdown."""
    rows = ["| mesh (cell size) | nodes | bending compliance deg/N | vs extrapolated |",
            "|---|---|---|---|"]
    f0 = conv.richardson.extrapolated
    for s, n, f in zip(conv.scales, conv.nodes, conv.compliance_deg_per_N, strict=True):
        rows.append(f"| x{s} (h/{s}) | {n} | {f:.1f} | {100 * (f / f0 - 1):+.1f} % |")
    r = conv.richardson
    rows.append(f"| extrapolated (p = {r.order:.2f}) | | {f0:.1f} | GCI of the finest "
                f"{100 * r.gci_fine:.1f} % |")
    return "\n".join(rows) + "\n"


__all__ = ["CHECK_TENSION", "MeshConvergence", "Richardson", "format_convergence",
           "linear_compliance", "mesh_convergence", "richardson", "solve_clamped"]
