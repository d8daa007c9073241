"""A rigid upright cylinder (``size``: radius, radius, half-height [m])."""

from __future__ import annotations

import math

import mujoco

from gripper.objects.kinds.rigid import RigidKind


class RigidCylinder(RigidKind):
    name = "rigid_cylinder"
    yaw_symmetric = True

    def add_geom(self, spec, body, obj):
        return body.add_geom(name="object_geom", type=mujoco.mjtGeom.mjGEOM_CYLINDER,
                             size=[obj.size[0], obj.size[2], 0])

    def volume(self, size):
        return math.pi * size[0] ** 2 * 2 * size[2]
