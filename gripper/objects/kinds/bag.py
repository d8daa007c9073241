"""A film bag around a rigid pack (``gripper/data/objects/bag_pack.toml``): a flexcomp cylinder
of polyethylene film holding one box; the pack is the body a trial tracks, and the film tears
when its edge strain passes the limit."""

from __future__ import annotations

import mujoco

from gripper.objects.kinds.base import CONTENTS_BODY, OBJECT_BODY, object_friction
from gripper.objects.kinds.flex import BAG_DAMPING, PE_POISSON, FilmKind, flex_contact, stiff_against_film

# The bag's film mass and the rigid pack inside it (gripper/data/objects/bag_pack.toml: 3 g of
# film, a 36 × 36 × 44 mm pack of 80 g).
BAG_FILM_MASS = 0.003  # kg
BAG_CONTENTS_HALF = (0.018, 0.018, 0.022)  # m


class Bag(FilmKind):
    name = "bag"
    material_fields = ("youngs_modulus", "thickness")
    # 4 x 4 x 5 points (64 vertices: film elements of about 17 mm), half the cost of 5 x 5 x 6
    # with the outcome and the strain inside the 4 / 5 / 6-point spread (docs/performance.md)
    default_mesh_points = (4, 4, 5)
    tracked_body = CONTENTS_BODY

    def build(self, spec, obj, place, pos, quat, *, rigid_contact):
        r, _, hz = obj.size
        c = obj.mesh_points
        friction = object_friction(obj, place)
        film_mass = BAG_FILM_MASS * place.mass_scale
        flex = spec.worldbody.make_flex(
            OBJECT_BODY, type="cylinder", dim=2, dof="full", count=list(c),
            spacing=[2 * r / (c[0] - 1), 2 * r / (c[1] - 1), 2 * hz / (c[2] - 1)], radius=0.0007,
            mass=film_mass, inertiabox=0.002, pos=pos, quat=quat, elastic2d=3)
        flex.young = obj.youngs_modulus
        flex.poisson = PE_POISSON
        flex.thickness = obj.thickness
        flex.damping = BAG_DAMPING
        flex.rgba = [0.75, 0.85, 0.95, 0.6]
        flex_contact(flex, friction)
        hx, hy, hcz = BAG_CONTENTS_HALF
        contents = spec.worldbody.add_body(name=CONTENTS_BODY, pos=[pos[0], pos[1], hcz + 0.0015], quat=quat)
        contents.add_freejoint(name="object_contents_free")
        g = contents.add_geom(name="object_contents_geom", type=mujoco.mjtGeom.mjGEOM_BOX,
                              size=[hx, hy, hcz], rgba=[0.8, 0.6, 0.2, 1.0])
        g.mass = obj.mass * place.mass_scale - film_mass
        stiff_against_film(g, friction)
