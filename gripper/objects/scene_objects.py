"""Building a grasp object into a scene: where it stands (:class:`Placement`, the trial's
sampled perturbation), and its MJCF, which its kind builds (:mod:`gripper.objects.kinds`: a
rigid geom or mesh, or a flex, the balloon's trilinear cage, the box's and the bags' shells,
with its contents).

Friction is the silicone–object pair coefficient; contact constants are the kinds'
(``gripper.objects.kinds.rigid.RIGID_CONTACT_SOLREF``, ``gripper.objects.kinds.flex.FLEX_CONTACT_SOLREF``).

Example:
    >>> import mujoco
    >>> from gripper.objects.library import get_object
    >>> from gripper.objects.scene_objects import Placement, add_object
    >>> spec = mujoco.MjSpec()
    >>> add_object(spec, get_object("block"), Placement(x=0.005))
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco

from gripper.core.fields import Validated, param
from gripper.objects.grasp_object import GraspObject
from gripper.objects.kinds.base import CONTENTS_BODY, OBJECT_BODY

# Height of the floor contact margin used when placing objects: objects start 1 mm above the
# floor and settle onto it during the protocol's settle phase.
DROP_GAP = 0.001


# --- building into a scene -----------------------------------------------------------------

@dataclass(frozen=True)
class Placement(Validated):
    """Where and how one trial's object is placed (the sampled perturbation).

    Attributes:
        x, y: offset of the object centre from the palm axis.
        yaw: rotation about the vertical.
        mass_scale, friction_scale: multipliers on the object's mass and friction.
    """

    SECTION = "placement"

    x: float = param(0.0, "m", source="centred under the palm")
    y: float = param(0.0, "m", source="centred under the palm")
    yaw: float = param(0.0, "rad", source="not rotated")
    mass_scale: float = param(1.0, "-", gt=0, source="the object's own mass")
    friction_scale: float = param(1.0, "-", gt=0, source="the object's own friction")


def _yaw_quat(yaw: float) -> list[float]:
    return [math.cos(0.5 * yaw), 0.0, 0.0, math.sin(0.5 * yaw)]


def add_object(spec: mujoco.MjSpec, obj: GraspObject, place: Placement = Placement(), *,
               rigid_contact: bool = True) -> None:
    """Add ``obj`` to ``spec`` standing on the floor at ``place``; edits ``spec`` in place.
    ``rigid_contact``: a rigid part's contacts near-rigid (``RIGID_CONTACT_SOLREF``), as the
    pads need; False keeps MuJoCo's default softness (``contact.model = "solver"``)."""
    obj.validate()
    pos = [place.x, place.y, obj.size[2] + DROP_GAP]
    obj.object_kind.build(spec, obj, place, pos, _yaw_quat(place.yaw), rigid_contact=rigid_contact)


__all__ = ["CONTENTS_BODY", "DROP_GAP", "OBJECT_BODY", "Placement", "add_object"]
