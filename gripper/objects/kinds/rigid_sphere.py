"""A rigid sphere (``size``: its radius three times [m])."""

from __future__ import annotations

import math

import mujoco

from gripper.objects.kinds.rigid import RigidKind


class RigidSphere(RigidKind):
    name = "rigid_sphere"
    yaw_symmetric = True

    def add_geom(self, spec, body, obj):
        return body.add_geom(name="object_geom", type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[obj.size[0], 0, 0])

    def volume(self, size):
        return 4 / 3 * math.pi * size[0] ** 3

    def check(self, obj, where):
        if not (obj.size[0] == obj.size[1] == obj.size[2]):
            raise ValueError(f"{where}.size: a sphere's three half-extents are its radius, got {list(obj.size)}")
