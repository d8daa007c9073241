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
from gripper.objects.grasp_object import GraspObject
from gripper.objects.kinds import ObjectKind, object_kind, registered_kinds
from gripper.objects.kinds.base import MATERIAL_RANGES, RIGID_CLOSE
from gripper.objects.kinds.flex import MESH_POINTS_RANGE
from gripper.objects.mesh_objects import mesh_object

MATERIAL_KEYS = tuple(MATERIAL_RANGES)
# The tables every object file may hold, with their keys (None: any key); a kind adds its own
# (ObjectKind.file_tables: the zipper bag's [contents]).
COMMON_TABLES: dict[str, tuple[str, ...] | None] = {
    "object": ("name", "kind", "mesh", "size", "mass", "density", "friction", "yaw_symmetric",
               "close_command", "mesh_points"),
    "damage": ("criterion", "limit"),
    "material": MATERIAL_KEYS,
    "reasons": None,  # any key: free text
}


def file_tables() -> dict[str, tuple[str, ...] | None]:
    """Every table an object file may hold: the common ones and each registered kind's own."""
    out = dict(COMMON_TABLES)
    for kind in registered_kinds().values():
        out.update(kind.file_tables)
    return out


def load_object_file(path: str | Path) -> GraspObject:
    """Read, check and build the object an object file describes.

    Raises:
        ValueError: one line naming the file, the key and what is allowed.
    """
    path = Path(path)
    data = read_user_data(path, "object file")
    return object_from_dict(data, where=f"object file {path}", base=path.parent)


class _Reader:
    """Reads and checks an object file's values; every error names the file and the key."""

    def __init__(self, where: str):
        self.where = where

    def fail(self, key: str, msg: str) -> ValueError:
        return ValueError(f"{self.where}: {key}: {msg}")

    def check_tables(self, data: Any) -> None:
        tables = file_tables()
        if not isinstance(data, dict):
            raise ValueError(f"{self.where}: expected tables {', '.join(tables)}")
        for section, table in data.items():
            if section not in tables:
                raise self.fail(section, f"unknown section; allowed: {', '.join(tables)}")
            if not isinstance(table, dict):
                raise self.fail(section, "must be a table")
            allowed = tables[section]
            for key, value in table.items():
                if allowed is not None and key not in allowed:
                    raise self.fail(f"{section}.{key}", f"unknown key; allowed: {', '.join(allowed)}")
                if allowed is None and not isinstance(value, str):
                    raise self.fail(f"{section}.{key}", f"must be text, got {value!r}")

    def __call__(self, table: dict, section: str, key: str, kind: str, default: Any = None,
                 required: bool = False) -> Any:
        """``table[key]`` checked as ``kind`` (text, bool, size, number > 0), else ``default``."""
        if key not in table:
            if required:
                raise self.fail(f"{section}.{key}", "missing")
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
            raise self.fail(f"{section}.{key}", f"must be {allowed}, got {v!r}")
        return tuple(float(x) for x in v) if kind == "size" else (float(v) if kind == "number" else v)


def object_from_dict(data: Any, *, where: str, base: Path = Path(".")) -> GraspObject:
    """Build an object from an object file's tables (see the module docstring); what differs
    between kinds their :class:`~gripper.objects.kinds.ObjectKind` says."""
    read = _Reader(where)
    read.check_tables(data)
    obj = data.get("object")
    if obj is None:
        raise read.fail("object", "missing section")
    name = read(obj, "object", "name", "text", required=True)
    try:
        check_safe_name(name, "object.name")
    except ValueError as e:
        raise read.fail("object.name", str(e).partition(": ")[2]) from None
    kind_name = read(obj, "object", "kind", "text", required=True)
    try:
        kind = object_kind(kind_name)
    except ValueError as e:
        raise read.fail("object.kind", str(e)) from None
    for section in file_tables().keys() - COMMON_TABLES.keys() - kind.file_tables.keys():
        if section in data:
            owners = [k.name for k in registered_kinds().values() if section in k.file_tables]
            what = "loose contents" if section == "contents" else f"a [{section}] table"
            raise read.fail(section, f"only a {' or '.join(owners)} holds {what}, this is a {kind_name}")
    fields = _common_fields(read, obj, kind)
    fields.update(_damage_and_material(read, data.get("damage", {}), data.get("material", {}), kind))
    fields.update(kind.read_tables(data, read, read.fail))
    fields["reasons"] = tuple(sorted(data.get("reasons", {}).items()))
    return _build(read, obj, kind, fields, base)


def _common_fields(read: _Reader, obj: dict, kind: ObjectKind) -> dict[str, Any]:
    """The ``[object]`` table's fields every kind has (mass or density, friction, the closing
    command, the mesh resolution)."""
    mass = read(obj, "object", "mass", "number")
    density = read(obj, "object", "density", "number")
    takes_density = not kind.deformable
    if (mass is None) == (density is None) and not (kind.sized_by_mesh and mass is None and density is None):
        raise read.fail("object.mass", "give exactly one of mass [kg] or density [kg/m³]")
    if density is not None and not takes_density:
        raise read.fail("object.density", f"a {kind.name} takes its mass, not a density")
    if density is not None:
        OBJECT_DENSITY.check(f"{read.where}: object.density", density)
    close = read(obj, "object", "close_command", "number", default=None if kind.deformable else RIGID_CLOSE,
                 required=kind.deformable)
    size = None
    if not kind.sized_by_mesh:
        if "mesh" in obj:
            raise read.fail("object.mesh", f"only kind = \"mesh\" takes a mesh, this is a {kind.name}")
        size = read(obj, "object", "size", "size", required=True)
    return {"name": obj["name"], "kind": kind.name, "mass": mass, "density": density, "size": size,
            "friction": read(obj, "object", "friction", "number", required=True),
            "yaw_symmetric": read(obj, "object", "yaw_symmetric", "bool", default=kind.yaw_symmetric),
            "close_command": close, "mesh_points": _mesh_points(read, obj.get("mesh_points"), kind)}


def _mesh_points(read: _Reader, points: Any, kind: ObjectKind) -> tuple[int, int, int]:
    if not kind.deformable:
        if points is not None:
            raise read.fail("object.mesh_points", f"a {kind.name} is rigid: it takes no mesh resolution")
        return (0, 0, 0)
    if points is None:
        return kind.default_mesh_points
    lo, hi = MESH_POINTS_RANGE
    if not (isinstance(points, list) and len(points) == 3 and all(
            isinstance(n, int) and not isinstance(n, bool) and lo <= n <= hi for n in points)):
        raise read.fail("object.mesh_points", f"must be three whole numbers from {lo} to {hi} (points "
                        f"along x, y, z), got {points!r}")
    return (points[0], points[1], points[2])


def _damage_and_material(read: _Reader, dmg: dict, mat: dict, kind: ObjectKind) -> dict[str, Any]:
    """The damage criterion and limit, and the material fields the kind needs."""
    if kind.own_criterion is None and "criterion" not in dmg:
        raise read.fail("damage.criterion", "missing: declare how the object is damaged, criterion = "
                        "\"contact_force\" with a limit [N], or \"none\"")
    criterion = read(dmg, "damage", "criterion", "text", default=kind.own_criterion)
    if criterion not in kind.criteria:
        raise read.fail("damage.criterion", f"a {kind.name} allows {', '.join(kind.criteria)}, got {criterion!r}")
    limit = read(dmg, "damage", "limit", "number", default=0.0, required=kind.criteria[criterion].limit is not None)
    for key in kind.material_fields:
        read(mat, "material", key, "number", required=True)
    if not kind.material_fields and mat:
        raise read.fail("material", f"a {kind.name} is rigid: it takes no material table")
    material = {k: read(mat, "material", k, "number", default=0.0) for k in MATERIAL_KEYS}
    return {"damage": criterion, "damage_limit": limit, **material}


def _build(read: _Reader, obj: dict, kind: ObjectKind, fields: dict[str, Any], base: Path) -> GraspObject:
    """The object: from its mesh file (kind ``mesh``), else from its size."""
    mass, density, size = fields.pop("mass"), fields.pop("density"), fields.pop("size")
    if kind.sized_by_mesh:
        mesh_name = read(obj, "object", "mesh", "text", required=True)
        if "size" in obj:
            raise read.fail("object.size", "a mesh takes its size from the mesh; remove size")
        mesh_path = Path(mesh_name) if Path(mesh_name).is_absolute() else base / mesh_name
        try:
            return mesh_object(mesh_path, mass=mass, density=density, friction=fields["friction"],
                               close_command=fields["close_command"], damage=fields["damage"],
                               damage_limit=fields["damage_limit"], yaw_symmetric=fields["yaw_symmetric"],
                               name=fields["name"], reasons=fields["reasons"])
        except ValueError as e:
            raise read.fail("object.mesh", str(e)) from None
    if mass is None:
        volume = kind.volume(size)
        if volume is None:
            raise read.fail("object.density", f"a {kind.name} takes its mass, not a density")
        mass = density * volume
    try:
        return GraspObject(size=size, mass=mass, **fields).validate()
    except ValueError as e:
        raise ValueError(f"{read.where}: {e}") from None
