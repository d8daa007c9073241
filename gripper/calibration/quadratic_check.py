"""Independent check of the continuum reference: quadratic tetrahedra (scikit-fem on a gmsh mesh).

The continuum reference (:mod:`gripper.references.continuum`) is MuJoCo's flex of linear
tetrahedra on a mapped mesh written here. This module solves the same body, clamp and small
load with a second, independent discretisation: gmsh meshes the finger's solid (a box less the
triangular cuts and the square cable channel, exactly as :mod:`gripper.references.finger_mesh`
describes it) into tetrahedra, and scikit-fem solves small-strain linear elasticity on them with
quadratic (10-node, ``ElementTetP2``) shape functions, which do not lock in bending and lock far
less than linear ones at Poisson's ratio 0.48.

Load: at small tension the cable is straight, so every via point's net force ``T (u_out -
u_in)`` vanishes and only the knot at the tip carries ``-T`` along x (see the reference's
docstring). Here it is a uniform traction on a band of the tip's distal face around the channel
opening: the same resultant on the same line of action (the hole axis). Clamp: every node with
``x <= clamp_length`` is fixed, as in the reference. Only the half y >= 0 is meshed, with the
symmetry condition ``u_y = 0`` on the plane y = 0.

Measure (of the linear solution scaled to microradians, where a best fit reads a linearised
rotation exactly): the small-load bending compliance ``d(bending)/dT`` [deg/N], bending being the
best-fit rotation of the tip element B6 relative to the base element B1 (over each element's
mesh vertices, as the reference measures it).

This is a development check (``pip install -e ".[dev]"`` brings scikit-fem, gmsh and meshio);
nothing else in the package imports it.

Example:
    >>> from gripper.calibration.quadratic_check import quadratic_compliance
    >>> quadratic_compliance(size=1.5e-3)["compliance_deg_per_N"]    # doctest: +SKIP
"""

from __future__ import annotations

import math
import time

import numpy as np

from gripper.core.params import FingerGeometry, GripperParams
from gripper.references.convergence import CHECK_TENSION, MEASURE_SCALE, solve_clamped
from gripper.references.finger_mesh import channel_side

KNOT_BAND = 1.0e-3  # m: width of the traction band around the channel opening on the tip face


def _gmsh_mesh(p: GripperParams, size: float, bridge_size: float
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The half body (y >= 0) meshed by gmsh into 4-node tetrahedra: node coordinates [m], each
    tetrahedron's node indices and each knot-patch triangle's node indices.

    ``size``: largest edge [m]; ``bridge_size``: edge on the cuts' apex lines [m].
    """
    import gmsh

    g = p.finger
    a = channel_side(g)
    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("finger")
        solid = _half_body(g, a)
        _add_knot_patch(g, a, solid)
        _grade_towards_apexes(g, _apex_lines(g), size, bridge_size)
        gmsh.model.mesh.generate(3)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        etypes, _, enodes = gmsh.model.mesh.getElements(3)
        tet = np.asarray(enodes[list(etypes).index(4)], dtype=np.int64).reshape(-1, 4)
        patch = _knot_patch_triangles(g, a)
    finally:
        gmsh.finalize()
    index = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(len(tags))
    return coords.reshape(-1, 3), index[tet], index[patch]


def _half_body(g: FingerGeometry, a: float) -> tuple[int, int]:
    """The half body as an OCC solid: a box less the triangular cuts and the square channel of
    side ``a`` [m]."""
    import gmsh

    occ = gmsh.model.occ
    L, W, H = g.length, g.width, g.height
    tan_half = math.tan(0.5 * math.radians(g.cut_angle_deg))
    body = occ.addBox(0.0, 0.0, 0.0, L, 0.5 * W, H)
    tools = []
    for e in range(1, g.n_segments):
        x0 = e * g.pitch
        # A triangular prism through the half width, apex on the bridge top.

        top = H + 1e-3  # reach past the grasping face
        dt = (top - g.bridge_thickness) * tan_half
        pts = [occ.addPoint(x0, -1e-3, g.bridge_thickness),
               occ.addPoint(x0 + dt, -1e-3, top), occ.addPoint(x0 - dt, -1e-3, top)]
        lines = [occ.addLine(pts[i], pts[(i + 1) % 3]) for i in range(3)]
        face = occ.addPlaneSurface([occ.addCurveLoop(lines)])
        ext = occ.extrude([(2, face)], 0.0, 0.5 * W + 2e-3, 0.0)
        tools += [t for t in ext if t[0] == 3]
    tools.append((3, occ.addBox(-1e-3, -1e-3, g.hole_height - 0.5 * a, L + 2e-3,
                                0.5 * a + 1e-3, a)))
    (solid,), _ = occ.cut([(3, body)], tools)
    return solid


def _add_knot_patch(g: FingerGeometry, a: float, solid: tuple[int, int]) -> None:
    """The knot's patch: a square ring of width KNOT_BAND around the channel opening on the
    tip face, made a surface of its own so the traction's line of action is exact."""
    import gmsh

    occ = gmsh.model.occ
    L = g.length
    half = 0.5 * a + KNOT_BAND
    ring = occ.addRectangle(g.hole_height - half, 0.0, 0.0, 2.0 * half, half)
    occ.rotate([(2, ring)], 0, 0, 0, 0, 1, 0, -0.5 * math.pi)  # into the plane x = 0
    occ.translate([(2, ring)], L, 0, 0)
    occ.fragment([solid], [(2, ring)])
    occ.synchronize()
    # The rectangle's piece over the channel opening bounds nothing: drop it.
    for dim, tag in gmsh.model.getEntities(2):
        x0, _, _, x1, y1, _ = gmsh.model.getBoundingBox(dim, tag)
        if abs(x0 - L) < 1e-6 and abs(x1 - L) < 1e-6 and y1 < 0.5 * a + 1e-6:
            occ.remove([(dim, tag)], recursive=True)
    occ.synchronize()


def _apex_lines(g: FingerGeometry) -> list[int]:
    """Tags of the cuts' apex lines (the singular re-entrant corners on the bridge tops)."""
    import gmsh

    apex = []
    for dim, tag in gmsh.model.getEntities(1):
        x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(dim, tag)
        on_cut = any(abs(x0 - e * g.pitch) < 1e-6 and abs(x1 - e * g.pitch) < 1e-6
                     for e in range(1, g.n_segments))
        if on_cut and abs(z0 - g.bridge_thickness) < 1e-6 and abs(z1 - g.bridge_thickness) < 1e-6:
            apex.append(tag)
    if len(apex) != g.n_hinges:
        raise RuntimeError(f"quadratic check: found {len(apex)} apex lines, expected {g.n_hinges}")
    return apex


def _grade_towards_apexes(g: FingerGeometry, apex: list[int], size: float,
                          bridge_size: float) -> None:
    """Cells graded towards each cut's apex line: ``bridge_size`` [m] on the line, growing
    linearly to ``size`` [m] at three bridge thicknesses from it."""
    import gmsh

    field = gmsh.model.mesh.field
    dist = field.add("Distance")
    field.setNumbers(dist, "CurvesList", apex)
    field.setNumber(dist, "Sampling", 200)
    thr = field.add("Threshold")
    field.setNumber(thr, "InField", dist)
    field.setNumber(thr, "SizeMin", bridge_size)
    field.setNumber(thr, "SizeMax", size)
    field.setNumber(thr, "DistMin", 0.0)
    field.setNumber(thr, "DistMax", 3.0 * g.bridge_thickness)
    field.setAsBackgroundMesh(thr)
    for opt in ("Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints",
                "Mesh.MeshSizeFromCurvature"):
        gmsh.option.setNumber(opt, 0)
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.option.setNumber("Mesh.Algorithm3D", 1)


def _knot_patch_triangles(g: FingerGeometry, a: float) -> np.ndarray:
    """Node tags of the meshed knot patch's triangles, shape (n, 3)."""
    import gmsh

    L = g.length
    half = 0.5 * a + KNOT_BAND
    patch = []
    for dim, tag in gmsh.model.getEntities(2):
        x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(dim, tag)
        if (abs(x0 - L) < 1e-6 and abs(x1 - L) < 1e-6 and z0 > g.hole_height - half - 1e-6
                and z1 < g.hole_height + half + 1e-6 and y1 < half + 1e-6):
            _, _, tri = gmsh.model.mesh.getElements(2, tag)
            patch.append(np.asarray(tri[0], dtype=np.int64).reshape(-1, 3))
    if len(patch) != 1:
        raise RuntimeError(f"quadratic check: expected one knot patch, found {len(patch)}")
    return patch[0]


def _best_fit_angle(x0: np.ndarray, x1: np.ndarray, w: np.ndarray) -> float:
    """Rotation about -y (curl towards +z) of the ``w``-weighted best fit x0 -> x1, mirror
    images included."""
    m = np.array([1.0, -1.0, 1.0])
    a, b = np.vstack([x0, x0 * m]), np.vstack([x1, x1 * m])
    w = np.concatenate([w, w]) / (2.0 * w.sum())
    h = (a - w @ a).T @ ((b - w @ b) * w[:, None])
    u, _, vt = np.linalg.svd(h)
    dfix = np.diag([1.0, 1.0, np.sign(np.linalg.det(vt.T @ u.T))])
    rot = vt.T @ dfix @ u.T
    return math.atan2(rot[2, 0], rot[0, 0])


def quadratic_compliance(params: GripperParams | None = None, *, size: float = 2.0e-3,
                         bridge_size: float | None = None, clamp_length: float = 0.008,
                         poisson_ratio: float | None = None) -> dict:
    """Small-load bending compliance of the finger with quadratic tetrahedra [deg/N].

    Args:
        size: largest tetrahedron edge away from the bridges [m].
        bridge_size: edge length around the bridges [m]; default ``size / 4``.
        clamp_length: length of B1 held by the mount [m] (the reference's default).
        poisson_ratio: override the material's (to separate volumetric locking).

    Returns:
        dict with ``compliance_deg_per_N``, ``nodes`` (quadratic), ``tets``, ``dofs`` and
        ``wall_time_s``.
    """
    import skfem
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    p = (params or GripperParams()).validate()
    g = p.finger
    nu = p.material.poisson_ratio if poisson_ratio is None else poisson_ratio
    t0 = time.perf_counter()
    pts, tets, patch = _gmsh_mesh(p, size, bridge_size or 0.25 * size)
    mesh = skfem.MeshTet(pts.T, tets.T)
    basis = skfem.Basis(mesh, skfem.ElementVector(skfem.ElementTetP2()))
    K = skfem.asm(linear_elasticity(*lame_parameters(p.material.youngs_modulus, nu)), basis)
    a = channel_side(g)

    patch_key = {tuple(sorted(t)) for t in patch.tolist()}
    facets = np.array([i for i, f in enumerate(np.sort(mesh.facets, axis=0).T.tolist())
                       if tuple(f) in patch_key])
    fb = skfem.FacetBasis(mesh, basis.elem, facets=facets)
    area = float(skfem.Functional(lambda w: 1.0 + 0.0 * w.x[0]).assemble(fb))
    expected = (0.5 * a + KNOT_BAND) * (a + 2 * KNOT_BAND) - 0.5 * a * a
    if abs(area - expected) > 1e-6 * expected:
        raise RuntimeError(f"quadratic check: knot patch area {area:.4g} m², expected {expected:.4g}")
    traction = -CHECK_TENSION * 0.5 / area  # the half body carries half of the knot force

    @skfem.LinearForm
    def knot(v, w):
        return traction * v[0]

    f = skfem.asm(knot, fb)
    dofs_x = basis.doflocs  # (3, ndofs): location of each dof
    nodal = basis.nodal_dofs  # (3, n_vertices)
    facet_d = basis.facet_dofs if basis.facet_dofs.size else np.empty((3, 0), int)
    edge_d = basis.edge_dofs
    fixed = [np.flatnonzero(dofs_x[0] <= clamp_length + 1e-9)]
    # Symmetry: u_y = 0 on y = 0 (the y dofs are the second row of each dof group).
    for grp in (nodal, edge_d, facet_d):
        if grp.size:
            on_plane = np.isclose(dofs_x[1, grp[1]], 0.0, atol=1e-12)
            fixed.append(grp[1][on_plane])
    D = np.unique(np.concatenate(fixed))
    u = solve_clamped(K, f, D, basis.doflocs)
    verts = mesh.p.T
    disp = u[nodal].T
    # Each vertex's volume share (a quarter of each tetrahedron), per element: the tetrahedra
    # are assigned to elements by their centroids (no tetrahedron spans a cut).
    vol = np.abs(np.einsum("ij,ij->i", np.cross(pts[tets[:, 1]] - pts[tets[:, 0]],
                                                   pts[tets[:, 2]] - pts[tets[:, 0]]),
                           pts[tets[:, 3]] - pts[tets[:, 0]])) / 6.0
    owner = np.clip((pts[tets].mean(1)[:, 0] // g.pitch).astype(int), 0, g.n_segments - 1)
    angles = []
    for e in (0, g.n_segments - 1):
        w = np.zeros(len(verts))
        np.add.at(w, tets[owner == e].ravel(), np.repeat(0.25 * vol[owner == e], 4))
        idx = np.flatnonzero(w > 0)
        angles.append(_best_fit_angle(verts[idx], verts[idx] + MEASURE_SCALE * disp[idx], w[idx]))
    bend = math.degrees(angles[1] - angles[0]) / MEASURE_SCALE
    return {"compliance_deg_per_N": bend / CHECK_TENSION, "nodes": int(basis.N // 3),
            "tets": int(len(tets)), "dofs": int(basis.N), "size_m": size,
            "bridge_size_m": bridge_size or 0.25 * size, "wall_time_s": time.perf_counter() - t0}

