"""Paper 000's own flexible multibody model of the finger, as a second reference kind.

Paper 000 (§III-IV) divides the actuator into six flexible elements joined at the bridges by
hinges carrying Table 2's torsion springs, bent by the cable's equivalent forces. Here each
element is a MuJoCo flex of the paper's silicone and the hinges carry Table 2's spring, read per
degree (as printed) or per radian. How it is built: ``docs/calibration.md``, "Paper 000's
flexible multibody model".

Example:
    >>> from gripper.references.fmbs import FmbsConfig, run_fmbs
    >>> rec = run_fmbs(fmbs=FmbsConfig(reading="per_radian"))   # doctest: +SKIP
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace

import mujoco
import numpy as np

from gripper.core.fields import Validated
from gripper.core.params import (
    DEG,
    PAPER_HINGE_STIFFNESS,
    PAPER_HINGE_STIFFNESS_PER_RAD_READING,
    GripperParams,
)
from gripper.references.continuum import BendingRecord, ReferenceConfig, ReferenceFinger, run_bending_record

READINGS = ("per_degree", "per_radian")
PAPER_HINGE_DAMPING = 10.0  # paper 000 Table 2, "N·m·s/deg" as printed (implausible, see above)
# Largest hinge angle the test aims at, as a fraction of the closure angle (the continuum
# reference's default 0.25 N reaches about 0.7).
TARGET_CLOSURE_FRACTION = 0.45


@dataclass(frozen=True)
class FmbsConfig(Validated):
    """The flexible multibody model's own settings (the rest is a :class:`ReferenceConfig`).

    Attributes:
        reading: how Table 2's "1.9e-3 N·m/deg" is read: ``"per_degree"`` (as printed,
            0.109 N·m/rad) or ``"per_radian"`` (1.9e-3 N·m/rad).
        hinge_damping: damper of each hinge [N·m·s/rad]; ``"modal"`` (default) for Table 2's
            modal damping 0.5 at the chain's first mode (:meth:`FmbsFinger.modal_hinge_damping`);
            or ``"paper"`` for Table 2's "10 N·m·s/deg" in the same reading as the spring.
    """

    reading: str = "per_degree"
    hinge_damping: float | str = "modal"

    def validate(self) -> FmbsConfig:
        if self.reading not in READINGS:
            raise ValueError(f"fmbs.reading: must be one of {', '.join(READINGS)}, "
                             f"got {self.reading!r}")
        c = self.hinge_damping
        if c not in ("paper", "modal") and (isinstance(c, bool) or not isinstance(c, int | float)
                             or not math.isfinite(c) or c < 0):
            raise ValueError(f"fmbs.hinge_damping: must be a number >= 0, 'modal' or 'paper', "
                             f"got {c!r}")
        return self

    @property
    def hinge_stiffness(self) -> float:
        """Torsion spring of each hinge [N·m/rad]."""
        return (PAPER_HINGE_STIFFNESS if self.reading == "per_degree"
                else PAPER_HINGE_STIFFNESS_PER_RAD_READING)

    @property
    def hinge_damping_value(self) -> float:
        """Damper of each hinge [N·m·s/rad] (``"modal"``: see FmbsFinger)."""
        if self.hinge_damping == "modal":
            raise ValueError("fmbs.hinge_damping: 'modal' depends on the finger's inertia; "
                             "use FmbsFinger.hinge_damping")
        if self.hinge_damping == "paper":
            return PAPER_HINGE_DAMPING / DEG if self.reading == "per_degree" else PAPER_HINGE_DAMPING
        return float(self.hinge_damping)

    def to_dict(self) -> dict:
        return asdict(self)


def fmbs_tension_max(p: GripperParams, fmbs: FmbsConfig) -> float:
    """Cable tension [N] at which the hinge springs alone would hold every hinge at
    ``TARGET_CLOSURE_FRACTION`` of its closure angle: T = f·theta_c·K / lever, the lever being
    the cable's height above the hinge axis."""
    g = p.finger
    lever = g.hole_height - g.hinge_z
    return TARGET_CLOSURE_FRACTION * math.radians(g.closure_angle_deg) * fmbs.hinge_stiffness / lever


ZONE_FRACTION = 0.5 * (1.0 - math.cos(math.pi / 4.0))  # = 0.146, see rigid_zones


def _element_u(p: GripperParams, mesh, e: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes of element ``e`` and their position along it, 0 at its proximal and 1 at its
    distal face, measured along the mesh's lines (which lean with the cut faces)."""
    from gripper.drives.cable.geometry import element_kind

    g = p.finger
    nodes = mesh.nodes_of_element[e]
    x, z = mesh.points[nodes, 0], mesh.points[nodes, 2]
    kind = element_kind(e, g.n_segments)
    d = np.maximum(0.0, z - g.bridge_thickness) * math.tan(0.5 * math.radians(g.cut_angle_deg))
    lo = e * g.pitch + (d if kind in ("middle", "tip") else 0.0)
    hi = (e + 1) * g.pitch - (d if kind in ("middle", "base") else 0.0)
    return nodes, (x - lo) / (hi - lo)


def rigid_zones(p: GripperParams, mesh, exclude: np.ndarray | None = None
                ) -> list[tuple[np.ndarray, np.ndarray, int]]:
    """The rigid zones of the flexible multibody finger: (nodes, origin, parent), parent the
    index of the zone a hinge joins it to (-1: a zone with planar dofs of its own).

    A zone is the silicone within ``ZONE_FRACTION`` of an element's length from its end, along
    the mesh's lines: the first of the default mesh's four cosine-graded cells (2.3 mm at the
    bridge of the default design, 0.78 of its thickness). It is the same region on every
    refinement (cosine grading puts a node at that fraction whatever the scale), so the mesh
    convergence of the model is systematic. Per bridge j: the end of element j-1, then the start
    of element j (hinged to it); last, the tip element's distal end (the knot, A_6). Nodes in
    ``exclude`` (the clamp's) are left out: on a deeply cut base element the zone's top reaches
    into the mount.
    """
    g = p.finger
    tol = 1e-9
    out = []
    keep = (lambda n: n) if exclude is None else (lambda n: n[~np.isin(n, exclude)])
    for j in range(1, g.n_segments):
        origin = np.array([j * g.pitch, 0.0, g.hinge_z])
        nb, ub = _element_u(p, mesh, j - 1)
        na, ua = _element_u(p, mesh, j)
        out.append((keep(nb[ub >= 1.0 - ZONE_FRACTION - tol]), origin, -1))
        out.append((keep(na[ua <= ZONE_FRACTION + tol]), origin, len(out) - 1))
    nt, ut = _element_u(p, mesh, g.n_segments - 1)
    out.append((keep(nt[ut >= 1.0 - ZONE_FRACTION - tol]), np.array([g.length, 0.0, g.hole_height]),
                -1))
    return out


# Rotational inertia added to every body [kg·m²] (node bodies have no other): keeps MuJoCo's
# inertia positive.
INERTIA_FLOOR = 1e-12


@dataclass
class _NodeBodies:
    """The body each mesh node belongs to (:meth:`FmbsFinger._node_bodies`).

    Attributes:
        owner: body name per node: ``"world"`` (clamped), ``"L<j>"``/``"R<j>"`` (the rigid
            zones before and after bridge j), ``"knot"`` or ``"body_<i>"`` (a node of its own).
        origins: each body's origin [m] in the finger frame.
        hinge_bodies: per bridge, (j, hinge origin [m], nodes before, nodes after).
        knot: the knot zone's nodes; knot_origin: its origin [m].
        node_bodies: the nodes with a body of their own.
    """

    owner: np.ndarray
    origins: dict[str, np.ndarray]
    hinge_bodies: list[tuple[int, np.ndarray, np.ndarray, np.ndarray]]
    knot: np.ndarray
    knot_origin: np.ndarray
    node_bodies: list[int]


def _inertial_xml(lumped: np.ndarray, pts: np.ndarray, nodes: np.ndarray, origin: np.ndarray
                  ) -> str:
    """The ``<inertial>`` of a rigid zone of ``nodes`` (lumped masses [kg]) about ``origin`` [m]:
    its mass and, on every axis, its inertia about y (the bending axis) [kg·m²]."""
    m = float(lumped[nodes].sum())
    r = pts[nodes] - origin
    iyy = float((lumped[nodes] * (r[:, 0] ** 2 + r[:, 2] ** 2)).sum()) + INERTIA_FLOOR
    return (f'<inertial pos="0 0 0" mass="{m:.9g}" '
            f'diaginertia="{iyy:.9g} {iyy:.9g} {iyy:.9g}"/>')


def _bodies_xml(p: GripperParams, pts: np.ndarray, zones: _NodeBodies, lumped: np.ndarray,
                k: float, c: float) -> list[str]:
    """The worldbody's bodies: each free node's (three slides), each bridge's pair of rigid
    zones (planar dofs, then the hinge of stiffness ``k`` [N·m/rad] and damping ``c``
    [N·m·s/rad]) and the knot's zone (planar dofs)."""
    g = p.finger
    floor = INERTIA_FLOOR
    bodies = []
    for i in zones.node_bodies:
        x, y, z = pts[i]
        bodies.append(
            f'<body name="body_{i}" pos="{x:.9g} {y:.9g} {z:.9g}">'
            f'<inertial pos="0 0 0" mass="{lumped[i]:.9g}" diaginertia="{floor} {floor} {floor}"/>'
            '<joint type="slide" axis="1 0 0"/><joint type="slide" axis="0 1 0"/>'
            '<joint type="slide" axis="0 0 1"/></body>')
    for j, origin, before, after in zones.hinge_bodies:
        bodies.append(
            f'<body name="L{j}" pos="{origin[0]:.9g} 0 {origin[2]:.9g}">'
            f'{_inertial_xml(lumped, pts, before, origin)}'
            '<joint type="slide" axis="1 0 0"/><joint type="slide" axis="0 0 1"/>'
            '<joint type="hinge" axis="0 -1 0"/>'
            f'<body name="R{j}">{_inertial_xml(lumped, pts, after, origin)}'
            f'<joint name="hinge{j}" type="hinge" axis="0 -1 0" stiffness="{k:.9g}" '
            f'damping="{c:.9g}"/></body></body>')
    bodies.append(
        f'<body name="knot" pos="{g.length:.9g} 0 {g.hole_height:.9g}">'
        f'{_inertial_xml(lumped, pts, zones.knot, zones.knot_origin)}'
        '<joint type="slide" axis="1 0 0"/><joint type="slide" axis="0 0 1"/>'
        '<joint type="hinge" axis="0 -1 0"/></body>')
    return bodies


def _model_xml(p: GripperParams, cfg: ReferenceConfig, mesh, bodies: list[str],
               owner: np.ndarray, verts: np.ndarray) -> str:
    """The MJCF of the flexible multibody finger: ``bodies`` and the flex over them (each
    vertex at ``verts`` [m] in its ``owner`` body's frame)."""
    return f"""<mujoco model="finger_fmbs">
  <option timestep="{cfg.timestep}" integrator="discrete" solver="Newton"
          iterations="{cfg.solver_iterations}" tolerance="{cfg.solver_tolerance:g}" gravity="0 0 0"/>
  <worldbody>
    {"".join(bodies)}
  </worldbody>
  <deformable>
    <flex name="body" dim="3" radius="0.0002" rgba="0.93 0.93 0.88 1"
          body="{" ".join(owner)}" vertex="{" ".join(f"{v:.9g}" for v in verts.ravel())}"
          element="{" ".join(str(i) for i in mesh.tets.ravel())}">
      <contact contype="0" conaffinity="0" selfcollide="none"/>
      <elasticity young="{p.material.youngs_modulus * cfg.modulus_factor:.9g}"
                  poisson="{p.material.poisson_ratio}" damping="{cfg.mesh_mode_damping:.9g}"/>
    </flex>
  </deformable>
</mujoco>"""


class FmbsFinger(ReferenceFinger):
    """The compiled flexible multibody finger (see the module docstring)."""

    def __init__(self, params: GripperParams | None = None,
                 config: ReferenceConfig | None = None, fmbs: FmbsConfig | None = None):
        self.fmbs = (fmbs or FmbsConfig()).validate()
        cfg = config or ReferenceConfig()
        super().__init__(params, replace(cfg, mesh=replace(cfg.mesh, split_bridges=True)))

    def modal_hinge_damping(self, lumped: np.ndarray) -> float:
        """Hinge damper [N·m·s/rad] that gives the chain's first mode Table 2's modal damping
        ratio (``ReferenceConfig.damping_ratio``, 0.5): c = 2·zeta·K/omega_1, with omega_1 =
        sqrt(K / (n_hinges·I)), the n springs in series turning the free finger of inertia I
        about the first hinge (its elements rigid; their own modes are far higher)."""
        g, pts = self.p.finger, self.mesh.points
        free = pts[:, 0] > g.pitch
        r2 = (pts[free, 0] - g.pitch) ** 2 + (pts[free, 2] - g.hinge_z) ** 2
        inertia = float((lumped[free] * self.mesh.node_weight[free] / self.mesh.node_weight[free]
                         * r2).sum()) / (0.5 if self.mesh.symmetric else 1.0)
        k = self.fmbs.hinge_stiffness
        omega = math.sqrt(k / (g.n_hinges * inertia))
        return 2.0 * self.cfg.damping_ratio * k / omega

    def _build(self) -> None:
        p, cfg, pts = self.p, self.cfg, self.mesh.points
        share = 0.5 if self.mesh.symmetric else 1.0  # the half mesh carries half of each hinge
        lumped = self.lumped_masses()
        zones = self._node_bodies()
        k = self.fmbs.hinge_stiffness * share
        self.hinge_damping = (self.modal_hinge_damping(lumped) if self.fmbs.hinge_damping == "modal"
                              else self.fmbs.hinge_damping_value)
        c = self.hinge_damping * share
        bodies = _bodies_xml(p, pts, zones, lumped, k, c)
        verts = np.array([pts[i] - zones.origins[zones.owner[i]] for i in range(len(pts))])
        self.model = mujoco.MjModel.from_xml_string(_model_xml(p, cfg, self.mesh, bodies,
                                                               zones.owner, verts))
        self.data = mujoco.MjData(self.model)
        self.free = np.zeros(len(pts), dtype=bool)
        self.free[zones.node_bodies] = True
        self.body_of_node = np.full(len(pts), -1)
        for i in zones.node_bodies:
            self.body_of_node[i] = self.model.body(f"body_{i}").id
        self._set_modal_damping(cfg.mass_damping)
        self._hold_symmetry_plane()
        mujoco.mj_forward(self.model, self.data)

        # Rigid-zone body of every zone node (-1 elsewhere): the cable's equivalent forces on
        # such nodes act on their body.
        owner = zones.owner
        self.zone_body_of_node = np.full(len(pts), -1)
        for name in set(owner[i] for i in range(len(pts))):
            if name.startswith(("L", "R")) or name == "knot":
                idx = [i for i in range(len(pts)) if owner[i] == name]
                self.zone_body_of_node[idx] = self.model.body(name).id
        self.zone_bodies = np.unique(self.zone_body_of_node[self.zone_body_of_node >= 0])

    def _node_bodies(self) -> _NodeBodies:
        """The body of every mesh node: the world (clamp), a rigid zone either side of each
        bridge, the knot's zone, or a body of its own.

        Raises:
            ValueError: the clamp reaches the first bridge.
        """
        p, mesh, pts = self.p, self.mesh, self.mesh.points
        g = p.finger
        owner = np.full(len(pts), "", dtype=object)
        owner[self.pinned] = "world"
        origins: dict[str, np.ndarray] = {"world": np.zeros(3)}
        zones = rigid_zones(p, mesh, exclude=self.pinned)
        hinge_bodies = []
        for j in range(1, g.n_segments):
            (before, origin, _), (after, _, _) = zones[2 * j - 2], zones[2 * j - 1]
            if len(after) == 0 or np.isin(after, self.pinned).any():
                raise ValueError("reference.clamp_length: the clamp reaches the first bridge")
            for name, nodes in ((f"L{j}", before), (f"R{j}", after)):
                owner[nodes] = name
                origins[name] = origin
            hinge_bodies.append((j, origin, before, after))
        # The knot (paper 000's connection point A_6): its rigid zone takes the knot's force as
        # a washer would, instead of the channel's rim being crushed.
        knot, knot_origin, _ = zones[-1]
        owner[knot] = "knot"
        origins["knot"] = knot_origin
        node_bodies = [i for i in range(len(pts)) if owner[i] == ""]
        for i in node_bodies:
            owner[i] = f"body_{i}"
            origins[owner[i]] = pts[i]
        return _NodeBodies(owner, origins, hinge_bodies, knot, knot_origin, node_bodies)

    def _set_modal_damping(self, alpha: float) -> None:
        """Modal damping (MuJoCo refuses joint damping on flex bodies in the XML; as in the
        continuum reference it is set on the compiled model): ``alpha`` [1/s] times each dof's
        mass, or its body's inertia for the interfaces' rotation. The hinges keep their damper."""
        m = self.model
        for jnt in range(m.njnt):
            if m.jnt_type[jnt] == mujoco.mjtJoint.mjJNT_HINGE and m.jnt_stiffness[jnt] > 0:
                continue
            b = m.jnt_bodyid[jnt]
            inertia = (m.body_inertia[b, 1] if m.jnt_type[jnt] == mujoco.mjtJoint.mjJNT_HINGE
                       else m.body_mass[b])
            m.dof_damping[m.jnt_dofadr[jnt]] = alpha * inertia

    def node_positions(self) -> np.ndarray:
        return self.data.flexvert_xpos.copy()

    def _clear_cable_forces(self) -> None:
        super()._clear_cable_forces()
        self.data.xfrc_applied[self.zone_bodies] = 0.0

    def _apply_node_forces(self, nodes: np.ndarray, forces: np.ndarray, pos: np.ndarray) -> None:
        """As the continuum reference's, and the shares of nodes in a rigid zone act on the
        zone's body at the node (force and its moment about the body's centre of mass):
        dropping them broke the balance that gives every hinge the cable's moment T·lever (the
        proximal hinge rested 11 % short)."""
        super()._apply_node_forces(nodes, forces, pos)
        xf = self.data.xfrc_applied
        bodies = self.zone_body_of_node[nodes]
        for i in np.flatnonzero(bodies >= 0):
            b = bodies[i]
            xf[b, :3] += forces[i]
            xf[b, 3:] += np.cross(pos[nodes[i]] - self.data.xipos[b], forces[i])


def run_fmbs(params: GripperParams | None = None, config: ReferenceConfig | None = None,
             fmbs: FmbsConfig | None = None, *, at_rest: bool = False) -> BendingRecord:
    """Run paper 000's flexible multibody bending test (tension staircase of ``config``; its
    ``tension_max`` is replaced by :func:`fmbs_tension_max` unless ``config`` is given).
    ``at_rest``: also relax each hold's end to rest, as :func:`gripper.references.continuum.run_reference`.

    Raises:
        ValueError: invalid settings, or a tension that closes a cut (as the continuum
            reference, the model has no contact between cut faces).
        SimulationUnstable: MuJoCo warned or the state became non-finite.
    """
    p = (params or GripperParams()).validate()
    f = (fmbs or FmbsConfig()).validate()
    cfg = config or ReferenceConfig(tension_max=fmbs_tension_max(p, f))
    if not at_rest:
        return run_bending_record(FmbsFinger(p, cfg, f))
    from gripper.references.continuum import relaxation_config
    from gripper.references.relaxation import with_rest_points

    snaps: list = []
    record = run_bending_record(FmbsFinger(p, cfg, f), snaps)
    relax = relaxation_config(cfg)
    return with_rest_points(record, lambda: FmbsFinger(p, relax, f), snaps)


__all__ = ["FmbsConfig", "FmbsFinger", "READINGS", "fmbs_tension_max", "run_fmbs"]
