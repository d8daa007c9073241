"""A depth camera in the palm, and what the approach reads from its image: the support
surface, the object's top height, footprint and centroid.

The camera, at the palm face's centre looking down, is modelled on a short-range active-stereo
depth camera (a RealSense D405 class module): stereo depth noise σ(z) = z²·subpixel/(f·B),
dropout, a 64 × 64 region of interest cast as MuJoCo rays. The estimate finds the support, the
object's top, footprint and centroid. The model and the estimate, step by step:
``docs/controller.md``, "The palm camera's model and estimate".

Example:
    >>> from gripper.sim.depth import DepthCamera
    >>> round(float(DepthCamera().depth_sigma(0.25)) * 1e3, 2)   # mm of RMS depth error at 25 cm
    0.62
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from gripper.core.fields import Validated, param

# Shares of the measured points, the lowest, taken to be the support surface: a fifth, or, where
# nothing then stands above it (an object that fills more than four fifths of the view), 2 %.
SUPPORT_QUANTILES = (0.2, 0.02)
# Percentile of the object points' heights taken as its top.
TOP_PERCENTILE = 98.0


class NoObjectSeen(RuntimeError):
    """The depth image shows nothing standing on the support surface."""


@dataclass(frozen=True)
class DepthCamera(Validated):
    """The palm camera and its estimate's thresholds (SI units; module docstring)."""

    SECTION = "depth"

    pixels: int = param(64, "-", ge=8, le=256, integer=True,
                        source="assumed: a 64 x 64 region of interest decimated from the 848 x 480 image")
    half_angle_deg: float = param(17.0, "deg", gt=1, lt=43.5,
                                  source="assumed: the region of interest covers ±76 mm of table from the "
                                  "home height (0.25 m); inside the D405's 87° x 58° field of view")
    focal_px: float = param(447.0, "px", gt=0,
                            source="D405 depth field of view 87° across 848 px: f = 424 / tan(43.5°)")
    baseline: float = param(0.018, "m", gt=0, source="D405 (D401 module) datasheet: 18 mm stereo baseline")
    subpixel: float = param(0.08, "px", ge=0, le=1,
                            source="assumed: 0.08 px RMS disparity, the typical figure Intel's depth-tuning "
                            "white paper gives for a textured scene")
    dropout: float = param(0.02, "-", ge=0, lt=1, source="assumed: 2 % of pixels without depth")
    min_range: float = param(0.07, "m", ge=0, source="D405: ideal range 7-50 cm")
    max_range: float = param(0.50, "m", gt=0, source="D405: ideal range 7-50 cm")
    object_threshold: float = param(0.003, "m", gt=0, le=0.05,
                                    source="assumed: five times the RMS depth error at the home height")
    min_object_pixels: int = param(4, "-", ge=1, le=1000, integer=True,
                                   source="assumed: a 10 mm part seen from 0.25 m covers about 16 pixels")

    def depth_sigma(self, z):
        """RMS depth error at depth ``z`` [m] (the stereo law of the module docstring)."""
        return np.asarray(z) ** 2 * self.subpixel / (self.focal_px * self.baseline)

    def ray_directions(self) -> np.ndarray:
        """Unit ray directions in the camera frame (x, y across, -z the optical axis), (n², 3),
        row-major over the pinhole grid."""
        n = self.pixels
        u = math.tan(math.radians(self.half_angle_deg)) * ((np.arange(n) + 0.5) * 2.0 / n - 1.0)
        uu, vv = np.meshgrid(u, u)
        vec = np.column_stack([uu.ravel(), vv.ravel(), -np.ones(n * n)])
        return vec / np.linalg.norm(vec, axis=1)[:, None]

    def to_dict(self) -> dict:
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


@dataclass(frozen=True)
class ObjectEstimate:
    """What the depth image says of the object (world frame, SI units).

    Attributes:
        support_z: height of the support surface [m].
        top_z: height of the object's top [m]; ``height`` is ``top_z - support_z``.
        x, y: centroid of its footprint seen from above [m].
        length, width: sides of the footprint's smallest enclosing rectangle, length >= width [m].
        yaw: direction of the rectangle's long side [rad].
        radius: farthest the footprint reaches from its centroid [m] (a disc's radius, a
            square's half-diagonal).
        pixels: object pixels seen.
    """

    support_z: float
    top_z: float
    x: float
    y: float
    length: float
    width: float
    yaw: float
    radius: float
    pixels: int

    @property
    def height(self) -> float:
        return self.top_z - self.support_z

    def to_dict(self) -> dict[str, float]:
        return {"support_z_m": self.support_z, "height_m": self.height, "x_m": self.x, "y_m": self.y,
                "length_m": self.length, "width_m": self.width, "yaw_rad": self.yaw,
                "radius_m": self.radius, "pixels": float(self.pixels)}


def depth_points(m: mujoco.MjModel, d: mujoco.MjData, cam: DepthCamera, origin: np.ndarray,
                 rot: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """Cast the camera's rays from ``origin`` (world, [m]) with orientation ``rot`` (3 × 3,
    camera to world) into the current state of ``d`` (positions and flex vertices computed);
    return the measured points (n, 3) in the world frame, NaN where there is no depth."""
    dirs = cam.ray_directions() @ np.asarray(rot).T
    n = len(dirs)
    group = np.array([1, 0, 0, 0, 0, 0], dtype=np.uint8)
    geomid = np.zeros(n, dtype=np.int32)
    dist = np.zeros(n)
    pnt = np.asarray(origin, dtype=float)
    mujoco.mj_multiRay(m, d, pnt, np.ascontiguousarray(dirs).ravel(), group, 1, -1, geomid, dist, None, n,
                       cam.max_range * 2)
    dist[dist < 0] = np.inf
    for f in range(m.nflex):
        if m.flex_group[f] != 0:
            continue
        for i in range(n):
            t = mujoco.mj_rayFlex(m, d, 0, 0, 0, 1, 0, f, pnt, dirs[i])
            if 0 <= t < dist[i]:
                dist[i] = t
    axis = -np.asarray(rot)[:, 2]
    cos = dirs @ axis  # depth along the optical axis per unit of range
    seen = np.isfinite(dist)
    z = np.where(seen, dist, 0.0) * cos
    seen &= (z >= cam.min_range) & (z <= cam.max_range)
    z_noisy = z + rng.standard_normal(n) * np.where(seen, cam.depth_sigma(np.where(seen, z, 0.0)), 0.0)
    seen &= rng.random(n) >= cam.dropout
    pts = pnt + dirs * np.where(seen, z_noisy / cos, 0.0)[:, None]
    pts[~seen] = np.nan
    return pts


def estimate_object(points: np.ndarray, cam: DepthCamera) -> ObjectEstimate:
    """The object estimate of the module docstring from the measured points, (pixels², 3) in
    the camera's row-major pixel order, NaN rows where there is no depth.

    Raises:
        NoObjectSeen: fewer than ``cam.min_object_pixels`` points stand on the support.
    """
    from scipy import ndimage
    from scipy.spatial import ConvexHull, QhullError

    valid = np.isfinite(points).all(axis=1)
    pts = points[valid]
    if len(pts) < 10:
        raise NoObjectSeen(f"no object seen: the depth image has {len(pts)} valid pixels")
    z = pts[:, 2]
    for q in SUPPORT_QUANTILES:  # the lowest fifth is the table, unless the object fills the view
        level = float(np.quantile(z, q))
        support = float(np.median(z[np.abs(z - level) < cam.object_threshold]))
        if (z > support + cam.object_threshold).sum() >= cam.min_object_pixels:
            break
    above = valid.copy()
    above[valid] = points[valid, 2] > support + cam.object_threshold
    n = int(round(math.sqrt(len(points))))
    labels, count = ndimage.label(above.reshape(n, n), structure=np.ones((3, 3)))
    if count:
        sizes = np.bincount(labels.ravel())[1:]
        above = (labels == 1 + int(np.argmax(sizes))).ravel()
    obj = points[above]
    if len(obj) < cam.min_object_pixels:
        raise NoObjectSeen(f"no object seen: {len(obj)} pixels stand more than {cam.object_threshold * 1e3:.0f} mm "
                           f"above the support surface (at least {cam.min_object_pixels} needed)")
    top = float(np.percentile(obj[:, 2], TOP_PERCENTILE))
    xy = obj[:, :2]
    try:
        hull = xy[ConvexHull(xy).vertices]
    except (QhullError, ValueError):  # all points on a line: a degenerate footprint
        hull = None
    if hull is None or len(hull) < 3:
        c = xy.mean(axis=0)
        span = np.ptp(xy, axis=0)
        return ObjectEstimate(support, top, float(c[0]), float(c[1]), float(span.max()), float(span.min()),
                              0.0, float(np.hypot(*(xy - c).T).max()), len(obj))
    cx, cy, _ = _polygon_centroid(hull)
    length, width, yaw = _min_area_rectangle(hull)
    radius = float(np.hypot(hull[:, 0] - cx, hull[:, 1] - cy).max())
    return ObjectEstimate(support, top, cx, cy, length, width, yaw, radius, len(obj))


def _polygon_centroid(poly: np.ndarray) -> tuple[float, float, float]:
    """Area centroid and area of a simple polygon (vertices in order)."""
    x, y = poly[:, 0], poly[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    area = 0.5 * cross.sum()
    if abs(area) < 1e-12:
        c = poly.mean(axis=0)
        return float(c[0]), float(c[1]), 0.0
    cx = ((x + xn) * cross).sum() / (6 * area)
    cy = ((y + yn) * cross).sum() / (6 * area)
    return float(cx), float(cy), float(abs(area))


def _min_area_rectangle(hull: np.ndarray) -> tuple[float, float, float]:
    """(length, width, yaw) of the smallest rectangle enclosing a convex polygon: one of its
    sides lies along a hull edge (rotating calipers)."""
    best = (math.inf, 0.0, 0.0, 0.0)
    edges = np.roll(hull, -1, axis=0) - hull
    for ex, ey in edges:
        a = math.atan2(ey, ex)
        c, s = math.cos(a), math.sin(a)
        u = hull @ np.array([c, s])
        v = hull @ np.array([-s, c])
        du, dv = float(np.ptp(u)), float(np.ptp(v))
        if du * dv < best[0]:
            best = (du * dv, du, dv, a)
    _, du, dv, a = best
    if dv > du:
        du, dv, a = dv, du, a + math.pi / 2
    yaw = (a + math.pi / 2) % math.pi - math.pi / 2
    return du, dv, yaw


def palm_depth_points(m: mujoco.MjModel, d: mujoco.MjData, palm: int, cam: DepthCamera,
                      rng: np.random.Generator) -> np.ndarray:
    """The camera's measured points (world frame) in the state of ``d``, seen from the centre
    of body ``palm``'s face (its frame's origin), looking along its -z; ``d`` is not changed
    (the rays are cast in a scratch copy of its state)."""
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    state = np.empty(mujoco.mj_stateSize(m, spec))
    mujoco.mj_getState(m, d, state, spec)
    scratch = mujoco.MjData(m)
    mujoco.mj_setState(m, scratch, state, spec)
    mujoco.mj_kinematics(m, scratch)
    if m.nflex:
        mujoco.mj_flex(m, scratch)
    return depth_points(m, scratch, cam, scratch.xpos[palm].copy(), scratch.xmat[palm].reshape(3, 3).copy(), rng)
