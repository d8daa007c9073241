"""User meshes as grasp objects: a watertight STL/OBJ/PLY loaded with trimesh, centred, its mass
from a given mass or a density (the object files and the ``mesh:PATH`` shortcut build on it).

Example:
    >>> from gripper.objects.mesh_objects import DEFAULT_MESH_DENSITY
    >>> DEFAULT_MESH_DENSITY
    620.0
"""

from __future__ import annotations

import io
import math
import warnings
from pathlib import Path

from gripper.core.user_files import MAX_MESH_BYTES, read_user_bytes
from gripper.objects.grasp_object import GraspObject

# The rigid objects' closing command: near the end of the servo's travel (π) and past full finger
# closure (≈ 2.3 rad), so the servo stalls on the part and squeezes with its stall torque
# (gripper/data/objects/block.toml gives the reason); user meshes default to it.
RIGID_CLOSE = 3.0


# --- user meshes ---------------------------------------------------------------------------

# Density used for a user mesh given without a mass: a typical 3D-printed part (PLA 1240 kg/m³
# at about 50 % effective fill).
DEFAULT_MESH_DENSITY = 620.0


MESH_SUFFIXES = ("stl", "obj", "ply")  # the formats trimesh reads without extra packages

def load_mesh(path: str | Path, *, repair: bool = True):
    """Load an STL/OBJ/PLY with trimesh; repair small holes (with a warning) or refuse.

    Raises:
        ValueError: unreadable file, not a triangle mesh, or not watertight after repair.
    """
    import trimesh

    path = Path(path)
    suffix = path.suffix.lower().lstrip(".")
    if suffix not in MESH_SUFFIXES:
        raise ValueError(f"mesh: {path}: the name must end in {', '.join('.' + s for s in MESH_SUFFIXES)}")
    data = read_user_bytes(path, "mesh", MAX_MESH_BYTES)  # a regular file of bounded size
    try:
        mesh = trimesh.load(io.BytesIO(data), file_type=suffix, force="mesh")
    except Exception as e:  # trimesh raises many types for malformed files
        raise ValueError(f"mesh: cannot read {path} as STL/OBJ/PLY ({e})") from None
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        raise ValueError(f"mesh: {path} holds no triangles")
    if not mesh.is_watertight:
        if repair:
            trimesh.repair.fill_holes(mesh)
            trimesh.repair.fix_normals(mesh)
        if not mesh.is_watertight:
            raise ValueError(f"mesh: {path} is not watertight (holes or open edges) and could not "
                             "be repaired; close it in a mesh editor")
        warnings.warn(f"mesh {path} was not watertight; holes filled by trimesh", stacklevel=2)
    if mesh.volume <= 0:
        mesh.invert()
    return mesh


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
