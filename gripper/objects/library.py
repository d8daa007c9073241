"""Where grasp objects come from: the built-in library (a latex balloon, a rigid block and
cylinder, a card box, a zipper storage bag; object files under ``gripper/data/objects``), a
user's object files, and user meshes (``mesh:PATH``). What an object is:
:mod:`gripper.objects.grasp_object`; how one is placed in a scene:
:mod:`gripper.objects.scene_objects`.

Example:
    >>> from gripper.objects.library import get_object
    >>> obj = get_object("balloon")
    >>> obj.kind, obj.mass
    ('balloon', 0.004)
"""

from __future__ import annotations

import dataclasses
import os
from pathlib import Path

from gripper.core.resources import OBJECTS_DIR
from gripper.objects.files import load_object_file
from gripper.objects.grasp_object import GraspObject
from gripper.objects.mesh_objects import DEFAULT_MESH_DENSITY, RIGID_CLOSE, load_mesh, mesh_object

# --- the default library -------------------------------------------------------------------



DEFAULT_OBJECTS = ("balloon", "block", "cylinder", "paper_box", "bag")
# Shipped object files beyond the benchmark's five, by name: the pack-in-a-bag of 0.11.0 and
# before (a hard case, docs/limitations.md).
EXTRA_OBJECTS = ("bag_pack",)


def _library() -> dict[str, GraspObject]:
    return {name: load_object_file(OBJECTS_DIR / f"{name}.toml") for name in (*DEFAULT_OBJECTS, *EXTRA_OBJECTS)}


LIBRARY: dict[str, GraspObject] = {}  # filled on first use (the object files are package data)


def library() -> dict[str, GraspObject]:
    """The built-in objects (the default five and :data:`EXTRA_OBJECTS`), read once from their
    object files in ``gripper/data/objects``."""
    if not LIBRARY:
        LIBRARY.update(_library())
    return LIBRARY


def get_object(spec: str) -> GraspObject:
    """The object ``spec`` names: a built-in name, an object file (``.toml`` or ``.json``), or a
    user mesh as ``mesh:PATH`` or ``mesh:PATH::MASS_KG``. Records name the object by
    :attr:`GraspObject.name`: the built-in's name, the file's ``object.name``, or the ``mesh:``
    spec exactly as given.

    Raises:
        ValueError: unknown name (lists the allowed ones), a bad file or a bad mesh.
    """
    if not isinstance(spec, str) or not spec:
        raise ValueError(f"objects: expected an object name, file or mesh:PATH, got {spec!r}")
    if spec.startswith("mesh:"):
        rest = spec[len("mesh:"):]
        path, sep, mass_text = rest.partition("::")
        mass = None
        if sep:
            try:
                mass = float(mass_text)
            except ValueError:
                raise ValueError(f"objects: {spec}: the mass after '::' must be a number in kg, "
                                 f"got {mass_text!r}") from None
        return dataclasses.replace(mesh_object(path, mass=mass), name=spec).validate()
    if spec.endswith((".toml", ".json")):
        obj = load_object_file(spec)
        if obj.name in library() and Path(spec).resolve().parent != OBJECTS_DIR.resolve():
            raise ValueError(f"objects: {spec}: object.name {obj.name!r} is a built-in object's name; its records "
                             "would mix with the built-in's: give it a name of its own")
        return obj
    lib = library()
    if spec not in lib:
        raise ValueError(f"objects: unknown object {spec!r}; allowed: {', '.join(lib)}, an object "
                         "file (.toml or .json) or mesh:PATH[::MASS]")
    return lib[spec]


def object_source(spec: str) -> tuple:
    """What ``spec`` reads, whatever its spelling: ("builtin", name), ("file", real path) or
    ("mesh", real path, mass); two specs of one run with the same source are one object twice."""
    if spec.startswith("mesh:"):
        path, _, mass = spec[len("mesh:"):].partition("::")
        return ("mesh", os.path.realpath(path), float(mass) if mass else None)
    if spec.endswith((".toml", ".json")):
        return ("file", os.path.realpath(spec))
    return ("builtin", spec)


__all__ = ["DEFAULT_MESH_DENSITY", "DEFAULT_OBJECTS", "EXTRA_OBJECTS", "LIBRARY", "RIGID_CLOSE", "get_object",
           "library", "load_mesh", "mesh_object", "object_source"]
