"""User meshes as grasp objects: a watertight STL/OBJ/PLY loaded with trimesh, centred, its mass
from a given mass or a density (the object files and the ``mesh:PATH`` shortcut build on it).

Example:
    >>> from gripper.objects.mesh_objects import DEFAULT_MESH_DENSITY
    >>> DEFAULT_MESH_DENSITY
    620.0
"""

from __future__ import annotations

import math
from pathlib import Path

from gripper.objects.grasp_object import GraspObject
from gripper.objects.kinds.base import RIGID_CLOSE
from gripper.objects.kinds.mesh import MESH_SUFFIXES, load_mesh

# --- user meshes ---------------------------------------------------------------------------

# Density used for a user mesh given without a mass: a typical 3D-printed part (PLA 1240 kg/m³
# at about 50 % effective fill).
DEFAULT_MESH_DENSITY = 620.0


def mesh_object(path: str | Path, *, mass: float | None = None, density: float | None = None,
                friction: float = 0.6, close_command: float = RIGID_CLOSE, damage: str = "contact_force",
                damage_limit: float = 200.0, yaw_symmetric: bool = False, name: str | None = None,
                reasons: tuple[tuple[str, str], ...] = ()) -> GraspObject:
    """A rigid object from a user mesh (metres), centred on its bounding box, base on the floor.

    Mass from ``mass``, else ``density`` (default :data:`DEFAULT_MESH_DENSITY`) × the mesh's
    volume; inertia from the mesh (MuJoCo computes it from the same triangles); collision from
    its convex hull. The footprint checked against the aperture is the hull's horizontal radius
    about the centre. The defaults of the ``mesh:PATH`` shortcut (friction 0.6, a 200 N contact
    force limit, full closing) are the block's; an object file declares its own.
    """
    mesh = load_mesh(path)
    lo, hi = mesh.bounds
    hx, hy, hz = (float(v) for v in 0.5 * (hi - lo))
    centre = 0.5 * (lo + hi)
    hull = mesh.convex_hull.vertices - centre
    footprint = float(max(math.hypot(x, y) for x, y in hull[:, :2]))
    if mass is None:
        rho = DEFAULT_MESH_DENSITY if density is None else density
        if isinstance(rho, bool) or not (isinstance(rho, int | float) and math.isfinite(rho) and rho > 0):
            raise ValueError(f"mesh: density must be > 0 kg/m³, got {rho!r}")
        mass = rho * float(mesh.volume)
    obj = GraspObject(name=name or f"mesh:{path}", kind="mesh", size=(hx, hy, hz), mass=mass,
                      friction=friction, yaw_symmetric=yaw_symmetric, close_command=close_command,
                      damage=damage, damage_limit=damage_limit, mesh_file=str(path),
                      footprint_radius=footprint, reasons=reasons)
    return obj.validate()


__all__ = ["DEFAULT_MESH_DENSITY", "MESH_SUFFIXES", "RIGID_CLOSE", "load_mesh", "mesh_object"]
