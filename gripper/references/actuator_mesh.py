"""The hexahedral mesh of paper 001's actuator (:mod:`gripper.references.pneumatic_params`): half
the cross-section (the actuator is symmetric about its mid-plane x = 0) in structured quads,
swept along the length into eight-node hexahedra (and, for the solver, twenty-node ones:
:meth:`ActuatorMesh.quadratic`), with each cell's material and each fibre cell's winding
direction.

The cross-section (x across, y up from the neutral layer's mid-plane, z along the length from
the clamped end; half-rounds centred at y_c = t_n/2 + t):

- the air duct, a half-disc of radius a above y_c whose two edges are rounded (``DUCT_FILLET``;
  an O-grid: a square core and two wedges);
- the main body around it: a half-ring a ≤ r ≤ a + t above y_c and a rectangle of the body's
  width and thickness t below;
- the neutral layer, thickness t_n, under the body, as wide as the body;
- the fibre layer, thickness d (the fibre's diameter), wound around body and neutral layer;
- the cladding, thickness t_c, around everything.

The duct is open over the length except for a sealing cap at each end (paper 001 §2.1: "sealed
at both ends"; the cap's thickness, ``CAP_THICKNESS``, is assumed, with its reason).
The fibre layer's and neutral layer's materials are in :mod:`gripper.references.fibre_materials`.

Example:
    >>> from gripper.references.actuator_mesh import MeshSize, actuator_mesh
    >>> from gripper.references.pneumatic_params import PneumaticActuator
    >>> m = actuator_mesh(PneumaticActuator(), MeshSize())
    >>> m.points.shape[1], m.cells.shape[1]
    (3, 8)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from gripper.core.fields import Validated, param
from gripper.references.pneumatic_params import PneumaticActuator

SILICONE, FIBRE, NEUTRAL = 0, 1, 2  # cell materials (the fibre and neutral cells are silicone too)
# the twenty-node hexahedron's edges, in VTK's order of its mid-edge nodes
HEX20_EDGES = np.array([(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
                        (0, 4), (1, 5), (2, 6), (3, 7)])
MERGE_DECIMALS = 10
# m, the silicone that seals each end of the duct. Assumed: the paper (§2.1) says only "sealed at
# both ends". A cap as thick as the 2 mm wall balloons like a membrane (its limit point ~100 kPa,
# p ≈ 1.24 μ t / a for a neo-Hookean bubble; measured: this model stalled at 127 kPa with it), which
# the built actuator, tested to 410 kPa (paper 001 Fig. 20), cannot have done; 5 mm is a moulded
# plug's usual size (Polygerinos et al. 2015's end caps).
CAP_THICKNESS = 0.005
# m, radius of the duct's rounded edges where its arc meets its flat side. Assumed: the paper's
# cross-section drawing is lost; a sharp 90° corner of the cavity is a re-entrant corner of the
# silicone, where the strain is singular under pressure and no mesh converges (measured: the
# finer the mesh, the lower the pressure at which Newton's method failed). A moulded duct's core
# has rounded edges; 1 mm is half the wall.
DUCT_FILLET = 0.001  # points closer than 1e-10 m are one point (the blocks share their edges exactly)


@dataclass(frozen=True)
class MeshSize(Validated):
    """The mesh's resolution: cells along each part of the cross-section and the cells' length.
    Defaults: the mesh the design studies use, level 1 of :meth:`at_refinement` (its
    convergence: ``docs/pneumatic.md``)."""

    SECTION = "mesh"

    duct_cells: int = param(2, "-", ge=1, le=16, integer=True,
                            source="cells along each half of the duct's quarter arc, and as many round the fillet")
    wall_cells: int = param(1, "-", ge=1, le=16, integer=True, source="cells through the main body's wall")
    layer_cells: int = param(1, "-", ge=1, le=8, integer=True,
                             source="cells through each thin layer (neutral, fibre, cladding): one quadratic "
                                    "cell carries a quadratic field through 0.1-2.5 mm")
    axial_length: float = param(0.01, "m", gt=0, le=0.01,
                                source="largest cell length along the actuator. At most 10 mm: a longer quadratic "
                                       "cell spans 10-20° of the bend in a layer that cannot stretch, and its error "
                                       "then dominates and changes sign against the cross-section's (measured: "
                                       "40/20/13 mm cells gave an observed order of 0.24 at 250 kPa)")

    @classmethod
    def at_refinement(cls, level: int) -> MeshSize:
        """The convergence study's family, ``level`` 1 to 3 (1: the studies' mesh): cells along
        each half of the duct's arc (as many round the fillet), through the wall, and along the
        length (at most 10 mm long), each level finer in all three:

        ====== ========== ========== ===========
        level  duct cells wall cells cell length
        ====== ========== ========== ===========
        1      2          1          10 mm
        2      3          2          6.7 mm
        3      4          2          5 mm
        ====== ========== ========== ===========

        One cell through each thin layer throughout (refining through them moved the bend at
        250 kPa by 0-3 %: ``docs/pneumatic.md``). The levels are not geometrically similar, so the
        convergence study measures each by its representative cell size (volume / cells)^(1/3),
        as Celik et al. (2008) do. One duct cell per half-arc is not in the asymptotic range (a
        45° quadratic cell in the inextensible winding: 30 % stiffer at 25 kPa than two or three,
        which agree to 0.2 %)."""
        if level not in MESH_FAMILY:
            raise ValueError(f"mesh level: one of {sorted(MESH_FAMILY)}, got {level}")
        return cls(*MESH_FAMILY[level]).validate()


# the family of MeshSize.at_refinement: (duct cells, wall cells, layer cells, cell length [m])
MESH_FAMILY = {1: (2, 1, 1, 0.01), 2: (3, 2, 1, 0.02 / 3), 3: (4, 2, 1, 0.005)}


@dataclass(frozen=True)
class ActuatorMesh:
    """The swept mesh: ``points`` (n, 3) [m], ``cells`` (m, 8) hexahedra in VTK order, each cell's
    ``material`` (SILICONE, FIBRE, NEUTRAL), and the same as twenty-node cells (``quad_points``,
    ``quad_cells``). The winding's direction in the fibre cells is :func:`winding_tangent`'s, taken
    at each quadrature point by the model."""

    points: np.ndarray
    cells: np.ndarray
    material: np.ndarray
    actuator: PneumaticActuator
    size: MeshSize
    quad_points: np.ndarray
    quad_cells: np.ndarray

    @cached_property
    def centroids(self) -> np.ndarray:
        return self.points[self.cells].mean(axis=1)

    def duct_surface_points(self, points: np.ndarray | None = None) -> np.ndarray:
        """Mask of the points (default: the mesh's) on the duct's wall, flat side and caps (where
        the pressure acts)."""
        geo = Geometry(self.actuator)
        x, y, z = (self.points if points is None else points).T
        tol = 1e-9
        # no points lie inside the open duct: every point of its closure is on its surface (the
        # mid-edge nodes of the fillet's chords lie just inside it)
        r = np.hypot(x, y - geo.y_centre)
        in_closure = (r <= geo.duct_radius_at(np.arctan2(y - geo.y_centre, x)) + tol) & (y >= geo.y_centre - tol)
        return in_closure & (z >= geo.cap - tol) & (z <= self.actuator.length - geo.cap + tol)

    def quadratic(self) -> tuple[np.ndarray, np.ndarray]:
        """The mesh as twenty-node hexahedra (VTK order): points (n', 3), the eight-node mesh's
        ``points`` first, then the mid-edge nodes (each on its arc where the cell's edge is round:
        the duct's wall and fillets, the body's, fibre's and cladding's round faces), and cells
        (m, 20)."""
        return self.quad_points, self.quad_cells

    def tip_line(self) -> tuple[int, int]:
        """The points at the free end's bottom and top on the mid-plane (x = 0): the material line
        whose rotation is the bending angle."""
        x, y, z = self.points.T
        at_tip = np.flatnonzero(np.isclose(z, self.actuator.length) & np.isclose(x, 0.0))
        return int(at_tip[np.argmin(y[at_tip])]), int(at_tip[np.argmax(y[at_tip])])


@dataclass(frozen=True)
class Geometry:
    """The cross-section's levels [m] (see the module docstring)."""

    actuator: PneumaticActuator

    @property
    def a(self) -> float:
        return self.actuator.duct_radius

    @property
    def r_body(self) -> float:
        return self.actuator.outer_radius

    @property
    def r_fibre(self) -> float:
        return self.r_body + self.actuator.fibre_diameter

    @property
    def r_out(self) -> float:
        return self.r_fibre + self.actuator.cladding_thickness

    @property
    def y_neutral_bottom(self) -> float:
        return -0.5 * self.actuator.neutral_thickness

    @property
    def y_neutral_top(self) -> float:
        return 0.5 * self.actuator.neutral_thickness

    @property
    def y_centre(self) -> float:
        return self.y_neutral_top + self.actuator.main_body_thickness

    @property
    def y_fibre_bottom(self) -> float:
        return self.y_neutral_bottom - self.actuator.fibre_diameter

    @property
    def y_bottom(self) -> float:
        return self.y_fibre_bottom - self.actuator.cladding_thickness

    @property
    def cap(self) -> float:
        """Thickness of the silicone sealing each end of the duct [m] (``CAP_THICKNESS``)."""
        return CAP_THICKNESS

    @property
    def fillet(self) -> float:
        """Radius of the duct's two rounded edges, where its arc meets its flat side [m]."""
        return min(DUCT_FILLET, 0.5 * self.a)

    @property
    def fillet_angle(self) -> float:
        """The direction from the half-rounds' centre [rad, from the flat side] where the fillet
        meets the duct's arc."""
        a, f = self.a, self.fillet
        return math.atan2(f, math.sqrt((a - f) ** 2 - f * f))

    def fillet_directions(self, t: np.ndarray) -> np.ndarray:
        """Directions from the half-rounds' centre [rad] of the points a fraction ``t`` of the way
        round the fillet's arc, from where it leaves the flat side (t = 0) to where it meets the
        duct's arc (t = 1)."""
        a, f = self.a, self.fillet
        cx = math.sqrt((a - f) ** 2 - f * f)
        psi = -0.5 * np.pi + np.asarray(t, dtype=float) * (self.fillet_angle + 0.5 * np.pi)
        return np.arctan2(f + f * np.sin(psi), cx + f * np.cos(psi))

    def duct_radius_at(self, theta: np.ndarray) -> np.ndarray:
        """The duct wall's distance [m] from the half-rounds' centre along the direction θ from
        the flat side (+x): a on the arc, less on the fillet (where the ray leaves the fillet's
        circle, centred at (√((a-f)² - f²), f) with radius f: the circle lies inside the duct)."""
        a, f = self.a, self.fillet
        cx, cy = math.sqrt((a - f) ** 2 - f * f), f
        theta = np.asarray(theta, dtype=float)
        e_c = np.cos(theta) * cx + np.sin(theta) * cy
        t = e_c + np.sqrt(np.maximum(e_c ** 2 - (cx * cx + cy * cy) + f * f, 0.0))
        return np.where(theta < self.fillet_angle, t, a)


def _graded(lo: float, hi: float, n: int) -> np.ndarray:
    return np.linspace(lo, hi, n + 1)


def _levels(breaks: list[tuple[float, int]], start: float) -> np.ndarray:
    """Node positions from ``start`` through each (end, cells) interval; empty intervals skipped."""
    out = [np.array([start])]
    lo = start
    for hi, n in breaks:
        if hi - lo > 1e-12:
            out.append(_graded(lo, hi, n)[1:])
            lo = hi
    return np.concatenate(out)


def _grid_quads(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The quadratic quads of a structured point grid sampled at twice the cells' resolution,
    (2 ni + 1, 2 nj + 1, 2): the corners are the even-indexed points, the mid-edge nodes the
    points between them (each on the block's own map: on its arc where the block's edge is
    round). Returns the points flattened and cells (k, 8): four corners, then the mid-edge nodes
    of edges 0-1, 1-2, 2-3, 3-0."""
    mi, mj = points.shape[:2]
    idx = np.arange(mi * mj).reshape(mi, mj)
    grid_i, grid_j = np.meshgrid(np.arange(0, mi - 1, 2), np.arange(0, mj - 1, 2), indexing="ij")
    i, j = grid_i.ravel(), grid_j.ravel()
    cells = np.stack([idx[i, j], idx[i + 2, j], idx[i + 2, j + 2], idx[i, j + 2],
                      idx[i + 1, j], idx[i + 2, j + 1], idx[i + 1, j + 2], idx[i, j + 1]], axis=-1)
    return points.reshape(-1, 2), cells


def _halves(levels: np.ndarray) -> np.ndarray:
    """Node positions with the midpoint of every interval put between them (2 n + 1 values)."""
    out = np.empty(2 * len(levels) - 1)
    out[0::2] = levels
    out[1::2] = 0.5 * (levels[:-1] + levels[1:])
    return out


def cross_section(actuator: PneumaticActuator, size: MeshSize) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The half cross-section (x ≥ 0) as eight-node quads: points (n, 2), counter-clockwise cells
    (m, 8) (corners, then mid-edge nodes) and which cells fill the duct (the O-grid's three
    blocks). Every block is sampled from its own map at twice its resolution, so the mid-edge
    nodes of the duct's wall (fillets included) and of every ring lie on their arcs."""
    g = Geometry(actuator)
    a, yc, nq = g.a, g.y_centre, size.duct_cells
    n_duct = max(1, nq // 2)  # cells from the O-grid's core to the duct's wall
    s = 0.5 * a  # the core square's side
    lam = _halves(np.linspace(0.0, 1.0, n_duct + 1))[None, :, None]
    u = _halves(np.linspace(0.0, 1.0, nq + 1))
    # below 45° the wall is the fillet, in cells of its own spaced evenly round its centre, then
    # the arc: no cell's edge bends round the kink in the wall's curvature, and the fillet (which
    # turns through 90° + its angle within a few degrees seen from the duct's centre) is refined
    # with the rest
    theta_wall = np.r_[g.fillet_directions(np.linspace(0.0, 1.0, 2 * nq + 1)),
                       np.linspace(g.fillet_angle, 0.25 * np.pi, 2 * nq + 1)[1:]]
    v = _halves(theta_wall[0::2] / (0.25 * np.pi))
    blocks = [np.stack(np.meshgrid(s * u, s * v, indexing="ij"), axis=-1)]
    # the two wedges, below and above 45°: from the core's side out to the duct's wall, a
    # transfinite blend whose outer edge is the wall itself
    for theta, inner in ((theta_wall, np.stack([np.full_like(v, s), s * v], axis=-1)),
                         (0.5 * np.pi - 0.25 * np.pi * u, np.stack([s * u, np.full_like(u, s)], axis=-1))):
        outer = g.duct_radius_at(theta)[:, None] * np.stack([np.cos(theta), np.sin(theta)], axis=-1)
        blocks.append(inner[:, None, :] + lam * (outer - inner)[:, None, :])
    # the half-ring above y_c, a polar map: the body's wall from the duct's wall out to the body's
    # round face (a blend in radius), then the fibre layer and the cladding (circles)
    theta = np.r_[theta_wall, 0.5 * np.pi - 0.25 * np.pi * u[::-1][1:]]
    r_duct = g.duct_radius_at(theta)[:, None]
    wall = _halves(np.linspace(0.0, 1.0, size.wall_cells + 1))[None, :]
    outer_radii = _halves(_levels([(g.r_fibre, size.layer_cells), (g.r_out, size.layer_cells)], g.r_body))[1:]
    radii = np.hstack([r_duct + wall * (g.r_body - r_duct),
                       np.broadcast_to(outer_radii, (len(theta), len(outer_radii)))])
    blocks.append(np.stack([radii * np.cos(theta)[:, None], radii * np.sin(theta)[:, None]], axis=-1))
    # below y_c: a tensor grid whose x nodes continue the core's, the wedge's flat side and the
    # ring's radii (straight cells: their mid-edge nodes at the middle)
    x_flat = float(g.duct_radius_at(np.zeros(1))[0])  # where the flat side meets the fillet
    xs = np.concatenate([s * np.linspace(0.0, 1.0, nq + 1), np.linspace(s, x_flat, n_duct + 1)[1:],
                         radii[0, 2::2]])
    ys = _levels([(g.y_fibre_bottom, size.layer_cells), (g.y_neutral_bottom, size.layer_cells),
                  (g.y_neutral_top, size.layer_cells), (yc, size.wall_cells)], g.y_bottom) - yc
    blocks.append(np.stack(np.meshgrid(_halves(xs), _halves(ys), indexing="ij"), axis=-1))
    pts, block_cells, duct, offset = [], [], [], 0
    for k, b in enumerate(blocks):
        p, c = _grid_quads(b)
        pts.append(p)
        block_cells.append(c + offset)
        duct.append(np.full(len(c), k < 3))  # the core and the two wedges
        offset += len(p)
    points = np.concatenate(pts) + np.array([0.0, yc])
    keys = np.round(points, MERGE_DECIMALS)
    _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    cells = inverse.reshape(-1)[np.concatenate(block_cells)]
    used = np.unique(cells)  # the blocks' face centres (odd, odd) belong to no cell
    renumber = np.full(len(first), -1)
    renumber[used] = np.arange(len(used))
    points, cells = points[first][used], renumber[cells]
    # orient every quad counter-clockwise (its corners' signed area positive)
    p = points[cells[:, :4]]
    area = 0.5 * np.sum(p[:, :, 0] * np.roll(p[:, :, 1], -1, 1) - np.roll(p[:, :, 0], -1, 1) * p[:, :, 1], axis=1)
    flip = area < 0
    cells[flip] = cells[flip][:, [0, 3, 2, 1, 7, 6, 5, 4]]
    return points, cells, np.concatenate(duct)


def axial_levels(actuator: PneumaticActuator, size: MeshSize) -> np.ndarray:
    """Node positions along the length [m]: every cap and neutral-segment end is a node, and no
    cell is longer than ``size.axial_length``."""
    g = Geometry(actuator)
    ends = np.cumsum(np.ravel(list(zip(actuator.segment_lengths, (*actuator.segment_gaps, 0.0), strict=True))))
    breaks = np.unique(np.round(np.r_[0.0, g.cap, ends[ends < actuator.length], actuator.length - g.cap,
                                      actuator.length], 12))
    return _levels([(hi, max(1, math.ceil((hi - lo) / size.axial_length - 1e-9)))
                    for lo, hi in zip(breaks[:-1], breaks[1:], strict=True)], 0.0)


def in_neutral_segment(actuator: PneumaticActuator, z: np.ndarray) -> np.ndarray:
    """Whether each position z [m] along the length lies on one of the neutral layer's segments."""
    inside = np.zeros_like(z, dtype=bool)
    start = 0.0
    for length, gap in zip(actuator.segment_lengths, (*actuator.segment_gaps, 0.0), strict=True):
        inside |= (z >= start) & (z <= start + length)
        start += length + gap
    return inside


def winding_tangent(g: Geometry, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The unit tangent (x, y) of the winding's path around the cross-section at points (x, y)
    [m] of the fibre layer (strictly inside its cells): round over the top, down the side,
    round the corner beside the neutral layer, across the bottom. Shape (n, 2)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    out = np.zeros((len(x), 2))
    above = y > g.y_centre
    theta = np.arctan2(y - g.y_centre, x)
    out[above] = np.column_stack([-np.sin(theta[above]), np.cos(theta[above])])
    side = ~above & (x > g.r_body) & (y > g.y_neutral_bottom)
    out[side, 1] = 1.0
    bottom = ~above & (x < g.r_body) & (y < g.y_neutral_bottom)
    out[bottom, 0] = 1.0
    corner = ~above & (x > g.r_body) & (y < g.y_neutral_bottom)
    dx, dy = x[corner] - g.r_body, y[corner] - g.y_neutral_bottom
    norm = np.hypot(dx, dy) + 1e-300
    out[corner] = np.column_stack([-dy / norm, dx / norm])
    return out


def actuator_mesh(actuator: PneumaticActuator, size: MeshSize) -> ActuatorMesh:
    """The actuator's hexahedral mesh (see the module docstring)."""
    actuator, size = actuator.validate(), size.validate()
    g = Geometry(actuator)
    pts2, quads, duct_quads = cross_section(actuator, size)
    zs = _halves(axial_levels(actuator, size))  # the cells' ends and their mid-edge nodes' levels
    n2, nz = len(pts2), len(zs)
    points = np.column_stack([np.tile(pts2, (nz, 1)), np.repeat(zs, n2)])
    lo = np.arange(0, nz - 1, 2)[:, None, None] * n2  # each cell's lower level
    corners, mids = quads[None, :, :4], quads[None, :, 4:]
    cells = np.concatenate([corners + lo, corners + lo + 2 * n2, mids + lo, mids + lo + 2 * n2, corners + lo + n2],
                           axis=2).reshape(-1, 20)
    centre = points[cells[:, :8]].mean(axis=1)
    x, y, z = centre.T
    in_duct = np.tile(duct_quads, (nz - 1) // 2) & (z > g.cap) & (z < actuator.length - g.cap)
    keep = ~in_duct
    cells, x, y, z = cells[keep], x[keep], y[keep], z[keep]
    # the corner nodes first (the eight-node mesh's points), then the mid-edge nodes
    corner_nodes = np.unique(cells[:, :8])
    mid_nodes = np.setdiff1d(np.unique(cells[:, 8:]), corner_nodes)
    order = np.concatenate([corner_nodes, mid_nodes])
    renumber = np.full(len(points), -1)
    renumber[order] = np.arange(len(order))
    quad_points, quad_cells = points[order], renumber[cells]
    points, cells = quad_points[:len(corner_nodes)], quad_cells[:, :8]
    above = y > g.y_centre
    r = np.hypot(x, y - g.y_centre)
    fibre = np.where(above, (r > g.r_body) & (r < g.r_fibre),
                     (y > g.y_fibre_bottom) & (x < g.r_fibre) & ((x > g.r_body) | (y < g.y_neutral_bottom)))
    neutral = (y > g.y_neutral_bottom) & (y < g.y_neutral_top) & (x < g.r_body) & in_neutral_segment(actuator, z)
    material = np.full(len(cells), SILICONE)
    material[fibre] = FIBRE
    material[neutral] = NEUTRAL
    return ActuatorMesh(points=points, cells=cells, material=material, actuator=actuator, size=size,
                        quad_points=quad_points, quad_cells=quad_cells)
