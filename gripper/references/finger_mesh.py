"""Tetrahedral mesh of the silicone finger body, built from :class:`FingerGeometry`.

A mapped mesh: each element a structured block of hexahedra whose columns lean with the cut
faces (so the cut faces are exact planes), continuous bridges, a cable channel, every hexahedron
split into linear tetrahedra (``centre24`` by default, against bending lock). Choices and
their checks: ``docs/calibration.md``, "How the finger is meshed".

Example:
    >>> from gripper.core.params import FingerGeometry
    >>> mesh = finger_mesh(FingerGeometry())
    >>> mesh.points.shape[1], mesh.tets.shape[1]
    (3, 4)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from gripper.core.fields import Validated
from gripper.core.params import FingerGeometry
from gripper.drives.cable.geometry import element_kind


@dataclass(frozen=True)
class MeshResolution(Validated):
    """Cell counts of the mapped mesh at ``scale`` = 1 (each count is multiplied by ``scale``).

    Attributes:
        scale: refinement factor applied to every count [-]; 1 default, 2 for convergence.
        along: cells along one element (x), cosine-graded [-]. Default 4: 2.3 mm at the ends
            where the bridges bend (``docs/calibration.md``, "Reference defaults").
        bridge: cells through the bridge thickness [-]. Default 2 (2.25 and 0.75 mm with the
            default ``bridge_grading``): the bridges carry the bending, so they get two cells
            through their thickness.
        below_hole: cells from the bridge top to the channel floor [-]. Default 2.
        channel: cells across the channel's height and width [-]. Default 1.
        above_hole: cells from the channel roof to the grasping face [-]. Default 1.
        side: cells across each side wall of the channel (y) [-]. Default 1.
        uniform: no channel and no cuts (a plain bar of the same size): the beam check.
        symmetric: mesh only the half y >= 0 (see the module docstring). The half channel then
            gets ``channel`` cells across its half width. Default True.
        bridge_grading: largest over smallest cell height in the bridge and in the wall from
            the bridge top to the channel, the smallest at the bridge top [-]; 1 is uniform.
            Default 3 (see the module docstring, "Grading").
        split_bridges: cut each bridge at its middle (the plane between two elements): the
            elements share no nodes and each has an interface face of its own there (paper
            000's flexible multibody model, :mod:`gripper.references.fmbs`). Default False.
        split: tetrahedra per hexahedral cell: ``"centre24"`` (default: 24, around centre and
            face nodes; little locking), ``"centre12"`` (12, centre node only) or ``"kuhn6"``
            (6, no added nodes; locks, see the module docstring).
    """

    scale: int = 1
    along: int = 4
    bridge: int = 2
    below_hole: int = 2
    channel: int = 1
    above_hole: int = 1
    side: int = 1
    uniform: bool = False
    split: str = "centre24"
    symmetric: bool = True
    bridge_grading: float = 3.0
    split_bridges: bool = False

    def validate(self) -> MeshResolution:
        if not (isinstance(self.bridge_grading, int | float) and 1.0 <= self.bridge_grading <= 20.0):
            raise ValueError(f"mesh.bridge_grading: must be a number in [1, 20], "
                             f"got {self.bridge_grading!r}")
        for name in ("uniform", "symmetric", "split_bridges"):
            if not isinstance(getattr(self, name), bool):
                raise ValueError(f"mesh.{name}: must be true or false, got {getattr(self, name)!r}")
        if self.split not in SPLITS:
            raise ValueError(f"mesh.split: must be one of {', '.join(SPLITS)}, got {self.split!r}")
        for name in ("scale", "along", "bridge", "below_hole", "channel", "above_hole", "side"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or not 1 <= v <= 32:
                raise ValueError(f"mesh.{name}: must be an integer in [1, 32], got {v!r}")
        return self


@dataclass(frozen=True)
class FingerMesh:
    """A tetrahedral mesh in the finger frame [m].

    Attributes:
        points: node coordinates, shape (n, 3) [m].
        tets: node indices of each tetrahedron, positively oriented, shape (m, 4).
        nodes_of_element: node indices of each element, shared bridge nodes in both.
        channel_nodes: per element, the nodes on the cable channel's wall.
        anchor_nodes: nodes on the channel's rim at the tip's distal face (where the cable is
            knotted).
        symmetric: only the half y >= 0 is meshed; the plane y = 0 is a symmetry plane.
    """

    points: np.ndarray
    tets: np.ndarray
    nodes_of_element: tuple[np.ndarray, ...]
    channel_nodes: tuple[np.ndarray, ...]
    anchor_nodes: np.ndarray
    symmetric: bool = False

    @cached_property
    def plane_nodes(self) -> np.ndarray:
        """Indices of the nodes on the symmetry plane y = 0 (empty for a full mesh)."""
        if not self.symmetric:
            return np.empty(0, dtype=int)
        return np.flatnonzero(np.abs(self.points[:, 1]) < 1e-12)

    @cached_property
    def node_weight(self) -> np.ndarray:
        """How many nodes of the whole body each node stands for: 2 off the symmetry plane
        (itself and its mirror image), 1 on it; all 1 for a full mesh [-]."""
        w = np.ones(len(self.points))
        if self.symmetric:
            w[:] = 2.0
            w[self.plane_nodes] = 1.0
        return w

    def mirrored(self, idx: np.ndarray, pos: np.ndarray) -> np.ndarray:
        """Positions ``pos`` of nodes ``idx`` with the mirror images of those off the plane
        appended (the whole body's nodes for a symmetric mesh; ``pos`` itself otherwise)."""
        if not self.symmetric:
            return pos
        off = self.node_weight[idx] > 1.0
        return np.vstack([pos, pos[off] * np.array([1.0, -1.0, 1.0])])

    @cached_property
    def element_volume_weights(self) -> tuple[np.ndarray, ...]:
        """Per element, the volume [m³] each of its nodes stands for (a quarter of each of that
        element's tetrahedra, mirror image included), aligned with ``nodes_of_element``.

        Best-fit rotations weigh nodes by it, so an element's angle is the rotation that best
        fits its *volume* (a property of the body), not its node cloud, which the grading crowds
        towards the element ends.
        """
        vol = np.abs(self.tet_volumes())
        owner = np.empty(len(self.tets), dtype=int)
        pos_of = [{int(n): k for k, n in enumerate(nodes)} for nodes in self.nodes_of_element]
        member = [set(d) for d in pos_of]
        for t, tet in enumerate(self.tets):
            ids = [int(n) for n in tet]
            owner[t] = next(e for e, mem in enumerate(member) if all(n in mem for n in ids))
        out = [np.zeros(len(nodes)) for nodes in self.nodes_of_element]
        for t, tet in enumerate(self.tets):
            e = owner[t]
            for n in tet:
                out[e][pos_of[e][int(n)]] += 0.25 * vol[t]
        return tuple(w * self.node_weight[nodes] for w, nodes in zip(out, self.nodes_of_element,
                                                                       strict=True))

    @property
    def n_nodes(self) -> int:
        return len(self.points)

    def tet_volumes(self) -> np.ndarray:
        """Signed volume of each tetrahedron [m³] (positive: positively oriented)."""
        return _signed_volumes(self.points, self.tets)

    def volume(self) -> float:
        """Total volume of the tetrahedra [m³]."""
        return float(_signed_volumes(self.points, self.tets).sum())


def channel_side(g: FingerGeometry) -> float:
    """Side of the square channel with the round hole's area [m]."""
    return 0.5 * g.hole_diameter * math.sqrt(math.pi)


def _levels(breaks: list[float], counts: list[int]) -> np.ndarray:
    out = [breaks[0]]
    for a, b, n in zip(breaks[:-1], breaks[1:], counts, strict=True):
        out += list(np.linspace(a, b, n + 1)[1:])
    return np.asarray(out)


def _graded(n: int, length: float, ratio: float) -> np.ndarray:
    """``n + 1`` levels over ``[0, length]``, cells growing geometrically from the first to
    the last by ``ratio`` (largest over smallest cell)."""
    w = ratio ** (np.arange(n) / max(n - 1, 1)) if n > 1 else np.ones(1)
    return np.concatenate([[0.0], np.cumsum(w / w.sum() * length)])


def _signed_volumes(points: np.ndarray, tets: np.ndarray) -> np.ndarray:
    a, b, c, d = (points[tets[:, i]] for i in range(4))
    return np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a) / 6.0


# Kuhn split of the unit cube into six tetrahedra along the diagonal (0,0,0)-(1,1,1).
_KUHN = [
    [(0, 0, 0), (1, 0, 0), (1, 1, 0), (1, 1, 1)],
    [(0, 0, 0), (1, 0, 0), (1, 0, 1), (1, 1, 1)],
    [(0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 1, 1)],
    [(0, 0, 0), (0, 1, 0), (0, 1, 1), (1, 1, 1)],
    [(0, 0, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1)],
    [(0, 0, 0), (0, 0, 1), (0, 1, 1), (1, 1, 1)],
]


SPLITS = ("kuhn6", "centre12", "centre24")
# The six faces of the unit cube, each as its four corners in cyclic order.
_FACES = [
    [(0, 0, 0), (0, 1, 0), (0, 1, 1), (0, 0, 1)], [(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)],
    [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)], [(0, 1, 0), (1, 1, 0), (1, 1, 1), (0, 1, 1)],
    [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)],
]


def finger_mesh(g: FingerGeometry, res: MeshResolution | None = None) -> FingerMesh:
    """Mesh the finger body of geometry ``g`` (see the module docstring).

    Raises:
        ValueError: invalid geometry or resolution.
    """
    g.validate()
    res = (res or MeshResolution()).validate()
    a = channel_side(g)
    zc0, zc1 = g.hole_height - 0.5 * a, g.hole_height + 0.5 * a
    if zc0 <= g.bridge_thickness or zc1 >= g.height:
        raise ValueError("finger.hole_height: the cable channel must clear the bridge and the "
                         "grasping face")
    builder = _MeshBuilder(g, res, _z_levels(g, res, zc0, zc1), _y_levels(g, res, a))
    nodes_of_element: list[set[int]] = []
    channel_nodes: list[set[int]] = []
    for e in range(g.n_segments):
        elem_nodes, chan = builder.add_element(e)
        nodes_of_element.append(elem_nodes)
        channel_nodes.append(chan)
    pts, tet_arr, remap = _used_and_oriented(np.asarray(builder.points),
                                             np.asarray(builder.tets, dtype=int))

    def mapped(nodes: set[int]) -> np.ndarray:
        return np.array(sorted(int(remap[n]) for n in nodes if remap[n] >= 0), dtype=int)

    chan_idx = tuple(mapped(c) for c in channel_nodes)
    if res.uniform:
        # The beam check has no channel: the cable forces go to the nodes nearest the hole axis.
        chan_idx = tuple(_nearest_line_nodes(pts, mapped(n), g.hole_height)
                         for n in nodes_of_element)
    return FingerMesh(points=pts, tets=tet_arr,
                      nodes_of_element=tuple(mapped(n) for n in nodes_of_element),
                      channel_nodes=chan_idx, anchor_nodes=_anchor_nodes(g, res, pts, chan_idx[-1]),
                      symmetric=res.symmetric)


def _z_levels(g: FingerGeometry, res: MeshResolution, zc0: float, zc1: float) -> np.ndarray:
    """Node levels through the height [m]: bridge, wall below the channel (both graded towards
    the bridge top by ``res.bridge_grading``), channel and wall above it."""
    s = res.scale
    z_lv = _levels([0.0, g.bridge_thickness, zc0, zc1, g.height],
                   [res.bridge * s, res.below_hole * s, res.channel * s, res.above_hole * s])
    if res.bridge_grading != 1.0 and not res.uniform:
        nb, nh = res.bridge * s, res.below_hole * s
        tb = g.bridge_thickness
        below = tb - _graded(nb, tb, res.bridge_grading)[::-1]  # finest at the bridge top
        above = tb + _graded(nh, zc0 - tb, res.bridge_grading)  # finest at the bridge top
        z_lv = np.concatenate([below, above[1:], z_lv[nb + nh + 1:]])
    return z_lv


def _y_levels(g: FingerGeometry, res: MeshResolution, a: float) -> np.ndarray:
    """Node levels across the width [m] (the half y >= 0 of a symmetric mesh): side walls and
    the channel of side ``a``."""
    s = res.scale
    if res.symmetric:
        return _levels([0.0, 0.5 * a, 0.5 * g.width], [res.channel * s, res.side * s])
    return _levels([-0.5 * g.width, -0.5 * a, 0.5 * a, 0.5 * g.width],
                   [res.side * s, res.channel * s, res.side * s])


class _MeshBuilder:
    """Nodes and tetrahedra of the mapped mesh as its elements are added, each node made once
    under its key (bridge nodes shared between neighbouring elements, centre nodes by their
    corners)."""

    def __init__(self, g: FingerGeometry, res: MeshResolution, z_lv: np.ndarray,
                 y_lv: np.ndarray):
        self.g, self.res, self.z_lv, self.y_lv = g, res, z_lv, y_lv
        self.a = channel_side(g)
        self.zc0, self.zc1 = g.hole_height - 0.5 * self.a, g.hole_height + 0.5 * self.a
        self.nx = res.along * res.scale
        self.u = 0.5 * (1.0 - np.cos(np.pi * np.arange(self.nx + 1) / self.nx))  # cosine grading in [0, 1]
        self.tan_half = math.tan(0.5 * math.radians(g.cut_angle_deg))
        self.iz_bridge = res.bridge * res.scale  # level index of the bridge top
        self.key_to_id: dict[tuple, int] = {}
        self.points: list[tuple[float, float, float]] = []
        self.tets: list[list[int]] = []

    def in_channel(self, jy: int, kz: int) -> bool:
        """Whether cell (jy, kz) of the cross-section is inside the channel."""
        yc = 0.5 * (self.y_lv[jy] + self.y_lv[jy + 1])
        zc = 0.5 * (self.z_lv[kz] + self.z_lv[kz + 1])
        return abs(yc) < 0.5 * self.a and self.zc0 < zc < self.zc1

    def add_element(self, e: int) -> tuple[set[int], set[int]]:
        """Mesh element ``e``: its nodes and those of them on the channel's wall."""
        ids = self._element_grid(e)
        elem_nodes: set[int] = set()
        chan: set[int] = set()
        for i in range(self.nx):
            for j in range(len(self.y_lv) - 1):
                for k in range(len(self.z_lv) - 1):
                    cell = ids[i:i + 2, j:j + 2, k:k + 2]
                    if not self.res.uniform and self.in_channel(j, k):
                        chan.update(cell.ravel().tolist())
                        continue
                    self._split_cell(cell, elem_nodes)
                    elem_nodes.update(cell.ravel().tolist())
        return elem_nodes, chan & elem_nodes

    def _element_grid(self, e: int) -> np.ndarray:
        """Node ids of element ``e``'s structured grid, shape (nx + 1, ny, nz): columns leaning
        with the cut faces, so that the cut faces are exact planes."""
        g, res = self.g, self.res
        kind = element_kind(e, g.n_segments)
        cut_prox = kind in ("middle", "tip") and not res.uniform
        cut_dist = kind in ("middle", "base") and not res.uniform
        x0 = e * g.pitch
        ids = np.empty((self.nx + 1, len(self.y_lv), len(self.z_lv)), dtype=int)
        for k, z in enumerate(self.z_lv):
            d = max(0.0, z - g.bridge_thickness) * self.tan_half
            lo = x0 + (d if cut_prox else 0.0)
            hi = x0 + g.pitch - (d if cut_dist else 0.0)
            for i in range(self.nx + 1):
                x = lo + (hi - lo) * self.u[i]
                for j, y in enumerate(self.y_lv):
                    # Nodes are shared between elements only on the bridge (k <= iz_bridge) at
                    # the common boundary; elsewhere the cut separates them.
                    shared = ((i == 0 and e > 0) and (k <= self.iz_bridge or res.uniform)
                              and not res.split_bridges)
                    key = (e - 1, self.nx, j, k) if shared else (e, i, j, k)
                    if key not in self.key_to_id:
                        self.key_to_id[key] = len(self.points)
                        self.points.append((x, y, z))
                    ids[i, j, k] = self.key_to_id[key]
        return ids

    def _centre_node(self, corners: tuple[int, ...], owner: set[int]) -> int:
        """The node at the centre of ``corners`` (a face or a cell), made once; added to
        ``owner``."""
        key = ("centre", corners)
        if key not in self.key_to_id:
            self.key_to_id[key] = len(self.points)
            self.points.append(tuple(np.mean([self.points[c] for c in corners], axis=0)))
        owner.add(self.key_to_id[key])
        return self.key_to_id[key]

    def _split_cell(self, corner: np.ndarray, owner: set[int]) -> None:
        """Tetrahedra of the hexahedral cell whose node ids are ``corner`` (2 x 2 x 2), split
        as ``res.split`` says; added nodes go to ``owner``."""
        if self.res.split == "kuhn6":
            for tet in _KUHN:
                self.tets.append([int(corner[di, dj, dk]) for di, dj, dk in tet])
            return
        centre = self._centre_node(tuple(sorted(corner.ravel().tolist())), owner)
        for face in _FACES:
            f = [int(corner[c]) for c in face]
            if self.res.split == "centre24":
                fc = self._centre_node(tuple(sorted(f)), owner)
                for q in range(4):
                    self.tets.append([f[q], f[(q + 1) % 4], fc, centre])
            else:  # the diagonal from the face's lowest node id: conforming
                q = int(np.argmin(f))
                a, b, c, d = (f[(q + r) % 4] for r in range(4))
                self.tets.append([a, b, c, centre])
                self.tets.append([a, c, d, centre])


def _used_and_oriented(pts: np.ndarray, tet_arr: np.ndarray
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Points and tetrahedra without the nodes no tetrahedron uses, every tetrahedron positively
    oriented, and the map from old node index to new (-1: dropped).

    Raises:
        ValueError: degenerate tetrahedra.
    """
    # Drop nodes no tetrahedron uses (the channel's inside has none: its wall nodes are used).
    used = np.unique(tet_arr)
    remap = -np.ones(len(pts), dtype=int)
    remap[used] = np.arange(len(used))
    pts = pts[used]
    tet_arr = remap[tet_arr]
    vol = _signed_volumes(pts, tet_arr)
    neg = vol < 0
    tet_arr[neg] = tet_arr[neg][:, [0, 2, 1, 3]]
    if np.any(np.abs(vol) < 1e-15):
        raise ValueError("mesh: degenerate tetrahedra; the resolution is too fine for this "
                         "geometry")
    return pts, tet_arr, remap


def _anchor_nodes(g: FingerGeometry, res: MeshResolution, pts: np.ndarray,
                  tip_channel: np.ndarray) -> np.ndarray:
    """Nodes where the cable is knotted: the channel's rim on the tip's distal face (for the
    channel-less beam check, the face's nodes nearest the hole axis)."""
    tip_face = np.isclose(pts[:, 0], g.length)
    if res.uniform:
        return np.flatnonzero(tip_face & (np.abs(pts[:, 2] - g.hole_height)
                                          <= np.abs(pts[tip_face, 2] - g.hole_height).min()
                                          + 1e-12))
    return np.flatnonzero(tip_face & np.isin(np.arange(len(pts)), tip_channel))


def _nearest_line_nodes(pts: np.ndarray, nodes: np.ndarray, z: float) -> np.ndarray:
    dz = np.abs(pts[nodes, 2] - z)
    return nodes[dz <= dz.min() + 1e-12]
