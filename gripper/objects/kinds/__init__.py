"""Object kinds: one module per kind behind :class:`~gripper.objects.kinds.base.ObjectKind`,
registered by name. The built-in kinds: ``rigid_box``, ``rigid_cylinder``, ``rigid_sphere``,
``mesh`` (rigid), ``balloon``, ``paper_box``, ``bag``, ``zipper_bag`` (deformable). A user's
kind joins with :func:`register_object_kind` (``docs/architecture.md``, "Add an object kind").

Example:
    >>> from gripper.objects.kinds import object_kind
    >>> sorted(object_kind("paper_box").criteria)
    ['dent']
"""

from __future__ import annotations

from gripper.objects.kinds.bag import Bag
from gripper.objects.kinds.balloon import Balloon
from gripper.objects.kinds.base import (
    CONTENTS_BODY,
    OBJECT_BODY,
    Criterion,
    ObjectKind,
    register_object_kind,
    registered_kinds,
    unregister_object_kind,
)
from gripper.objects.kinds.mesh import MeshPart
from gripper.objects.kinds.paper_box import PaperBox
from gripper.objects.kinds.rigid_box import RigidBox
from gripper.objects.kinds.rigid_cylinder import RigidCylinder
from gripper.objects.kinds.rigid_sphere import RigidSphere
from gripper.objects.kinds.zipper_bag import ZipperBag

for _kind in (RigidBox(), RigidCylinder(), RigidSphere(), MeshPart(), Balloon(), PaperBox(), Bag(), ZipperBag()):
    register_object_kind(_kind)


def object_kind(name: str) -> ObjectKind:
    """The registered kind called ``name``.

    Raises:
        ValueError: no such kind (lists the registered ones).
    """
    kinds = registered_kinds()
    if name not in kinds:
        raise ValueError(f"must be one of {', '.join(kinds)}, got {name!r}")
    return kinds[name]


__all__ = ["CONTENTS_BODY", "OBJECT_BODY", "Criterion", "ObjectKind", "object_kind", "register_object_kind",
           "registered_kinds", "unregister_object_kind"]
