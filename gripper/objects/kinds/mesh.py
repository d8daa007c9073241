"""A rigid part from a user's mesh (STL/OBJ/PLY in metres), its collision the mesh's convex hull;
``footprint_radius`` is the hull's horizontal radius about its centre, which sizes it against
the opening (the mesh objects themselves: :mod:`gripper.objects.mesh_objects`)."""

from __future__ import annotations

import io
import warnings
from pathlib import Path

import mujoco

from gripper.core.user_files import MAX_MESH_BYTES, read_user_bytes
from gripper.objects.kinds.rigid import RigidKind

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


class MeshPart(RigidKind):
    name = "mesh"
    square_footprint = True
    sized_by_mesh = True

    def half_width(self, obj):
        return obj.footprint_radius if obj.footprint_radius > 0 else super().half_width(obj)

    def add_geom(self, spec, body, obj):
        mesh = load_mesh(obj.mesh_file)
        verts = mesh.vertices - 0.5 * (mesh.bounds[0] + mesh.bounds[1])
        spec.add_mesh(name="object_mesh", uservert=verts.ravel().tolist(), userface=mesh.faces.ravel().tolist())
        return body.add_geom(name="object_geom", type=mujoco.mjtGeom.mjGEOM_MESH, meshname="object_mesh")
