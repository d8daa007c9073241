"""Flexible-multibody reference: the silicone finger as a MuJoCo 3D flex, bent by its cable.

The body (cuts, bridges, cable channel) is meshed by :func:`gripper.references.finger_mesh.finger_mesh`
from the same :class:`~gripper.core.params.FingerGeometry` as the hinge model and simulated as a
``flexcomp`` of linear tetrahedra with the silicone of paper 000 Tables 1-2, clamped at B1, loaded
by a staircase of cable tensions (2 s at 5e-4 s, paper 000 §IV). How it is built (symmetry, the
cable's equivalent forces, the load, mass and damping, gravity) and why: ``docs/calibration.md``,
"How the reference is built". Its checks: :mod:`gripper.references.continuum_checks`.

Example:
    >>> from gripper.references.continuum import ReferenceConfig, run_reference
    >>> res = run_reference(config=ReferenceConfig(duration=0.1))   # doctest: +SKIP
    >>> res.element_angles_deg.shape[1]                              # doctest: +SKIP
    6
"""

from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass, field, replace

import mujoco
import numpy as np

from gripper.core.fields import Validated
from gripper.core.params import GripperParams
from gripper.core.timesteps import PAPER_BENDING_TIMESTEP
from gripper.drives.cable.finger import GUIDE_DEPTH
from gripper.references.finger_mesh import FingerMesh, MeshResolution, finger_mesh
from gripper.references.relaxation import with_rest_points
from gripper.sim.stability import SimulationUnstable, check_stable

PAPER_DURATION = 2.0  # s, paper 000 §IV
PAPER_MODAL_DAMPING = 0.5  # -, paper 000 Table 2 ("modal damping 0.5")
RAMP_TIME = 0.05  # s, each tension step's half-cosine ramp: 10 x shorter than a hold
# Margin past the closure angle before a hinge counts as closed, in the reference and in bench
# data (gripper.calibration.measured) [deg]: about twice the 1° reading noise the fit is checked
# against (tests: identifiability with 1° noise).
CLOSED_CUT_MARGIN_DEG = 2.0
SYMMETRY_STIFFNESS_FACTOR = 1e6  # -, symmetry-plane spring over E x width (see _hold_symmetry_plane)


@dataclass(frozen=True)
class ReferenceConfig(Validated):
    """Settings of the reference bending test.

    Attributes:
        mesh: mesh resolution (see :class:`MeshResolution`).
        tension_max: highest cable tension [N]. Default 0.25 N: keeps the default finger's
            cuts open (largest hinge angle about 29°, 0.7 of the 41° closing angle),
            since the reference does not model contact between cut faces.
        n_levels: number of tension steps (quasi-static points) [-].
        duration: length of the whole test [s] (paper 000 §IV: 2 s).
        timestep: [s] (paper 000 §IV: 5e-4 s).
        damping_ratio: modal damping ratio zeta of the first bending mode [-] (paper 000
            Table 2: 0.5).
        first_mode_hz: first bending frequency used to turn zeta into mass-proportional
            damping [Hz].
            Default 1.5 Hz: the period of the default finger's response to a small tension
            step, measured on a lightly damped run (``docs/calibration.md``, "Reference
            defaults").
        mesh_mode_damping: flex (Rayleigh stiffness-proportional) damping [s]. Default 1e-5 s:
            zeta about 0.6 for the finest mesh modes (bulk wave at 59 m/s across a 1 mm cell,
            about 1.2e5 rad/s) and 7e-5 at the first mode, so it damps mesh noise only.
        clamp_length: length of B1 held by the palm mount, from its proximal face [m].
            Default half a pitch (8 mm): a mount that grips half of the base element.
        solver_iterations: iteration cap of MuJoCo's effective-metric solve [-]. The default
            3000 converges for the default mesh; MuJoCo warns (and the run fails) otherwise.
        solver_tolerance: relative residual at which MuJoCo's iterative M+K solve stops [-].
            Default 1e-2: on the default design and mesh, the whole 2 s test agrees with a
            1e-6 run within 0.005° on every element angle and 3 µm on the tip, at half the
            time (112 s against 222 s, run side by side). At a 5e-4 s step the solve is well
            conditioned (h²K/M is 100x smaller than at the 5 ms relaxation steps of the static
            checks, which keep 1e-6: there 1e-4 left a finer mesh far from rest).
        sample_every: record every k-th step [-].
        modulus_factor: factor on the silicone's Young's modulus that corrects the mesh's
            discretisation stiffness [-]: ``MeshConvergence.stiffness_correction`` from
            :mod:`gripper.references.convergence`, so that this mesh has the extrapolated
            (converged) small-load compliance. 1 runs the mesh as it is. ``gripper
            calibrate`` sets it from a convergence study of the design.
    """

    mesh: MeshResolution = field(default_factory=MeshResolution)
    tension_max: float = 0.25
    n_levels: int = 5
    duration: float = PAPER_DURATION
    timestep: float = PAPER_BENDING_TIMESTEP
    damping_ratio: float = PAPER_MODAL_DAMPING
    first_mode_hz: float = 1.5
    mesh_mode_damping: float = 1e-5
    clamp_length: float = 0.008
    solver_iterations: int = 3000
    solver_tolerance: float = 1e-2
    sample_every: int = 20
    modulus_factor: float = 1.0

    def validate(self) -> ReferenceConfig:
        self.mesh.validate()
        for name in ("tension_max", "duration", "timestep", "first_mode_hz", "clamp_length",
                     "solver_tolerance", "mesh_mode_damping", "modulus_factor"):
            v = getattr(self, name)
            if not (isinstance(v, int | float) and math.isfinite(v) and v > 0):
                raise ValueError(f"reference.{name}: must be a number > 0, got {v!r}")
        if not 0 <= self.damping_ratio < 10:
            raise ValueError(f"reference.damping_ratio: must be in [0, 10), "
                             f"got {self.damping_ratio!r}")
        if self.timestep > 0.01:
            raise ValueError(f"reference.timestep: must be <= 0.01 s, got {self.timestep!r}")
        for name, lo, hi in (("n_levels", 1, 100), ("solver_iterations", 10, 100000),
                             ("sample_every", 1, 10000)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= hi:
                raise ValueError(f"reference.{name}: must be an integer in [{lo}, {hi}], "
                                 f"got {v!r}")
        if self.duration / self.n_levels <= 2 * RAMP_TIME:
            raise ValueError(f"reference.n_levels: each level needs > {2 * RAMP_TIME} s; "
                             f"got {self.n_levels} levels in {self.duration} s")
        return self

    @property
    def mass_damping(self) -> float:
        """Mass-proportional damping coefficient alpha = 2 zeta (2 pi f1) [1/s], f1 scaled by
        sqrt(modulus_factor) (a frequency goes as the square root of the stiffness)."""
        f1 = self.first_mode_hz * math.sqrt(self.modulus_factor)
        return 2.0 * self.damping_ratio * 2.0 * math.pi * f1

    def to_dict(self) -> dict:
        return asdict(self)


def tension_schedule(t: np.ndarray, tension_max: float, n_levels: int,
                     duration: float) -> np.ndarray:
    """Staircase tension [N] at times ``t`` [s]: ``n_levels`` half-cosine steps, then holds."""
    hold = duration / n_levels
    k = np.clip(np.floor(t / hold), 0, n_levels - 1)
    frac = np.clip((t - k * hold) / RAMP_TIME, 0.0, 1.0)
    step = 0.5 * (1.0 - np.cos(np.pi * frac))
    return tension_max / n_levels * (k + step)


def plateau_indices(t: np.ndarray, n_levels: int, duration: float) -> np.ndarray:
    """Indices of the samples at the end of each hold (the quasi-static points)."""
    hold = duration / n_levels
    ends = hold * np.arange(1, n_levels + 1)
    return np.array([int(np.argmin(np.abs(t - e))) for e in ends])


@dataclass
class BendingRecord:
    """A bending test in the finger frame, from the reference, a hinge model or a bench.

    Attributes:
        t: time [s], shape (n,).
        tension_N: cable tension [N], shape (n,).
        r: cable shortening rate [-], shape (n,).
        element_angles_deg: rotation of each element B1..Bn about the hinge axis from its
            straight pose, positive curling towards the grasping face [deg], shape (n, n_seg).
        tip_xz_m: tip point (neutral axis at the distal face) x and z [m], shape (n, 2).
        static: indices of the quasi-static samples (the ends of the holds), shape (k,).
        wall_time_s: wall-clock time of the simulation [s].
        warnings: MuJoCo warnings counted over the run.
        rest_element_angles_deg, rest_tip_xz_m: the static points **at rest**, shape (k, n_seg)
            and (k, 2): each hold's end state relaxed at its tension until its own residual is
            small (:func:`gripper.references.continuum_checks.rest_points`); None for records
            whose static points are at rest already (bench data) or that predate them.
        rest_moved_deg: each rest point's residual, the bending angle's move over the last half
            second of its relaxation [deg], shape (k,).
    """

    t: np.ndarray
    tension_N: np.ndarray
    r: np.ndarray
    element_angles_deg: np.ndarray
    tip_xz_m: np.ndarray
    static: np.ndarray
    wall_time_s: float = 0.0
    warnings: int = 0
    rest_element_angles_deg: np.ndarray | None = None
    rest_tip_xz_m: np.ndarray | None = None
    rest_moved_deg: np.ndarray | None = None

    @property
    def has_rest(self) -> bool:
        """Whether the record carries its static points at rest (see the attributes)."""
        return self.rest_element_angles_deg is not None and self.rest_tip_xz_m is not None

    def to_json_dict(self) -> dict:
        return {k: (v.tolist() if isinstance(v, np.ndarray) else v)
                for k, v in self.__dict__.items()}


FLEX_RADIUS = 0.0002  # m: the flex's collision radius (it collides only in gripper.calibration.contact_check)
# Contact is off: the reference measures bending with open cuts (see tension_max).
CONTACT_OFF = 'contype="0" conaffinity="0" selfcollide="none"'


def _flexcomp_xml(p: GripperParams, mesh: FingerMesh, pinned: np.ndarray, cfg: ReferenceConfig, *,
                  world: str = "", contact: str = CONTACT_OFF) -> str:
    """The reference's scene; ``world``: more world elements (an obstacle), ``contact``: the
    flex's contact attributes."""
    mass = p.material.density * mesh.volume()
    pts = " ".join(f"{v:.9g}" for v in mesh.points.ravel())
    elem = " ".join(str(i) for i in mesh.tets.ravel())
    pin = " ".join(str(i) for i in pinned)
    return f"""<mujoco model="finger_reference">
  <option timestep="{cfg.timestep}" integrator="discrete" solver="Newton"
          iterations="{cfg.solver_iterations}" tolerance="{cfg.solver_tolerance:g}" gravity="0 0 0"/>
  <worldbody>{world}
    <body name="clamp">
      <flexcomp name="body" type="direct" dim="3" point="{pts}" element="{elem}"
                mass="{mass:.9g}" radius="{FLEX_RADIUS}" rgba="0.93 0.93 0.88 1">
        <contact {contact}/>
        <elasticity young="{p.material.youngs_modulus * cfg.modulus_factor:.9g}" poisson="{p.material.poisson_ratio}"
                    damping="{cfg.mesh_mode_damping:.9g}"/>
        <pin id="{pin}"/>
      </flexcomp>
    </body>
  </worldbody>
</mujoco>"""


def kabsch_angles(mesh: FingerMesh, cur: np.ndarray, groups: list[np.ndarray],
                   weights: list[np.ndarray] | None = None
                   ) -> tuple[np.ndarray, list[tuple[np.ndarray, np.ndarray, np.ndarray]]]:
    """Best-fit rotation of each node group of the whole body (mirror images included), the
    nodes weighted by ``weights`` (per group, whole-body weights such as
    ``FingerMesh.element_volume_weights``; equal if omitted); angle about -y (curl to +z) [rad]
    and transforms (rotation, weighted centroid before, after)."""
    angles = np.empty(len(groups))
    fits = []
    for k, idx in enumerate(groups):
        a, b = mesh.mirrored(idx, mesh.points[idx]), mesh.mirrored(idx, cur[idx])
        if weights is None:
            w = np.ones(len(a))
        else:  # split each node's whole-body weight between it and its mirror image
            half = weights[k] / mesh.node_weight[idx]
            w = np.concatenate([half, half[mesh.node_weight[idx] > 1.0]])
        w = w / w.sum()
        ca, cb = w @ a, w @ b
        h = (a - ca).T @ ((b - cb) * w[:, None])
        u, _, vt = np.linalg.svd(h)
        dfix = np.diag([1.0, 1.0, np.sign(np.linalg.det(vt.T @ u.T))])
        rot = vt.T @ dfix @ u.T
        angles[k] = math.atan2(rot[2, 0], rot[0, 0])
        fits.append((rot, ca, cb))
    return angles, fits


class ReferenceFinger:
    """The compiled reference model and the bookkeeping of its nodes and cable.

    Example:
        >>> ref = ReferenceFinger(GripperParams(), ReferenceConfig())   # doctest: +SKIP
        >>> ref.model.nv                                                # doctest: +SKIP
    """

    def __init__(self, params: GripperParams | None = None,
                 config: ReferenceConfig | None = None):
        self.p = (params or GripperParams()).validate()
        self.cfg = (config or ReferenceConfig()).validate()
        g = self.p.finger
        self.mesh = finger_mesh(g, self.cfg.mesh)
        pts = self.mesh.points
        self.pinned = np.flatnonzero(pts[:, 0] <= self.cfg.clamp_length + 1e-9)
        self._build()
        # Cable path: guide (fixed), one via per element, knot at the tip.
        self.weight = self.mesh.node_weight
        # Share of each whole-body load the meshed part carries: half for a symmetric half mesh.
        self.load_share = 0.5 if self.mesh.symmetric else 1.0
        self.groups = [c for c in self.mesh.channel_nodes] + [self.mesh.anchor_nodes]
        self.guide = np.array([-GUIDE_DEPTH, 0.0, g.hole_height])
        path0 = np.vstack([self.guide] + [self.centroid(grp, pts) for grp in self.groups])
        self.length0 = g.length  # r is referred to the finger length, as in the hinge test
        self.path_length0 = float(np.linalg.norm(np.diff(path0, axis=0), axis=1).sum())
        self.tip_point = np.array([g.length, 0.0, g.hinge_z])

    def _scene_xml(self, *, world: str = "", contact: str = CONTACT_OFF) -> str:
        """The MJCF of the reference's scene; a subclass adds ``world`` elements (an obstacle)
        and sets the flex's ``contact`` attributes."""
        return _flexcomp_xml(self.p, self.mesh, self.pinned, self.cfg, world=world, contact=contact)

    def _build(self) -> None:
        """Compile the model; set ``model``, ``data``, ``free`` (nodes with dofs of their own)
        and ``body_of_node`` (-1 for the others)."""
        pts = self.mesh.points
        self.model = mujoco.MjModel.from_xml_string(self._scene_xml())
        self.data = mujoco.MjData(self.model)
        free = np.ones(len(pts), dtype=bool)
        free[self.pinned] = False
        self.body_of_node = np.full(len(pts), -1)
        for i in np.flatnonzero(free):
            self.body_of_node[i] = self.model.body(f"body_{i}").id
        self.free = free
        self._set_lumped_mass_and_damping()
        self._hold_symmetry_plane()

    def lumped_masses(self) -> np.ndarray:
        """Each node's mass: a quarter of each of its tetrahedra's [kg]."""
        tet_mass = self.p.material.density * np.abs(self.mesh.tet_volumes())
        lumped = np.zeros(self.mesh.n_nodes)
        np.add.at(lumped, self.mesh.tets.ravel(), np.repeat(0.25 * tet_mass, 4))
        return lumped

    def _set_lumped_mass_and_damping(self) -> None:
        """Node masses from the tetrahedra's volumes; dof damping alpha x node mass."""
        m = self.model
        lumped = self.lumped_masses()
        bodies = self.body_of_node[self.free]
        m.body_mass[bodies] = lumped[self.free]
        m.dof_damping[m.jnt_dofadr] = self.cfg.mass_damping * m.body_mass[m.jnt_bodyid]
        mujoco.mj_setConst(m, self.data)
        mujoco.mj_forward(m, self.data)

    def _hold_symmetry_plane(self) -> None:
        """Hold the nodes on the symmetry plane in it: a stiff spring on each one's y slide.

        The spring, ``SYMMETRY_STIFFNESS_FACTOR`` x E x finger width, is 1e6 times the
        stiffness of a finger-wide cube of silicone, so the plane nodes' y drift is that factor
        below the body's own deformation. As joint stiffness it sits on the diagonal of MuJoCo's
        effective metric (integrated implicitly, exact in the block preconditioner); every node
        keeps its three world-axis slides, the fast path of flex elasticity.
        """
        m = self.model
        k = SYMMETRY_STIFFNESS_FACTOR * self.p.material.youngs_modulus * self.p.finger.width
        for i in self.mesh.plane_nodes:
            b = self.body_of_node[i]
            if b < 0:
                continue
            j = m.body_jntadr[b] + 1  # flexcomp's slides are x, y, z in this order
            if not np.allclose(m.jnt_axis[j], [0.0, 1.0, 0.0]):
                raise RuntimeError("reference: flexcomp node joints are not x, y, z slides")
            m.jnt_stiffness[j] = k
            m.qpos_spring[m.jnt_qposadr[j]] = 0.0

    def centroid(self, idx: np.ndarray, pos: np.ndarray) -> np.ndarray:
        """Centroid of the whole body's nodes ``idx`` (mirror images counted) [m]."""
        w = self.weight[idx]
        c = (w[:, None] * pos[idx]).sum(0) / w.sum()
        if self.mesh.symmetric:
            c[1] = 0.0
        return c

    def node_positions(self) -> np.ndarray:
        pos = self.mesh.points.copy()
        pos[self.free] = self.data.xpos[self.body_of_node[self.free]]
        return pos

    def apply_cable(self, tension: float, pos: np.ndarray) -> float:
        """Set the cable's equivalent nodal forces for ``tension`` [N]; return the path length."""
        path = np.vstack([self.guide] + [self.centroid(grp, pos) for grp in self.groups])
        seg = np.diff(path, axis=0)
        lengths = np.linalg.norm(seg, axis=1)
        u = seg / lengths[:, None]
        self._clear_cable_forces()
        for k, grp in enumerate(self.groups):
            u_out = u[k + 1] if k + 1 < len(u) else np.zeros(3)
            force = tension * (u_out - u[k])
            # Equal shares per node of the whole body; a plane node carries half of its share.
            share = self.load_share * self.weight[grp] / self.weight[grp].sum()
            self._apply_node_forces(grp, share[:, None] * force, pos)
        return float(lengths.sum())

    def _clear_cable_forces(self) -> None:
        self.data.xfrc_applied[:, :3] = 0.0

    def _apply_node_forces(self, nodes: np.ndarray, forces: np.ndarray, pos: np.ndarray) -> None:
        """Add ``forces`` [N] (one row per node) on ``nodes``; those without a body of their
        own (pinned) take none."""
        bodies = self.body_of_node[nodes]
        moving = bodies >= 0
        if moving.any():
            self.data.xfrc_applied[bodies[moving], :3] += forces[moving]

    def measure(self, pos: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Element angles [rad] (B1..Bn) and the tip point's x, z [m]."""
        angles, fits = kabsch_angles(self.mesh, pos, list(self.mesh.nodes_of_element),
                                      list(self.mesh.element_volume_weights))
        rot, ca, cb = fits[-1]
        tip = rot @ (self.tip_point - ca) + cb
        return angles, tip[[0, 2]]


def run_reference(params: GripperParams | None = None,
                  config: ReferenceConfig | None = None, *, at_rest: bool = False) -> BendingRecord:
    """Run the reference bending test (see the module docstring). ``at_rest``: also relax each
    hold's end to rest (:func:`gripper.references.continuum_checks.rest_points`; ``gripper
    calibrate`` does, a minute or two per level).

    Raises:
        ValueError: invalid parameters or config, or a tension that closes a cut: the reference
            has no contact between cut faces, so the run stops as soon as a hinge (the
            rotation between neighbouring elements) passes the closure angle by
            ``CLOSED_CUT_MARGIN_DEG``, naming the tension to stay below.
        SimulationUnstable: MuJoCo warned (e.g. the effective-metric solve did not converge)
            or the state became non-finite.
    """
    ref = ReferenceFinger(params, config)
    if not at_rest:
        return run_bending_record(ref)
    snaps: list = []
    record = run_bending_record(ref, snaps)
    relax = relaxation_config(ref.cfg)
    return with_rest_points(record, lambda: ReferenceFinger(ref.p, relax), snaps)


def run_bending_record(ref: ReferenceFinger, snapshots: list | None = None) -> BendingRecord:
    """The tension staircase of ``ref.cfg`` on a built reference finger (the continuum body or
    paper 000's flexible multibody model, :mod:`gripper.references.fmbs`); see
    :func:`run_reference` for what it raises. ``snapshots``: a list that receives ``qpos`` at
    each static sample (the ends of the holds), for relaxing them to rest."""
    closed_limit = math.radians(ref.p.finger.closure_angle_deg + CLOSED_CUT_MARGIN_DEG)
    cfg = ref.cfg
    m, d = ref.model, ref.data
    n_steps = int(round(cfg.duration / cfg.timestep))
    times = np.arange(n_steps + 1) * cfg.timestep
    tensions = tension_schedule(times, cfg.tension_max, cfg.n_levels, cfg.duration)
    rows = []
    states = []
    t0 = time.perf_counter()
    for step in range(n_steps + 1):
        pos = ref.node_positions()
        length = ref.apply_cable(float(tensions[step]), pos)
        if step % cfg.sample_every == 0 or step == n_steps:
            angles, tip = ref.measure(pos)
            if snapshots is not None:
                states.append(d.qpos.copy())
            rows.append((d.time, tensions[step], (ref.path_length0 - length) / ref.length0,
                         angles, tip))
            hinge = np.diff(angles)
            if (hinge > closed_limit).any():
                j = int(np.argmax(hinge))
                raise ValueError(
                    f"reference.tension_max: at {tensions[step]:.3g} N hinge B{j + 1}-B{j + 2} is at "
                    f"{math.degrees(hinge[j]):.1f}°, past the cut's closure angle "
                    f"{ref.p.finger.closure_angle_deg:.1f}°; the reference has no contact between "
                    f"cut faces: keep tension_max below about {tensions[step]:.2g} N "
                    f"(now {cfg.tension_max:g} N)")
        if step == n_steps:
            break
        mujoco.mj_step(m, d)
        if step % 100 == 0:
            check_stable(m, d, "reference bending test")
    check_stable(m, d, "reference bending test")
    wall = time.perf_counter() - t0
    t = np.array([r[0] for r in rows])
    static = plateau_indices(t, cfg.n_levels, cfg.duration)
    if snapshots is not None:
        snapshots.extend(states[i] for i in static)
    return BendingRecord(
        t=t,
        tension_N=np.array([r[1] for r in rows]),
        r=np.array([r[2] for r in rows]),
        element_angles_deg=np.degrees(np.array([r[3] for r in rows])),
        tip_xz_m=np.array([r[4] for r in rows]),
        static=static,
        wall_time_s=wall,
        warnings=int(sum(w.number for w in d.warning)),
    )



def rest_config(mesh: MeshResolution) -> ReferenceConfig:
    """A configuration that comes to rest for static checks: 5 ms implicit steps, the first mode
    critically damped. The solve keeps a 1e-6 tolerance: at 5 ms steps it is ill-conditioned
    (see ReferenceConfig)."""
    return ReferenceConfig(mesh=mesh, timestep=5e-3, damping_ratio=1.0, solver_tolerance=1e-6,
                           solver_iterations=20000)


def relaxation_config(cfg: ReferenceConfig) -> ReferenceConfig:
    """``cfg`` (its mesh, correction, clamp) with the relaxation's step, damping and solve."""
    return replace(rest_config(cfg.mesh), modulus_factor=cfg.modulus_factor, clamp_length=cfg.clamp_length,
                   tension_max=cfg.tension_max, mesh_mode_damping=cfg.mesh_mode_damping)


__all__ = ["BendingRecord", "ReferenceConfig", "ReferenceFinger", "SimulationUnstable", "plateau_indices",
           "relaxation_config", "rest_config", "run_bending_record", "run_reference", "tension_schedule"]
