"""A closed zipper bag: a film shell (a box surface of the filled bag's size, as the paper
box's, with the film's modulus and gauge) holding loose rigid items in one layer on its floor
(the object file's ``[contents]`` table); it tears when its film's edge strain passes the limit."""

from __future__ import annotations

import math

import mujoco

from gripper.core.ranges import OBJECT_HALF_EXTENT, OBJECT_MASS
from gripper.objects.kinds.base import CONTENTS_BODY, object_friction
from gripper.objects.kinds.flex import BAG_DAMPING, PE_POISSON, FilmKind, shell_flex, stiff_against_film

# A zipper bag's contents lie in one layer on the bag's floor, in a grid, this far from the film
# and from each other [m] (the film's contact radius plus a margin).
ZIPPER_GAP = 0.002
CONTENTS_MAX = 64


class ZipperBag(FilmKind):
    name = "zipper_bag"
    material_fields = ("youngs_modulus", "thickness")
    default_mesh_points = (6, 4, 3)  # about 10 x 7.5 x 8 mm film elements (docs/objects.md)
    square_footprint = True
    file_tables = {"contents": ("count", "size", "mass")}

    def check(self, obj, where):
        super().check(obj, where)
        zipper_bag_layout(obj)  # raises if the contents do not fit or outweigh the bag

    def read_tables(self, tables, read, fail):
        cont = tables.get("contents", {})
        count = cont.get("count")
        if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count <= CONTENTS_MAX:
            raise fail("contents.count", f"must be a whole number from 1 to {CONTENTS_MAX}, got {count!r}")
        return {"contents_count": count,
                "contents_size": read(cont, "contents", "size", "size", required=True),
                "contents_mass": read(cont, "contents", "mass", "number", required=True)}

    def build(self, spec, obj, place, pos, quat, *, rigid_contact):
        friction = object_friction(obj, place)
        film_mass = (obj.mass - obj.contents_count * obj.contents_mass) * place.mass_scale
        shell_flex(spec, obj, mass=film_mass, pos=pos, quat=quat, radius=0.0007, poisson=PE_POISSON,
                   damping=BAG_DAMPING, rgba=[0.75, 0.85, 0.95, 0.5], friction=friction)
        c, s_ = math.cos(place.yaw), math.sin(place.yaw)
        for k, (x, y, z) in enumerate(zipper_bag_layout(obj)):
            body = spec.worldbody.add_body(name=f"{CONTENTS_BODY}_{k}",
                                           pos=[pos[0] + c * x - s_ * y, pos[1] + s_ * x + c * y, pos[2] + z],
                                           quat=quat)
            body.add_freejoint(name=f"{CONTENTS_BODY}_{k}_free")
            g = body.add_geom(name=f"{CONTENTS_BODY}_{k}_geom", type=mujoco.mjtGeom.mjGEOM_BOX,
                              size=list(obj.contents_size), rgba=[0.85, 0.2, 0.15, 1.0])
            g.mass = obj.contents_mass * place.mass_scale
            stiff_against_film(g, friction)  # as the bag's pack: as stiff against the film as the fingers


def zipper_bag_layout(obj) -> list[tuple[float, float, float]]:
    """Centres of a zipper bag's items in the bag's frame [m]: one layer on its floor, a grid
    along the bag's length (x) and width (y), each item's long side along x.

    Raises:
        ValueError: no contents, items that do not fit in one layer, or contents heavier than
            the bag's total mass.
    """
    where = f"object.{obj.name}.contents"
    n = obj.contents_count
    if not (isinstance(n, int) and not isinstance(n, bool) and 1 <= n <= CONTENTS_MAX):
        raise ValueError(f"{where}.count: a zipper_bag holds 1 to {CONTENTS_MAX} items, got {n!r}")
    hs = obj.contents_size
    if len(hs) != 3:
        raise ValueError(f"{where}.size: three half-extents [m], got {list(hs)!r}")
    for i, v in enumerate(hs):
        OBJECT_HALF_EXTENT.check(f"{where}.size[{i}]", v)
    m = OBJECT_MASS.check(f"{where}.mass", obj.contents_mass)
    if not n * m < obj.mass:
        raise ValueError(f"{where}.mass: each item > 0 kg and all {n} lighter than the bag's total "
                         f"{obj.mass:g} kg (film included), got {m!r}")
    bx, by, bz = obj.size
    pitch_x, pitch_y = 2 * hs[0] + ZIPPER_GAP, 2 * hs[1] + ZIPPER_GAP
    nx = int((2 * bx - ZIPPER_GAP) // pitch_x)
    ny = int((2 * by - ZIPPER_GAP) // pitch_y)
    if nx * ny < n or 2 * hs[2] + 2 * ZIPPER_GAP > 2 * bz:
        raise ValueError(f"{where}: {n} items of {2e3 * hs[0]:.1f} x {2e3 * hs[1]:.1f} x {2e3 * hs[2]:.1f} mm "
                         f"do not lie in one layer inside {2e3 * bx:.0f} x {2e3 * by:.0f} x {2e3 * bz:.0f} mm")
    rows = math.ceil(n / nx)
    out = []
    for k in range(n):
        i, j = k % nx, k // nx
        cols = min(nx, n - j * nx)
        out.append(((i - 0.5 * (cols - 1)) * pitch_x, (j - 0.5 * (rows - 1)) * pitch_y,
                    -bz + ZIPPER_GAP + hs[2]))
    return out
