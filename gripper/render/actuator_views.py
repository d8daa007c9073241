"""Pictures and a video of paper 001's actuator inflating: the finite-element model's deformed
surface (:mod:`gripper.references.actuator_fe`, both halves: the model's mirror image across its
plane of symmetry added), drawn with matplotlib, offscreen.

Example:
    >>> from gripper.render.actuator_views import inflation_pictures  # doctest: +SKIP
"""

from __future__ import annotations

from functools import partial
from pathlib import Path
from typing import Any

import numpy as np

from gripper.core.atomic import write_atomic
from gripper.render.video import write_video

# the hexahedron's six faces (VTK corner order), each counter-clockwise seen from outside
HEX_FACES = np.array([(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)])


def boundary_faces(cells: np.ndarray) -> np.ndarray:
    """The faces (k, 4) of eight-node hexahedra that belong to one cell only: the surface."""
    faces = cells[:, HEX_FACES].reshape(-1, 4)
    key = np.sort(faces, axis=1)
    _, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    return faces[counts[inverse.reshape(-1)] == 1]


def _surface(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Quads (k, 4, 3) of both halves' outer surface, symmetry plane excluded."""
    faces = boundary_faces(cells)
    on_plane = np.all(np.isclose(points[faces][:, :, 0], 0.0, atol=1e-9), axis=1)
    quads = points[faces[~on_plane]]
    mirror = quads * np.array([-1.0, 1.0, 1.0])
    return np.concatenate([quads, mirror])


def draw(points: np.ndarray, cells: np.ndarray, title: str, ax: Any, limits: np.ndarray) -> None:
    """One view of the deformed actuator on a 3D axis: its length across, the clamped end on the
    right, the neutral layer below (it bends downwards, towards the layer)."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # type: ignore[import-untyped]

    quads = _surface(points, cells)[:, :, [0, 2, 1]] * np.array([1.0, -1.0, 1.0]) * 1e3  # mm: (x, -z, y)
    normal = np.cross(quads[:, 1] - quads[:, 0], quads[:, 3] - quads[:, 0])
    shade = 0.45 + 0.5 * np.abs(normal[:, 1]) / (np.linalg.norm(normal, axis=1) + 1e-30)
    colours = np.column_stack([0.9 * shade, 0.55 * shade, 0.35 * shade, np.ones_like(shade)])
    ax.add_collection3d(Poly3DCollection(quads, facecolors=colours, edgecolors=(0, 0, 0, 0.15), linewidths=0.2))
    ax.set_xlim(*limits[0])
    ax.set_ylim(*limits[1])
    ax.set_zlim(*limits[2])
    ax.set_box_aspect(np.ptp(limits, axis=1))
    ax.view_init(elev=8, azim=-60)
    ax.set_axis_off()
    ax.set_title(title, fontsize=9)


def _limits(shapes: list[np.ndarray]) -> np.ndarray:
    pts = np.concatenate(shapes)[:, [0, 2, 1]] * np.array([1.0, -1.0, 1.0]) * 1e3
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    lo[0], hi[0] = -np.abs(pts[:, 0]).max(), np.abs(pts[:, 0]).max()
    pad = 0.05 * (hi - lo).max()
    return np.column_stack([lo - pad, hi + pad])


def inflation_pictures(pressures: np.ndarray, shapes: list[np.ndarray], cells: np.ndarray, out: Path,
                       *, picks: int = 4) -> Path:
    """One PNG: the actuator at ``picks`` pressures of a sweep, side by side."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    idx = np.unique(np.linspace(0, len(shapes) - 1, picks).round().astype(int))
    limits = _limits([shapes[i] for i in idx])
    fig = plt.figure(figsize=(3.2 * len(idx), 4.2))
    for k, i in enumerate(idx):
        ax = fig.add_subplot(1, len(idx), k + 1, projection="3d")
        draw(shapes[i], cells, f"{pressures[i] / 1e3:.0f} kPa", ax, limits)
    fig.tight_layout()
    write_atomic(out, partial(_save, fig))
    plt.close(fig)
    return out


def inflation_video(pressures: np.ndarray, shapes: list[np.ndarray], cells: np.ndarray, out: Path,
                    *, fps: float = 8.0, size: tuple[int, int] = (480, 480)) -> Path:
    """An MP4 (or GIF) of the sweep, one frame per recorded pressure."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    limits = _limits(shapes)
    frames = []
    for p, pts in zip(pressures, shapes, strict=True):
        fig = plt.figure(figsize=(size[0] / 100, size[1] / 100), dpi=100)
        ax = fig.add_subplot(projection="3d")
        draw(pts, cells, f"{p / 1e3:.0f} kPa", ax, limits)
        fig.canvas.draw()
        frames.append(np.asarray(fig.canvas.buffer_rgba())[:, :, :3].copy())  # type: ignore[attr-defined]
        plt.close(fig)
    write_video(np.stack(frames), out, fps)
    return out


def _save(fig: Any, tmp: str) -> None:
    fig.savefig(tmp, dpi=110, format="png")
