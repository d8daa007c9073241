"""What the deformable kinds share: a MuJoCo flex named ``object`` with the deformables'
contact, the closed box shell of the paper box and the zipper bag, and the damage measure of
films and membranes (peak edge strain).

Deformable objects need MuJoCo's ``discrete`` integrator (MuJoCo 4 integrates flex elasticity
only there, or with explicit Euler); grasp scenes use it for every object so that all objects
share one integrator.
"""

from __future__ import annotations

import tempfile
from pathlib import Path
from typing import Any, ClassVar

import mujoco

from gripper.objects.kinds.base import EDGE_STRAIN, OBJECT_BODY, Criterion, ObjectKind

# Contact of deformable objects (with fingers, palm and floor; the flex has priority, so its values
# are used). MuJoCo's default contact (20 ms time constant, impedance 0.9-0.95) is stiff in
# proportion to the effective mass at the contact, and a flex spreads a few grams over ~100
# vertices: a plate pressing the 4 g balloon sank 10-20 mm into it and the balloon under it sank as
# far into the floor (gripper.experiments.crush), so the squeeze was taken by the contacts, not by the balloon's
# elasticity. Two steps of the trials' 2 ms (MuJoCo's stability floor; it clamps shorter time
# constants to two steps) and impedance 0.99-0.999 keep the sinking to 1-3 mm.
FLEX_CONTACT_SOLREF = (0.004, 1.0)
FLEX_CONTACT_SOLIMP = (0.99, 0.999, 0.001, 0.5, 2.0)

# Allowed resolutions: flexcomp needs 3 points an axis for a closed surface; 12 is a 10-fold cost.
MESH_POINTS_RANGE = (3, 12)

BAG_DAMPING = 0.002  # s, Rayleigh damping of the film: LDPE is lossy (tan δ ≈ 0.1)
PE_POISSON = 0.4  # LDPE 0.35-0.45


def flex_contact(flex: mujoco.MjsFlex, friction: list[float]) -> None:
    """The deformables' contact on ``flex``: its friction wins (priority), stiff and no self-contact."""
    flex.friction = friction
    flex.priority = 1
    flex.condim = 3
    flex.solref = list(FLEX_CONTACT_SOLREF)
    flex.solimp = list(FLEX_CONTACT_SOLIMP)
    flex.selfcollide = mujoco.mjtFlexSelf.mjFLEXSELF_NONE


def stiff_against_film(geom: mujoco.MjsGeom, friction: list[float]) -> None:
    """A rigid item inside a film: as stiff against the film as the fingers are. At equal
    priority MuJoCo averages the two geoms' solref/solimp, and with the default on this side
    (0.02 s) the bag's pack sank 10-17 mm through the film's few-milligram vertices in every
    grasp, and a film vertex popping back over a pack edge read as a 64 % "tear"."""
    geom.friction = friction
    geom.priority = 1
    geom.solref = list(FLEX_CONTACT_SOLREF)
    geom.solimp = list(FLEX_CONTACT_SOLIMP)


class DeformableKind(ObjectKind):
    """A flex: a mesh resolution within :data:`MESH_POINTS_RANGE`, no rigid body to track
    unless it holds one, and a damage criterion of its own."""

    deformable = True
    tracked_body: ClassVar[str | None] = None

    def check(self, obj: Any, where: str) -> None:
        lo, hi = MESH_POINTS_RANGE
        if not all(lo <= n <= hi for n in obj.mesh_points):
            raise ValueError(f"{where}.mesh_points: a {self.name} takes {lo} to {hi} points along each axis, "
                             f"got {list(obj.mesh_points)}")


class FilmKind(DeformableKind):
    """A membrane or film that bursts or tears: damaged by its peak edge strain."""

    criteria: ClassVar[dict[str, Criterion]] = {"strain": EDGE_STRAIN}
    own_criterion = "strain"
    reads_strain = True


def box_shell(half: tuple[float, float, float], counts: tuple[int, int, int]):
    """A closed, watertight triangle mesh of a box surface (half-extents [m]) whose faces are
    grids of ``counts`` points along x, y, z, with outward normals (trimesh)."""
    import numpy as np
    import trimesh

    verts: list = []
    faces: list = []

    def face(origin, u, v, nu, nv):
        base = len(verts)
        for j in range(nv):
            for i in range(nu):
                verts.append(origin + u * i / (nu - 1) + v * j / (nv - 1))
        for j in range(nv - 1):
            for i in range(nu - 1):
                a = base + j * nu + i
                faces.extend([[a, a + 1, a + nu + 1], [a, a + nu + 1, a + nu]])

    hx, hy, hz = half
    cx, cy, cz = counts
    ex, ey, ez = np.eye(3)
    lo = np.array([-hx, -hy, -hz])
    # (u, v) ordered so that u × v points out of the box: every triangle winds outwards
    face(lo, 2 * hy * ey, 2 * hx * ex, cy, cx)                          # bottom (-z)
    face(np.array([-hx, -hy, hz]), 2 * hx * ex, 2 * hy * ey, cx, cy)    # top (+z)
    face(lo, 2 * hx * ex, 2 * hz * ez, cx, cz)                          # y- side
    face(np.array([-hx, hy, -hz]), 2 * hz * ez, 2 * hx * ex, cz, cx)    # y+ side
    face(lo, 2 * hz * ez, 2 * hy * ey, cz, cy)                          # x- side
    face(np.array([hx, -hy, -hz]), 2 * hy * ey, 2 * hz * ez, cy, cz)    # x+ side
    mesh = trimesh.Trimesh(np.array(verts), np.array(faces), process=True)  # merges shared edges
    if not (mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0):  # pragma: no cover
        raise RuntimeError("paper box shell is not a closed, outward-wound surface")
    return mesh


def shell_flex(spec, obj, *, mass, pos, quat, radius, poisson, damping, rgba, friction) -> mujoco.MjsFlex:
    """A 2D flex over :func:`box_shell` of the object's size and mesh points, with its material
    (modulus, thickness) and the deformables' contact: the paper box's card, the zipper bag's
    film."""

    mesh = box_shell(obj.size, obj.mesh_points)
    # make_flex reads a mesh from a file; the shell is generated, written to a temporary OBJ
    with tempfile.TemporaryDirectory() as tmp:
        path = str(Path(tmp) / "shell.obj")
        mesh.export(path)
        flex = spec.worldbody.make_flex(
            OBJECT_BODY, type="mesh", file=path, dim=2, dof="full", radius=radius, mass=mass,
            inertiabox=0.002, pos=pos, quat=quat, elastic2d=3)
    flex.young = obj.youngs_modulus
    flex.poisson = poisson
    flex.thickness = obj.thickness
    flex.damping = damping
    flex.rgba = rgba
    flex_contact(flex, friction)
    return flex
