"""The rigid kinds' shared build: one free body named ``object`` with one geom, its mass and
the silicone-object friction, near-rigid contact where the fingers carry pads.

Friction is the silicone–object pair coefficient. MuJoCo otherwise takes the larger of the two
geoms' coefficients, so object geoms carry ``priority`` 1 and their value is the one used.
"""

from __future__ import annotations

from typing import Any

import mujoco

from gripper.objects.kinds.base import OBJECT_BODY, ObjectKind, object_friction

# A rigid part's contact when the fingers carry compliant pads (gripper.parts.pads): near-rigid,
# so the pads' springs, in N/m, carry the indentation. A contact's static stiffness is
# 1 / ((1 - d) A timeconst^2), A its inverse effective mass in the integrator's metric: with
# d = 0.999 and 4 ms (twice the trials' step, MuJoCo's stability floor) it is 2.7e5 N/m or more
# for A up to 230 kg⁻¹ (a 1 g pad on a 10 g part), about 100 times the pads' few thousand N/m.
# Fixed in seconds, not steps, so the contact is the same at every step size. The part's geom has
# priority, so these are the values its contacts use (with the floor too: a rigid part on a table).
RIGID_CONTACT_SOLREF = (0.004, 1.0)
RIGID_CONTACT_SOLIMP = (0.999, 0.999, 0.001, 0.5, 2.0)
RIGID_RGBA = (0.2, 0.5, 0.8, 1.0)


class RigidKind(ObjectKind):
    """A rigid solid: subclasses give its geom (:meth:`add_geom`) and volume."""

    def add_geom(self, spec: mujoco.MjSpec, body: mujoco.MjsBody, obj: Any) -> mujoco.MjsGeom:
        """The object's one geom on ``body`` (named ``object_geom``)."""
        raise NotImplementedError

    def build(self, spec, obj, place, pos, quat, *, rigid_contact: bool) -> None:
        body = spec.worldbody.add_body(name=OBJECT_BODY, pos=pos, quat=quat)
        body.add_freejoint(name="object_free")
        geom = self.add_geom(spec, body, obj)
        geom.mass = obj.mass * place.mass_scale
        geom.friction = object_friction(obj, place)
        geom.priority = 1
        if rigid_contact:
            geom.solref = list(RIGID_CONTACT_SOLREF)
            geom.solimp = list(RIGID_CONTACT_SOLIMP)
        geom.rgba = list(RIGID_RGBA)
