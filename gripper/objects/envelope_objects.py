"""The capability envelope's test objects: rigid spheres, cylinders and square boxes of a given
width, mass and friction coefficient (``gripper envelope`` and the study response ``envelope``).

Example:
    >>> from gripper.objects.envelope_objects import envelope_object
    >>> envelope_object("cylinder", 0.03, 0.05, 0.6).size
    (0.015, 0.015, 0.03)
"""

from __future__ import annotations

from gripper.objects.grasp_object import GraspObject

SHAPES = {"sphere": "rigid_sphere", "cylinder": "rigid_cylinder", "box": "rigid_box"}
# Height of the envelope's cylinders and boxes [m]: the library block's and cylinder's 60-70 mm
# class, so that the palm stands where it does for them (grasp height: fingertips 8 mm above
# the floor, palm 10 mm above the top).
ENVELOPE_HEIGHT = 0.060
# A point is held when at least this fraction of its trials succeed.
HELD_FRACTION = 2 / 3


def point_held(fraction: float | None) -> bool:
    """Whether a point whose trials succeeded in ``fraction`` of the runs that ended (None: none
    ended) counts as held: at least :data:`HELD_FRACTION`."""
    return fraction is not None and fraction >= HELD_FRACTION - 1e-9


def envelope_object(shape: str, size: float, mass: float, friction: float) -> GraspObject:
    """The rigid object of one envelope point (``size``: the width [m])."""
    r = 0.5 * size
    half = (r, r, r) if shape == "sphere" else (r, r, 0.5 * ENVELOPE_HEIGHT)
    name = f"{shape}-{size * 1e3:g}mm-{mass * 1e3:g}g-mu{friction:g}"
    return GraspObject(name=name, kind=SHAPES[shape], size=half, mass=mass, friction=friction,
                       yaw_symmetric=shape != "box", close_command=3.0, damage="none", damage_limit=0.0,
                       oversize=True).validate()


def check_envelope_points(shapes, sizes, masses, frictions) -> None:
    """Build the object of every shape and width, every mass and every friction once, so that a
    grid whose object leaves the physical ranges (:mod:`gripper.core.ranges`) is refused before
    any trial runs.

    Raises:
        ValueError: starting with the list at fault (``sizes: ...``, ``masses: ...``, ...).
    """
    w0, m0, mu0 = 0.03, 0.05, 0.6  # a point inside every range: each list is checked on its own
    builds = [("sizes", s, w, m0, mu0) for s in shapes for w in sizes]
    builds += [("masses", shapes[0], w0, m, mu0) for m in masses]
    builds += [("frictions", shapes[0], w0, m0, mu) for mu in frictions]
    for key, *point in builds:
        try:
            envelope_object(*point)
        except ValueError as e:
            raise ValueError(f"{key}: {e}") from None


__all__ = ["ENVELOPE_HEIGHT", "HELD_FRACTION", "SHAPES", "check_envelope_points", "envelope_object", "point_held"]
