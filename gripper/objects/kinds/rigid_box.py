"""A rigid box (``size``: its half-extents [m])."""

from __future__ import annotations

import mujoco

from gripper.objects.kinds.rigid import RigidKind


class RigidBox(RigidKind):
    name = "rigid_box"
    square_footprint = True

    def add_geom(self, spec, body, obj):
        return body.add_geom(name="object_geom", type=mujoco.mjtGeom.mjGEOM_BOX, size=list(obj.size))

    def volume(self, size):
        return 8 * size[0] * size[1] * size[2]
