"""The duct's cross-section of paper 001's actuator in a deformed shape, in the section's own
frame: how far the finite-element model's section departs from the reference shape the
semi-analytical moment balance keeps (:mod:`gripper.references.bending_moment_model`).

Example:
    >>> from gripper.references.actuator_mesh import MeshSize, actuator_mesh
    >>> from gripper.references.actuator_section import duct_section
    >>> from gripper.references.pneumatic_params import PneumaticActuator
    >>> m = actuator_mesh(PneumaticActuator(), MeshSize())
    >>> round(duct_section(m, m.quad_points, 0.065)["height"] * 1e3, 3)   # undeformed: the duct's 6 mm
    6.0
"""

from __future__ import annotations

import numpy as np

from gripper.references.actuator_mesh import ActuatorMesh, Geometry


def polygon_area_moment(xy: np.ndarray) -> tuple[float, float]:
    """Area and first moment about y = 0 (∫ y dA) of a closed polygon [m², m³]."""
    x, y = xy.T
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    cross = x * y1 - x1 * y
    return float(0.5 * cross.sum()), float((cross * (y + y1)).sum() / 6.0)


def duct_section(mesh: ActuatorMesh, deformed: np.ndarray, z0: float) -> dict:
    """The duct's half cross-section at the station ``z0`` [m] in the deformed shape, in the
    section's own frame: the section's nodes moved back by the rigid motion that best fits its
    neutral-layer nodes (which do not stretch; Kabsch), so what is left is the section's change
    of shape. Returns its area, first moment about the neutral layer's mid-plane (the pressure's
    lever, :mod:`gripper.references.bending_moment_model`) and height [m², m³, m]."""
    g = Geometry(mesh.actuator)
    ref = mesh.quad_points
    at = np.flatnonzero(np.isclose(ref[:, 2], z0, rtol=0, atol=1e-9))
    neutral = at[np.abs(ref[at, 1]) <= 0.5 * mesh.actuator.neutral_thickness + 1e-12]
    a, b = ref[neutral], deformed[neutral]
    ca, cb = a.mean(axis=0), b.mean(axis=0)
    u, _, vt = np.linalg.svd((b - cb).T @ (a - ca))
    rot = u @ np.diag([1.0, 1.0, np.sign(np.linalg.det(u @ vt))]) @ vt  # maps reference to deformed
    local = (deformed[at] - cb) @ rot + ca
    on_duct = mesh.duct_surface_points(ref[at])
    x, y = ref[at, 0], ref[at, 1]
    wall = on_duct & (y > g.y_centre + 1e-12)
    flat = on_duct & np.isclose(y, g.y_centre, atol=1e-12)
    # the half duct's outline: along the flat side from the mid-plane, round the wall, down the mid-plane
    theta = np.arctan2(y - g.y_centre, x)
    order = np.r_[np.flatnonzero(flat)[np.argsort(x[flat])], np.flatnonzero(wall)[np.argsort(theta[wall])]]
    outline = local[order][:, :2]
    outline = np.vstack([outline, [0.0, outline[-1, 1]], [0.0, outline[0, 1]]]) if outline[-1, 0] > 1e-12 else outline
    area, moment = polygon_area_moment(outline)
    return {"area": area, "first_moment": moment, "height": float(outline[:, 1].max() - outline[:, 1].min())}


def mid_station(mesh: ActuatorMesh) -> float:
    """The cells' end nearest the middle of the length [m] (where every node of a section is)."""
    z_levels = np.unique(np.round(mesh.points[:, 2], 12))
    return float(z_levels[np.argmin(np.abs(z_levels - 0.5 * mesh.actuator.length))])


__all__ = ["duct_section", "mid_station", "polygon_area_moment"]
