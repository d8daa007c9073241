"""Rounded convex shapes: a convex body with its edges rounded to a radius, as the point cloud
whose convex hull MuJoCo collides (a Minkowski sum of the body shrunk by the radius with a ball
or a disc of that radius, so the outer size is unchanged).

Example:
    >>> import numpy as np
    >>> square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    >>> np.allclose(inset_polygon(square, 0.1), [[0.1, 0.1], [0.9, 0.1], [0.9, 0.9], [0.1, 0.9]])
    True
"""

from __future__ import annotations

import math

import numpy as np

# Points on each rounded corner: an arc of ARC_POINTS per quarter turn keeps the facets within
# 1 - cos(45° / ARC_POINTS) of the radius (3 points: 2 % of it, 0.03 mm at 1.5 mm).
ARC_POINTS = 3


def _signed_area(poly: np.ndarray) -> float:
    x, y = poly[:, 0], poly[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def inset_polygon(poly: np.ndarray, radius: float) -> np.ndarray:
    """The convex polygon ``poly`` (k, 2), counter-clockwise, with every edge moved inwards by
    ``radius`` [m].

    Raises:
        ValueError: the polygon is not counter-clockwise, or too thin for the radius (an edge
            would vanish).
    """
    poly = np.asarray(poly, dtype=float)
    if _signed_area(poly) <= 0:
        raise ValueError("inset_polygon: the polygon must be counter-clockwise")
    if radius == 0:
        return poly.copy()
    k = len(poly)
    edges = np.roll(poly, -1, axis=0) - poly
    lengths = np.linalg.norm(edges, axis=1)
    normals = np.column_stack([-edges[:, 1], edges[:, 0]]) / lengths[:, None]  # inward (CCW)
    out = np.empty_like(poly)
    for i in range(k):
        a, b = i - 1, i  # the edges before and after vertex i
        # points p with n_a·p = n_a·P_a + r and n_b·p = n_b·P_b + r
        mat = np.array([normals[a], normals[b]])
        rhs = np.array([normals[a] @ poly[a] + radius, normals[b] @ poly[b] + radius])
        out[i] = np.linalg.solve(mat, rhs)
    new_edges = np.roll(out, -1, axis=0) - out
    if np.any(np.einsum("ij,ij->i", new_edges, edges) <= 0):
        raise ValueError(f"inset_polygon: a {radius:g} m rounding does not fit this polygon")
    return out


def _arc_directions(n_arc: int) -> np.ndarray:
    """Unit vectors of a full circle, 4 x ``n_arc`` of them (2D)."""
    phi = np.linspace(0.0, 2.0 * math.pi, 4 * n_arc, endpoint=False)
    return np.column_stack([np.cos(phi), np.sin(phi)])


def _ball_directions(n_arc: int) -> np.ndarray:
    """Unit vectors on a sphere: latitude rings of the circle's spacing (3D)."""
    dirs = [np.array([0.0, 0.0, 1.0]), np.array([0.0, 0.0, -1.0])]
    for lat in np.linspace(-0.5 * math.pi, 0.5 * math.pi, 2 * n_arc + 1)[1:-1]:
        ring = _arc_directions(n_arc) * math.cos(lat)
        dirs += [np.array([x, y, math.sin(lat)]) for x, y in ring]
    return np.asarray(dirs)


def rounded_prism(profile_xz: np.ndarray, width: float, radius: float,
                  n_arc: int = ARC_POINTS, *, taper: float = 1.0) -> np.ndarray:
    """Points (n, 3) of the prism of convex profile ``profile_xz`` (x, z; counter-clockwise in the
    x-z plane seen from -y) extruded over y in [-width/2, width/2], every edge and corner rounded
    to ``radius`` (a ball swept over the prism shrunk by ``radius``). ``taper``: the width at the
    profile's largest x over ``width``, the width changing linearly with x between (a wedge in
    plan view; 1: a straight prism)."""
    x0, x1 = float(profile_xz[:, 0].min()), float(profile_xz[:, 0].max())

    def half(x: np.ndarray, inset: float) -> np.ndarray:
        return 0.5 * width * (1.0 + (taper - 1.0) * (x - x0) / (x1 - x0)) - inset

    if radius == 0:
        return np.vstack([np.column_stack([profile_xz[:, 0], s * half(profile_xz[:, 0], 0.0), profile_xz[:, 1]])
                          for s in (1.0, -1.0)])
    if radius >= 0.5 * width * min(1.0, taper):
        raise ValueError(f"rounded_prism: radius {radius:g} m must be below half the narrowest width "
                         f"{width * min(1.0, taper):g} m")
    core = inset_polygon(profile_xz, radius)
    # the wedge's sides inset by the radius along their own normal, close enough for the small
    # angles of a tapered fingertip (the normal's tilt changes the inset by 1 - cos)
    corners = np.vstack([np.column_stack([core[:, 0], s * half(core[:, 0], radius), core[:, 1]]) for s in (1.0, -1.0)])
    ball = radius * _ball_directions(n_arc)
    return (corners[:, None, :] + ball[None, :, :]).reshape(-1, 3)


def rounded_sweep(section_yz: np.ndarray, length: float, radius: float,
                  n_arc: int = ARC_POINTS, round_ends: bool = False) -> np.ndarray:
    """Points (n, 3) of the convex cross-section ``section_yz`` (y, z; counter-clockwise) swept
    along x over [0, ``length``], its long edges rounded to ``radius`` in the section's plane;
    ``round_ends``: the end faces' edges too (a ball swept over the body shrunk by ``radius``),
    else the ends stay flat."""
    core = inset_polygon(section_yz, radius)
    if radius == 0 or not round_ends:
        ring = core if radius == 0 else (core[:, None, :] + radius * _arc_directions(n_arc)[None]).reshape(-1, 2)
        return np.vstack([np.column_stack([np.full(len(ring), x), ring]) for x in (0.0, length)])
    if 2.0 * radius >= length:
        raise ValueError(f"rounded_sweep: radius {radius:g} m must be below half the length {length:g} m")
    corners = np.vstack([np.column_stack([np.full(len(core), x), core]) for x in (radius, length - radius)])
    ball = radius * _ball_directions(n_arc)[:, [2, 0, 1]]  # the ball's axis along x
    return (corners[:, None, :] + ball[None, :, :]).reshape(-1, 3)


__all__ = ["ARC_POINTS", "inset_polygon", "rounded_prism", "rounded_sweep"]
