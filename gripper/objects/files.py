"""Object files: one TOML (or JSON) file per grasp object, the built-in five included.

Format (``docs/objects.md`` has a worked example)::

    [object]
    name = "bracket"               # how records name it
    kind = "mesh"                  # rigid_box, rigid_cylinder, mesh, balloon, paper_box, bag, zipper_bag
    mesh = "bracket.stl"           # kind mesh: STL/OBJ/PLY in metres, relative to this file
    size = [0.02, 0.02, 0.03]      # primitives and deformables: half-extents [m]
    mass = 0.060                   # [kg]; or density = 620.0 [kg/m³] (rigid kinds)
    friction = 0.6                 # against the silicone pads [-]
    yaw_symmetric = false          # default: true for cylinders and balloons
    close_command = 3.0            # [rad of spool angle]; default 3.0 (full closing) for rigid kinds
    mesh_points = [4, 4, 5]        # deformable kinds: mesh points along x, y, z (default: the kind's)

    [damage]
    criterion = "contact_force"    # rigid kinds: contact_force or none; balloon, bag: strain;
    limit = 30.0                   # paper_box: dent; the limit in the criterion's unit

    [material]                     # deformable kinds
    youngs_modulus = 3.0e9         # [Pa]
    thickness = 2.0e-4             # [m], shells and films
    yield_strain = 0.005           # [-], paper_box

    [contents]                     # zipper_bag: its loose items, in one layer on its floor
    count = 6
    size = [0.0159, 0.0079, 0.0048] # one item's half-extents [m]
    mass = 0.0023                  # one item's mass [kg]; object.mass is the film's and theirs

    [reasons]                      # free text per number: where it comes from
    mass = "weighed"

Every error names the file, the key and what is allowed.

Example:
    >>> from gripper.objects.files import load_object_file
    >>> from gripper.core.resources import OBJECTS_DIR
    >>> load_object_file(OBJECTS_DIR / "block.toml").damage_limit
    200.0
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from gripper.core.fields import check_safe_name
from gripper.core.ranges import OBJECT_DENSITY
from gripper.core.user_files import read_user_data
from gripper.objects.grasp_object import (
    DAMAGE_CRITERIA,
    DEFAULT_MESH_POINTS,
    KINDS,
    MATERIAL_NEEDS,
    MESH_POINTS_RANGE,
    RIGID_KINDS,
    GraspObject,
)
from gripper.objects.mesh_objects import RIGID_CLOSE, mesh_object

MATERIAL_KEYS = ("youngs_modulus", "thickness", "yield_strain")
SECTIONS: dict[str, tuple[str, ...] | None] = {
    "object": ("name", "kind", "mesh", "size", "mass", "density", "friction", "yaw_symmetric",
               "close_command", "mesh_points"),
    "damage": ("criterion", "limit"),
    "material": MATERIAL_KEYS,
    "contents": ("count", "size", "mass"),
    "reasons": None,  # any key: free text
}
# The criterion a deformable kind is damaged by (the project models one per kind).
OWN_CRITERION = {"balloon": "strain", "bag": "strain", "zipper_bag": "strain", "paper_box": "dent"}


def load_object_file(path: str | Path) -> GraspObject:
    """Read, check and build the object an object file describes.

    Raises:
        ValueError: one line naming the file, the key and what is allowed.
    """
    path = Path(path)
    data = read_user_data(path, "object file")
    return object_from_dict(data, where=f"object file {path}", base=path.parent)


def object_from_dict(data: Any, *, where: str, base: Path = Path(".")) -> GraspObject:
    """Build an object from an object file's tables (see the module docstring)."""
    def fail(key: str, msg: str) -> ValueError:
        return ValueError(f"{where}: {key}: {msg}")

    if not isinstance(data, dict):
        raise ValueError(f"{where}: expected tables {', '.join(SECTIONS)}")
    for section, table in data.items():
        if section not in SECTIONS:
            raise fail(section, f"unknown section; allowed: {', '.join(SECTIONS)}")
        if not isinstance(table, dict):
            raise fail(section, "must be a table")
        allowed = SECTIONS[section]
        for key, value in table.items():
            if allowed is not None and key not in allowed:
                raise fail(f"{section}.{key}", f"unknown key; allowed: {', '.join(allowed)}")
            if allowed is None and not isinstance(value, str):
                raise fail(f"{section}.{key}", f"must be text, got {value!r}")
    obj = data.get("object")
    if obj is None:
        raise fail("object", "missing section")
    dmg, mat = data.get("damage", {}), data.get("material", {})
    reasons = tuple(sorted(data.get("reasons", {}).items()))

    def get(table: dict, section: str, key: str, kind: str, default: Any = None, required: bool = False):
        if key not in table:
            if required:
                raise fail(f"{section}.{key}", "missing")
            return default
        v = table[key]
        if kind == "text":
            ok = isinstance(v, str) and v != ""
            allowed = "non-empty text"
        elif kind == "bool":
            ok, allowed = isinstance(v, bool), "true or false"
        elif kind == "size":
            ok = (isinstance(v, list) and len(v) == 3 and all(
                isinstance(x, int | float) and not isinstance(x, bool) and math.isfinite(x) and x > 0 for x in v))
            allowed = "three numbers > 0 (half-extents in m)"
        else:
            ok = isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v) and v > 0
            allowed = "a number > 0"
        if not ok:
            raise fail(f"{section}.{key}", f"must be {allowed}, got {v!r}")
        return tuple(float(x) for x in v) if kind == "size" else (float(v) if kind == "number" else v)

    name = get(obj, "object", "name", "text", required=True)
    try:
        check_safe_name(name, "object.name")
    except ValueError as e:
        raise fail("object.name", str(e).partition(": ")[2]) from None
    kind = get(obj, "object", "kind", "text", required=True)
    if kind not in KINDS:
        raise fail("object.kind", f"must be one of {', '.join(KINDS)}, got {kind!r}")
    mass = get(obj, "object", "mass", "number")
    density = get(obj, "object", "density", "number")
    if (mass is None) == (density is None) and not (kind == "mesh" and mass is None and density is None):
        raise fail("object.mass", "give exactly one of mass [kg] or density [kg/m³]")
    if density is not None and kind not in RIGID_KINDS:
        raise fail("object.density", f"a {kind} takes its mass, not a density")
    if density is not None:
        OBJECT_DENSITY.check(f"{where}: object.density", density)
    friction = get(obj, "object", "friction", "number", required=True)
    yaw_symmetric = get(obj, "object", "yaw_symmetric", "bool",
                        default=kind in ("rigid_cylinder", "rigid_sphere", "balloon"))
    close = get(obj, "object", "close_command", "number",
                default=RIGID_CLOSE if kind in RIGID_KINDS else None, required=kind not in RIGID_KINDS)
    points = obj.get("mesh_points")
    if kind not in DEFAULT_MESH_POINTS:
        if points is not None:
            raise fail("object.mesh_points", f"a {kind} is rigid: it takes no mesh resolution")
        points = (0, 0, 0)
    elif points is None:
        points = DEFAULT_MESH_POINTS[kind]
    else:
        lo, hi = MESH_POINTS_RANGE
        if not (isinstance(points, list) and len(points) == 3 and all(
                isinstance(n, int) and not isinstance(n, bool) and lo <= n <= hi for n in points)):
            raise fail("object.mesh_points", f"must be three whole numbers from {lo} to {hi} (points "
                       f"along x, y, z), got {points!r}")
        points = tuple(points)
    size = None
    if kind != "mesh":
        if "mesh" in obj:
            raise fail("object.mesh", f"only kind = \"mesh\" takes a mesh, this is a {kind}")
        size = get(obj, "object", "size", "size", required=True)
    own = OWN_CRITERION.get(kind)
    if own is None and "criterion" not in dmg:
        raise fail("damage.criterion", "missing: declare how the object is damaged, criterion = "
                   "\"contact_force\" with a limit [N], or \"none\"")
    criterion = get(dmg, "damage", "criterion", "text", default=own)
    if criterion not in DAMAGE_CRITERIA or kind not in DAMAGE_CRITERIA[criterion][1]:
        fits = [c for c, (_, kinds) in DAMAGE_CRITERIA.items() if kind in kinds]
        raise fail("damage.criterion", f"a {kind} allows {', '.join(fits)}, got {criterion!r}")
    limit = get(dmg, "damage", "limit", "number", default=0.0, required=criterion != "none")
    for key in MATERIAL_NEEDS.get(kind, ()):
        get(mat, "material", key, "number", required=True)
    if kind not in MATERIAL_NEEDS and mat:
        raise fail("material", f"a {kind} is rigid: it takes no material table")
    material = {k: get(mat, "material", k, "number", default=0.0) for k in MATERIAL_KEYS}
    cont = data.get("contents", {})
    contents: dict[str, Any] = {}
    if kind == "zipper_bag":
        count = cont.get("count")
        if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count <= 64:
            raise fail("contents.count", f"must be a whole number from 1 to 64, got {count!r}")
        contents = {"contents_count": count,
                    "contents_size": get(cont, "contents", "size", "size", required=True),
                    "contents_mass": get(cont, "contents", "mass", "number", required=True)}
    elif cont:
        raise fail("contents", f"only a zipper_bag holds loose contents, this is a {kind}")

    if kind == "mesh":
        mesh_name = get(obj, "object", "mesh", "text", required=True)
        if "size" in obj:
            raise fail("object.size", "a mesh takes its size from the mesh; remove size")
        mesh_path = Path(mesh_name) if Path(mesh_name).is_absolute() else base / mesh_name
        try:
            made = mesh_object(mesh_path, mass=mass, density=density, friction=friction,
                               close_command=close, damage=criterion, damage_limit=limit,
                               yaw_symmetric=yaw_symmetric, name=name, reasons=reasons)
        except ValueError as e:
            raise fail("object.mesh", str(e)) from None
        return made
    assert size is not None
    if mass is None:
        volume = (8 * size[0] * size[1] * size[2] if kind == "rigid_box"
                  else 4 / 3 * math.pi * size[0] ** 3 if kind == "rigid_sphere"
                  else math.pi * size[0] ** 2 * 2 * size[2])
        mass = density * volume
    try:
        return GraspObject(name=name, kind=kind, size=size, mass=mass, friction=friction,
                           yaw_symmetric=yaw_symmetric, close_command=close, damage=criterion,
                           damage_limit=limit, mesh_points=points, reasons=reasons, **material,
                           **contents).validate()
    except ValueError as e:
        raise ValueError(f"{where}: {e}") from None
