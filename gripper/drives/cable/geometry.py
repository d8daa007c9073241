"""Shapes of the finger elements and the positions of the cable path, in the finger frame.

Finger frame (SI, metres): x along the finger from the palm face (x = 0) to the tip, z from the
back face (z = 0, the bridge side) to the grasping face (z = height), y across.

Each element is a prism whose side profile (x-z) is convex: a block of length ``pitch`` with half
of a triangular cut taken out of each end that meets another element. The cut's apex sits on the
bridge top (z = bridge_thickness); its faces open at ``cut_angle`` towards the grasping face.

Example:
    >>> from gripper.core.params import FingerGeometry
    >>> prof = element_profile(FingerGeometry(), "middle")
    >>> len(prof)
    6
"""

from __future__ import annotations

from typing import Literal

import numpy as np

from gripper.core.params import Cable, FingerGeometry
from gripper.core.rounding import rounded_prism

ElementKind = Literal["base", "middle", "tip"]


def element_kind(index: int, n_segments: int) -> ElementKind:
    """Kind of element ``index`` (0-based) of ``n_segments``."""
    if index == 0:
        return "base"
    if index == n_segments - 1:
        return "tip"
    return "middle"


def element_profile(g: FingerGeometry, kind: ElementKind) -> np.ndarray:
    """Side profile of one element, shape (k, 2) of (x, z) [m], counter-clockwise, convex.

    The element spans x in [0, pitch] in its own frame (origin at its proximal end, back face).
    """
    p, h, tb, d = g.pitch, g.height, g.bridge_thickness, g.cut_half_width
    prox_cut = kind in ("middle", "tip")
    dist_cut = kind in ("middle", "base")
    pts = [(0.0, 0.0), (p, 0.0)]
    pts += [(p, tb), (p - d, h)] if dist_cut else [(p, h)]
    pts += [(d, h), (0.0, tb)] if prox_cut else [(0.0, h)]
    return np.asarray(pts)


def element_taper(g: FingerGeometry, kind: ElementKind) -> float:
    """The element's distal width over its proximal width: ``g.tip_taper`` for the tip, else 1."""
    return g.tip_taper if kind == "tip" else 1.0


def element_vertices(g: FingerGeometry, kind: ElementKind) -> np.ndarray:
    """Vertices of the element prism, shape (2k, 3) [m]: the profile extruded over the width
    (the tip's narrowing linearly to ``g.tip_width`` at its distal end)."""
    return rounded_prism(element_profile(g, kind), g.width, 0.0, taper=element_taper(g, kind))


def element_face(g: FingerGeometry, kind: ElementKind) -> tuple[float, float, float]:
    """The grasping face between the element's cuts: its ends x0, x1 [m] and its mean width [m]
    (the tip's narrows)."""
    prof = element_profile(g, kind)
    top = prof[np.isclose(prof[:, 1], g.height), 0]
    x0, x1 = float(top.min()), float(top.max())
    mid = 0.5 * (x0 + x1) / g.pitch
    return x0, x1, g.width * (1.0 + (element_taper(g, kind) - 1.0) * mid)


def cable_line_z(g: FingerGeometry, cable: Cable) -> float:
    """Height of the cable via points: the hole axis [m].

    The 0.5 mm cable runs loose in 6 mm holes (paper 000 §II). It is routed through a via point
    on the hole axis at the middle of each element and runs straight from element to element
    across the cuts. Up to the cut-closing angle that straight chord stays inside the holes (it
    reaches the mouth wall, (pitch/2)·tan(theta/2) ≈ hole radius, only near closure), so the
    path is the one a taut cable takes; unlike via points at the hole mouths it never folds back
    on itself when a hinge turns about the bridge, below the cut apex.
    """
    del cable  # the cable rides the hole axis whatever its diameter
    return g.hole_height


def cable_via_points(g: FingerGeometry, cable: Cable, kind: ElementKind) -> list[tuple[str, float]]:
    """Cable via points of one element as (role, x) at height :func:`cable_line_z`.

    Roles: ``mid`` (hole axis at the element's middle), ``anchor`` (where the cable is fixed,
    the tip's distal face: paper 000 §II "one end of the cable is fixed at the end").
    """
    del cable
    pts = [("mid", 0.5 * g.pitch)]
    if kind == "tip":
        pts.append(("anchor", g.pitch))
    return pts
