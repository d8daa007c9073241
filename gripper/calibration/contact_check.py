"""The hinge-chain finger in contact, checked against the continuum body (issue 44, item 3).

Two tests, each run on the hinge chain (:func:`gripper.drives.cable.finger.build_bending_spec`: one
finger clamped at B1, bending in the horizontal plane, grasping face towards world +y) and on
the continuum reference's discretisation of the same body
(:func:`gripper.references.finger_mesh.finger_mesh`, clamped over ``CLAMP_LENGTH`` as in
:func:`gripper.references.convergence.linear_compliance`). Finger frame throughout: x along the
finger, z towards the grasping face, y across (the hinge axes).

* **Blocked tip.** The finger straight, a rigid frictionless stop touching the tip element's
  distal edge on the grasping side (the line x = L, z = height, across the width); the cable
  pulled with tension T; the stop's reaction.

  - Continuum, linear (:func:`blocked_tip_linear`, :func:`blocked_tip_force_continuum`): the
    scikit-fem model of ``linear_compliance`` (same mesh, knot load and clamp) with the
    displacement normal to the stop (z) of the distal edge's nodes held at zero, a Dirichlet
    condition; the reaction is ``K u - f`` at those dofs, summed, times 2 for the symmetric half
    mesh. With the finger straight every via point of the cable lies on one line, so the
    cable's only load is the knot's ``-T`` along x, as in ``linear_compliance``. The blocked
    finger does not stay straight: it takes an S shape (the proximal hinges open, the distal
    ones close), so the model holds only while its hinges turn a few degrees
    (``small_rotation_tension``, about 0.025 N on the default design) and its cuts stay open
    (``cut_closing_tension``, about 0.19 N): the tensions of the grasp's set-point (0.5-5 N)
    are far outside it, and :func:`blocked_tip_force_continuum` refuses them.
  - Continuum, nonlinear (:func:`continuum_contact` against :func:`tip_stop`): the MuJoCo flex
    reference with the stop as a plane in its scene, relaxed to rest; its large rotations and
    the contact are MuJoCo's. Minutes per tension.
  - Chain (:func:`blocked_tip_force_chain`, :func:`chain_contact`): the stop is a plane that
    collides with the tip element only (an explicit contact pair; see :func:`tip_stop` for why
    not a box), frictionless (``condim`` 1). The servo is switched off (MuJoCo's actuation
    disabled) and the reel's slide joint pulled with a constant generalised force T, which the
    cable's tendon limit carries to the finger as tension T (its sensor reads T at rest); run
    to rest, the stop's contact normal forces summed (``mj_contactForce``).

* **Cylinder.** The finger closes on a rigid world-fixed frictionless cylinder (axis along the
  hinge axes) resting on the two edges of the middle cut's opening on the grasping face (the
  cut between B3 and B4, x = L/2): :func:`cylinder_contact_chain` and, on the MuJoCo flex
  reference with the cylinder in its scene, :func:`cylinder_contact_continuum` (2 minutes per
  case). The flex has no contact between cut faces, so the comparison needs tensions that
  keep the cuts open; at the set-point the chain's cuts are closed (its stops hold them).

Where each holds, and the measured numbers: ``docs/calibration.md``, "The finger in contact".

Example:
    >>> from gripper.calibration.contact_check import blocked_tip_linear
    >>> blocked_tip_linear().force_per_newton        # doctest: +SKIP
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass

import mujoco
import numpy as np

from gripper.core.params import FingerGeometry, GripperParams
from gripper.core.resources import DEFAULT_CALIBRATION_DIR
from gripper.drives.cable.finger import build_bending_spec
from gripper.parts.names import FingerNames
from gripper.references.continuum import FLEX_RADIUS, ReferenceConfig, ReferenceFinger, kabsch_angles
from gripper.references.convergence import MEASURE_SCALE, linear_finger, solve_clamped
from gripper.references.finger_mesh import FingerMesh, MeshResolution
from gripper.sim.stability import SimulationUnstable, check_stable

CLAMP_LENGTH = 0.008  # m, the reference's clamp (ReferenceConfig.clamp_length)
# Tensions of the blocked-tip comparison [N]: the small-load range where both models stay
# near straight (largest hinge angle under about 6°, see SMALL_ROTATION_DEG).
LINEAR_TENSIONS = (0.002, 0.005, 0.01, 0.015, 0.02)
# The grasp controller's range of cable tensions [N] (GRIP_TENSION is 7.5 N since 0.21.0).
SET_POINT_TENSIONS = (0.5, 1.0, 2.0, 3.5, 5.0)
# deg: the largest hinge angle up to which the linear model counts as small-rotation
SMALL_ROTATION_DEG = 6.0
CYLINDER_DIAMETERS = (0.020, 0.040, 0.060)  # m


def committed_modulus_factor() -> float:
    """The default design's stiffness correction (the committed convergence study's
    ``stiffness_correction``): the factor on Young's modulus that gives the default mesh the
    converged compliance [-]. It scales every displacement of the linear model and none of its
    reactions."""
    conv = json.loads((DEFAULT_CALIBRATION_DIR / "convergence.json").read_text())
    return float(conv["stiffness_correction"])


@dataclass(frozen=True)
class BlockedTipLinear:
    """The blocked-tip test on the continuum body, linear (per newton of cable tension).

    Attributes:
        force_per_newton: the stop's reaction per newton of tension [N/N].
        edge_reactions_per_newton: each distal-edge node's share of it (the whole body's: a
            node off the symmetry plane counts with its mirror image), finger y from 0 to
            the side [N/N]; all positive when the whole edge presses on the stop.
        hinge_deg_per_newton: each hinge's angle (B(j+1) against Bj, positive closing the
            cut) per newton [deg/N], with ``modulus_factor``.
        free_hinge_deg_per_newton: the same without the stop [deg/N].
        cut_closing_tension: the tension at which the first cut's faces meet at the grasping
            face, from the displacement of its two corners across the width [N].
        small_rotation_tension: the tension at which the largest hinge angle reaches
            ``SMALL_ROTATION_DEG`` [N].
        modulus_factor: factor on Young's modulus [-] (sets the angles, not the force).
        nodes: mesh nodes [-].
        wall_time_s: [s].
    """

    force_per_newton: float
    edge_reactions_per_newton: tuple[float, ...]
    hinge_deg_per_newton: tuple[float, ...]
    free_hinge_deg_per_newton: tuple[float, ...]
    cut_closing_tension: float
    small_rotation_tension: float
    modulus_factor: float
    nodes: int
    wall_time_s: float


def blocked_tip_linear(params: GripperParams | None = None, mesh: MeshResolution | None = None, *,
                       clamp_length: float = CLAMP_LENGTH,
                       modulus_factor: float | None = None) -> BlockedTipLinear:
    """The blocked-tip test on the continuum body's linear model (see the module docstring).

    Args:
        mesh: the mesh (default: the reference's).
        clamp_length: length of B1 held by the mount [m].
        modulus_factor: factor on Young's modulus; default :func:`committed_modulus_factor`
            (the default design's; it scales the angles and limits, never the force).
    """
    t0 = time.perf_counter()
    p = (params or GripperParams()).validate()
    g = p.finger
    factor = committed_modulus_factor() if modulus_factor is None else float(modulus_factor)
    lf = linear_finger(p, mesh or MeshResolution(), clamp_length=clamp_length,
                       youngs_modulus=p.material.youngs_modulus * factor)
    fm, basis, K, f, share = lf.mesh, lf.basis, lf.K, lf.load_per_newton, lf.share  # 1 N of tension
    pts, nd = fm.points, basis.nodal_dofs
    edge = np.flatnonzero(np.isclose(pts[:, 0], g.length) & np.isclose(pts[:, 2], g.height))
    edge = edge[np.argsort(pts[edge, 1])]

    def hinge_angles(u: np.ndarray) -> np.ndarray:  # read at microradians (linear_compliance)
        cur = pts + MEASURE_SCALE * u[nd].T
        angles, _ = kabsch_angles(fm, cur, list(fm.nodes_of_element), list(fm.element_volume_weights))
        return np.degrees(np.diff(angles)) / MEASURE_SCALE

    free_hinges = hinge_angles(solve_clamped(K, f, lf.fixed, basis.doflocs))
    u_blocked = solve_clamped(K, f, np.union1d(lf.fixed, nd[2, edge]), basis.doflocs)
    hinge_blocked = hinge_angles(u_blocked)
    reaction = (K @ u_blocked - f)[nd[2, edge]]  # on the finger, along z: the stop pushes back
    edge_force = -reaction / share
    opening_rate = _cut_closing_rates(fm, g, u_blocked[nd].T)
    closing = opening_rate > 0
    gap = 2.0 * g.cut_half_width
    cut_closing = float(gap / opening_rate[closing].max()) if closing.any() else math.inf
    return BlockedTipLinear(
        force_per_newton=float(edge_force.sum()),
        edge_reactions_per_newton=tuple(float(x) for x in edge_force),
        hinge_deg_per_newton=tuple(float(x) for x in hinge_blocked),
        free_hinge_deg_per_newton=tuple(float(x) for x in free_hinges),
        cut_closing_tension=cut_closing,
        small_rotation_tension=float(SMALL_ROTATION_DEG / np.abs(hinge_blocked).max()),
        modulus_factor=factor, nodes=fm.n_nodes, wall_time_s=time.perf_counter() - t0)


def _cut_closing_rates(fm: FingerMesh, g: FingerGeometry, disp: np.ndarray) -> np.ndarray:
    """Per cut, how fast its opening at the grasping face closes [m per newton]: the x
    displacement of the distal element's proximal top corner less the proximal element's
    distal top corner, each averaged over the width (positive closes the cut)."""
    pts = fm.points
    top = np.isclose(pts[:, 2], g.height)
    rates = []
    for j in range(1, g.n_segments):
        x_cut = j * g.pitch
        prox = np.intersect1d(fm.nodes_of_element[j - 1], np.flatnonzero(top))
        dist = np.intersect1d(fm.nodes_of_element[j], np.flatnonzero(top))
        a = prox[np.isclose(pts[prox, 0], x_cut - g.cut_half_width)]
        b = dist[np.isclose(pts[dist, 0], x_cut + g.cut_half_width)]
        ua = np.average(disp[a, 0], weights=fm.node_weight[a])
        ub = np.average(disp[b, 0], weights=fm.node_weight[b])
        rates.append(ua - ub)
    return np.asarray(rates)


def blocked_tip_force_continuum(params: GripperParams | None, tensions, *,
                                mesh: MeshResolution | None = None,
                                max_hinge_deg: float = SMALL_ROTATION_DEG) -> np.ndarray:
    """The stop's reaction on the continuum body's blocked tip [N], one per tension [N].

    Linear in the tension (:func:`blocked_tip_linear`, solved once per newton and scaled).

    Raises:
        ValueError: a tension at which the linear model's largest hinge angle passes
            ``max_hinge_deg`` (default ``SMALL_ROTATION_DEG``), or at which a cut would close:
            there the finger is no longer near straight, and the linear model (no large
            rotations, no contact between cut faces) does not describe it.
    """
    t = np.asarray(tensions, dtype=float)
    lin = blocked_tip_linear(params, mesh)
    limit = min(lin.small_rotation_tension * max_hinge_deg / SMALL_ROTATION_DEG, lin.cut_closing_tension)
    if np.any(t < 0) or np.any(t > limit):
        raise ValueError(f"blocked tip, continuum: tensions must be in [0, {limit:.3g}] N, where the "
                         f"linear model's hinges stay under {max_hinge_deg:g}° and its cuts open "
                         f"({np.abs(lin.hinge_deg_per_newton).max():.0f}°/N blocked; the first cut "
                         f"closes at {lin.cut_closing_tension:.3g} N); got {t.max():g} N")
    return lin.force_per_newton * t


# -- obstacles ----------------------------------------------------------------------------------

@dataclass(frozen=True)
class Obstacle:
    """A rigid, world-fixed, frictionless obstacle, placed in the finger frame (x along the
    finger, z towards the grasping face); it spans the finger's width (y) and more.

    Attributes:
        kind: ``"plane"`` (the half-space z >= its centre's z, facing the finger) or
            ``"cylinder"`` (axis along y, the hinge axes).
        centre_xz: a point of the plane, or the cylinder's axis: x and z [m].
        radius: the cylinder's radius [m] (0 for a plane).
        only_element: in the hinge chain, the one element (1 = B1) the obstacle collides with
            (an explicit contact pair); None for every element.
    """

    kind: str
    centre_xz: tuple[float, float]
    radius: float = 0.0
    only_element: int | None = None


def tip_stop(params: GripperParams | None = None) -> Obstacle:
    """The blocked-tip stop: the half-space beyond the grasping face's plane (z >= height), in
    the chain touching the tip element only. The tip element curls into it, so it presses with
    its distal edge; the stop has no end along x that the edge could slide past.

    A plane rather than a box: a box's face against the tip element's distal edge (an edge on a
    face) let MuJoCo's convex collision take the tip's face normal, tilted 5° at 0.015 N, for
    the stop's, which moved the measured force by 2.6 % between 0.015 and 0.016 N; and a box of
    the tip element's length let the edge slide off its end past about 0.05 N. A plane's
    contacts always take its normal.
    """
    g = (params or GripperParams()).finger
    return Obstacle("plane", (g.length, g.height), only_element=g.n_segments)


def middle_cylinder(params: GripperParams | None, diameter: float, *, clearance: float = 0.0) -> Obstacle:
    """A cylinder of ``diameter`` [m] over the middle of the finger (x = L/2, the middle cut),
    resting on the two edges of that cut's opening on the grasping face (the corners of B3's
    and B4's grasping faces), ``clearance`` [m] off them."""
    g = (params or GripperParams()).finger
    r, w = 0.5 * diameter, g.cut_half_width
    if r <= w:
        raise ValueError(f"cylinder diameter: must exceed the cut's opening {2 * w:g} m, got {diameter!r}")
    return Obstacle("cylinder", (0.5 * g.length, g.height + math.sqrt((r + clearance) ** 2 - w * w)), r)


# -- the hinge chain ----------------------------------------------------------------------------

CHAIN_RAMP_TIME = 2.0  # s: the tension's ramp from 0
CHAIN_CHUNK_TIME = 1.0  # s: forces and angles are averaged over each chunk
CHAIN_MAX_TIME = 120.0  # s of simulated time
CHAIN_REST_DEG = 2e-3  # deg: at rest when no hinge's chunk mean moves more than this ...
CHAIN_REST_FORCE = 2e-3  # -: ... and the mean contact force by less than this fraction


@dataclass(frozen=True)
class ContactRest:
    """A finger at rest against an obstacle under a constant cable tension.

    Attributes:
        model: ``"chain"`` or ``"continuum"``.
        tension: the cable tension applied [N].
        cable_tension: the cable tension at rest (the chain's tendon-limit sensor; the
            continuum's applied value) [N].
        normal_force: the contacts' normal forces summed, the whole body's [N].
        resultant_force: magnitude of the contact forces' resultant in the bending plane [N].
        contact_elements: the elements (1 = B1) in contact; empty when none touches.
        element_forces: each one's normal force, the whole body's [N].
        contact_xz: each one's contact point, the normal-force-weighted mean of its contacts'
            points, finger frame x and z [m].
        element_angles_deg: each element's rotation from straight, B1 first [deg].
        penetration: the deepest contact's penetration [m].
        at_rest: the rest criterion was met within the time limit.
        sim_time: simulated time [s].
        wall_time_s: [s].
        force_fluctuation: standard deviation of the normal force over the averaging window
            (the chain's last chunk; 0 for the continuum, read once at rest) [N].
    """

    model: str
    tension: float
    cable_tension: float
    normal_force: float
    resultant_force: float
    contact_elements: tuple[int, ...]
    element_forces: tuple[float, ...]
    contact_xz: tuple[tuple[float, float], ...]
    element_angles_deg: tuple[float, ...]
    penetration: float
    at_rest: bool
    sim_time: float
    wall_time_s: float
    force_fluctuation: float = 0.0

    @property
    def hinge_angles_deg(self) -> tuple[float, ...]:
        """Each hinge's angle, B(j+1) against Bj [deg]."""
        return tuple(float(x) for x in np.diff(self.element_angles_deg))


def _contact_solref(timestep: float) -> list[float]:
    return [2.0 * timestep, 1.0]


CONTACT_SOLIMP = (0.99, 0.99, 1e-4, 0.5, 2.0)  # a stiff obstacle: 1 % of its penetration is soft


def chain_contact(params: GripperParams | None, tension: float, obstacle: Obstacle) -> ContactRest:
    """The hinge chain (:func:`build_bending_spec`) with ``obstacle`` in its scene and the cable
    at ``tension`` [N], run to rest (see the module docstring).

    The servo is off (actuation disabled) and the reel's slide joint is pulled with a constant
    generalised force equal to the tension, ramped over ``CHAIN_RAMP_TIME``; the rope's tendon
    limit carries it to the finger. Forces and angles are the means over a chunk of
    ``CHAIN_CHUNK_TIME`` (the contact force of a convex element's edge on a cylinder, from
    MuJoCo's convex collision, chatters step to step; its mean is what holds the finger), and
    the finger is at rest when two chunks' means agree (``CHAIN_REST_DEG``, ``CHAIN_REST_FORCE``;
    at most ``CHAIN_MAX_TIME``).
    """
    t0 = time.perf_counter()
    p = (params or GripperParams()).validate()
    g = p.finger
    spec = build_bending_spec(p)
    names = FingerNames("f0", g.n_segments)
    mount = np.array([0.0, 0.0, 0.1])
    cx, cz = obstacle.centre_xz
    solref, solimp = _contact_solref(p.sim.timestep), list(CONTACT_SOLIMP)
    contact = dict(condim=1, friction=[0, 0, 0], solref=solref, solimp=solimp)
    if obstacle.kind == "plane":  # its normal (local z) along world -y: solid on the +y side
        geom = spec.worldbody.add_geom(name="obstacle", type=mujoco.mjtGeom.mjGEOM_PLANE,
                                       size=[0.05, 0.05, 0.01], pos=[cx, cz, mount[2]],
                                       zaxis=[0, -1, 0], **contact)
    else:  # a cylinder's axis is its local z: world z, the hinge axes
        geom = spec.worldbody.add_geom(name="obstacle", type=mujoco.mjtGeom.mjGEOM_CYLINDER,
                                       size=[obstacle.radius, g.width, 0], pos=[cx, cz, mount[2]],
                                       **contact)
    geom.priority = 1
    if obstacle.only_element is not None:
        geom.contype = geom.conaffinity = 0
        spec.add_pair(geomname1="obstacle", geomname2=names.collision(obstacle.only_element),
                      condim=1, friction=[0, 0, 0, 0, 0], solref=solref, solimp=solimp)
    m = spec.compile()
    d = mujoco.MjData(m)
    m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_ACTUATION
    reel = m.joint(names.reel).dofadr[0]
    hq = np.array([m.joint(h).qposadr[0] for h in names.hinges])
    sensor = m.sensor(f"{names.cable}_tension").adr[0]
    gid = m.geom("obstacle").id
    seg_of_body = {m.body(b).id: k + 1 for k, b in enumerate(names.bodies)}
    chunk = int(round(CHAIN_CHUNK_TIME / m.opt.timestep))
    at_rest = False
    previous = None
    while d.time < CHAIN_MAX_TIME:
        forces, angles = np.zeros(chunk), np.zeros((chunk, len(hq)))
        sums = _ContactSums()
        for k in range(chunk):
            d.qfrc_applied[reel] = tension * min(1.0, d.time / CHAIN_RAMP_TIME)
            mujoco.mj_step(m, d)
            contacts = _chain_contacts(m, d, gid, mount, seg_of_body)
            forces[k] = sum(c[2] for c in contacts)
            angles[k] = d.qpos[hq]
            sums.add(contacts, 1.0 / chunk)
        check_stable(m, d, "contact check (chain)")
        mean_q, mean_f = np.degrees(angles.mean(axis=0)), float(forces.mean())
        if (previous is not None and d.time > CHAIN_RAMP_TIME + CHAIN_CHUNK_TIME
                and np.abs(mean_q - previous[0]).max() < CHAIN_REST_DEG
                and abs(mean_f - previous[1]) <= CHAIN_REST_FORCE * max(abs(mean_f), 1e-12)):
            at_rest = True
            break
        previous = (mean_q, mean_f)
    return sums.rest("chain", tension, float(d.sensordata[sensor]),
                     np.concatenate([[0.0], np.cumsum(mean_q)]), at_rest, float(d.time),
                     time.perf_counter() - t0, force_fluctuation=float(forces.std()))


def _chain_contacts(m: mujoco.MjModel, d: mujoco.MjData, gid: int, mount: np.ndarray,
                    seg_of_body: dict[int, int]) -> list:
    """The obstacle's contacts in the chain: (finger-frame point, element, normal force, force
    vector onto the obstacle in the finger frame, penetration) each. The mount's frame: world x
    is finger x, world y finger z, world z 0.1 m less finger y."""
    out = []
    f6 = np.zeros(6)
    for i in range(d.ncon):
        c = d.contact[i]
        if gid not in (c.geom1, c.geom2):
            continue
        other = c.geom2 if c.geom1 == gid else c.geom1
        mujoco.mj_contactForce(m, d, i, f6)
        normal = _TO_FINGER @ (c.frame[:3] * (1.0 if c.geom2 == gid else -1.0))  # onto the obstacle
        out.append((_TO_FINGER @ (c.pos - mount), seg_of_body.get(int(m.geom_bodyid[other]), 0),
                    float(f6[0]), f6[0] * normal, -float(c.dist)))
    return out


_TO_FINGER = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])  # world -> finger frame (rows)


class _ContactSums:
    """Contacts (finger-frame point, element, normal force, force vector onto the obstacle,
    penetration), summed per element with weights: a mean over steps, or a scale (2 for the
    symmetric half mesh, whose mirror half carries as much)."""

    def __init__(self) -> None:
        self.force: dict[int, float] = {}
        self.moment: dict[int, np.ndarray] = {}
        self.vector = np.zeros(3)
        self.penetration = 0.0

    def add(self, contacts: list, weight: float) -> None:
        for point, element, normal, vector, depth in contacts:
            self.force[element] = self.force.get(element, 0.0) + weight * normal
            self.moment[element] = self.moment.get(element, np.zeros(3)) + weight * normal * point
            self.vector += weight * vector
            self.penetration = max(self.penetration, depth)

    def rest(self, model: str, tension: float, cable: float, angles_deg: np.ndarray, at_rest: bool,
             sim_time: float, wall: float, force_fluctuation: float = 0.0) -> ContactRest:
        touching = sorted(e for e, f in self.force.items() if f > 0)
        xz = [self.moment[e][[0, 2]] / self.force[e] for e in touching]
        return ContactRest(
            model=model, tension=float(tension), cable_tension=cable,
            normal_force=float(sum(self.force.values())),
            resultant_force=float(math.hypot(self.vector[0], self.vector[2])),
            contact_elements=tuple(int(e) for e in touching),
            element_forces=tuple(float(self.force[e]) for e in touching),
            contact_xz=tuple((float(x), float(z)) for x, z in xz),
            element_angles_deg=tuple(float(a) for a in angles_deg),
            penetration=float(self.penetration), at_rest=at_rest, sim_time=sim_time,
            wall_time_s=wall, force_fluctuation=force_fluctuation)


def blocked_tip_force_chain(params: GripperParams | None, tensions) -> np.ndarray:
    """The stop's reaction on the hinge chain's blocked tip at rest [N], one per tension [N]
    (:func:`chain_contact` against :func:`tip_stop`, about a second each). Past about 0.04 N
    on the default design the chain's proximal hinges reach their extension stops and the tip
    slides along the stop as the finger curls (``docs/calibration.md``, "The finger in
    contact")."""
    stop = tip_stop(params)
    return np.array([chain_contact(params, float(t), stop).normal_force for t in tensions])


def cylinder_contact_chain(params: GripperParams | None, diameter: float, tension: float) -> ContactRest:
    """The hinge chain closing on :func:`middle_cylinder` of ``diameter`` [m] at ``tension``
    [N], at rest."""
    return chain_contact(params, tension, middle_cylinder(params, diameter))


# -- the continuum body (MuJoCo flex) ----------------------------------------------------------

FLEX_RAMP_TIME = 0.5  # s: the tension's ramp from 0 (5 ms steps, first mode critically damped)
FLEX_MAX_TIME = 10.0  # s of simulated time
# deg: at rest when the bending moves less than this over half a second: a quarter of the
# calibration's REST_TOL_DEG, as the contact forces here are read at a few hundredths of a newton
FLEX_REST_TOL_DEG = 0.005
# The flex's contact: stiffness and damping given directly (MuJoCo's negative solref, per unit
# of the contact's effective mass). The time-constant form at two 5 ms steps let the light
# edge nodes sink 46 µm into the stop at 0.005 N (0.6 % of the blocked force); this one, 1 µm.
FLEX_CONTACT_SOLREF = (-1.0e6, -2.0e3)


def _obstacle_xml(p: GripperParams, obstacle: Obstacle) -> str:
    """``obstacle`` as a world geom, frictionless and stiff, moved off the body by the flex's
    collision radius, which inflates its surface."""
    cx, cz = obstacle.centre_xz
    solref = " ".join(f"{v:g}" for v in FLEX_CONTACT_SOLREF)
    solimp = " ".join(f"{v:g}" for v in CONTACT_SOLIMP)
    contact = f'condim="1" priority="1" friction="0 0 0" solref="{solref}" solimp="{solimp}"'
    if obstacle.kind == "plane":
        return (f'<geom name="obstacle" type="plane" size="0.05 0.05 0.01" pos="{cx:.9g} 0 '
                f'{cz + FLEX_RADIUS:.9g}" zaxis="0 0 -1" {contact}/>')
    return (f'<geom name="obstacle" type="cylinder" size="{obstacle.radius:.9g} {p.finger.width:.9g}" '
            f'pos="{cx:.9g} 0 {cz:.9g}" zaxis="0 1 0" {contact}/>')


class ContactReference(ReferenceFinger):
    """The continuum reference (:class:`ReferenceFinger`: mesh, lumped masses, damping,
    symmetry plane, cable) with ``obstacle`` in its scene and contact on between the two. The
    cut faces still do not touch each other: tensions must keep the cuts open."""

    def __init__(self, params: GripperParams | None, config: ReferenceConfig, obstacle: Obstacle):
        self.obstacle = obstacle
        super().__init__(params, config)

    def _scene_xml(self, *, world: str = "", contact: str = "") -> str:
        return super()._scene_xml(world=world + "\n    " + _obstacle_xml(self.p, self.obstacle),
                                  contact='contype="1" conaffinity="1" selfcollide="none" condim="1"')


def continuum_contact(params: GripperParams | None, tension: float, obstacle: Obstacle, *,
                      modulus_factor: float | None = None, mesh: MeshResolution | None = None,
                      rest_tol_deg: float | None = None) -> ContactRest:
    """The continuum reference (MuJoCo flex, :class:`ContactReference`) with ``obstacle`` in
    its scene and the cable at ``tension`` [N], relaxed to rest: the relaxation of
    ``gripper.references.continuum_checks`` (5 ms implicit steps, first mode critically
    damped), the tension ramped over ``FLEX_RAMP_TIME``, at rest when the bending moves less
    than ``rest_tol_deg`` over half a second (default ``FLEX_REST_TOL_DEG``; at most
    ``FLEX_MAX_TIME``). The contact forces of the half mesh are doubled. ``modulus_factor``:
    default :func:`committed_modulus_factor`.

    Raises:
        ValueError: a cut closed (the body has no contact between cut faces).
        SimulationUnstable: MuJoCo warned or the state became non-finite.
    """
    from gripper.references.continuum import relaxation_config
    from gripper.references.relaxation import relax_to_rest

    t0 = time.perf_counter()
    factor = committed_modulus_factor() if modulus_factor is None else float(modulus_factor)
    cfg = relaxation_config(ReferenceConfig(mesh=mesh or MeshResolution(), modulus_factor=factor))
    ref = ContactReference(params, cfg, obstacle)
    g = ref.p.finger
    at_rest = True
    try:
        tol = FLEX_REST_TOL_DEG if rest_tol_deg is None else rest_tol_deg
        angles, _, _ = relax_to_rest(ref, tension, ramp_time=FLEX_RAMP_TIME, rest_tol_deg=tol,
                                     max_time=FLEX_MAX_TIME, what="contact check (continuum)")
    except SimulationUnstable as err:
        if "not at rest" not in str(err):
            raise
        at_rest = False
        angles, _ = ref.measure(ref.node_positions())
    hinge = np.degrees(np.diff(angles))
    if hinge.max() > g.closure_angle_deg:
        raise ValueError(f"contact check (continuum): at {tension:g} N a hinge turned {hinge.max():.1f}°, past "
                         f"the cut's closure {g.closure_angle_deg:.1f}°; the body has no contact between "
                         f"cut faces: use a smaller tension")
    m, d = ref.model, ref.data
    geom = m.geom("obstacle").id
    tets = ref.mesh.tets
    members = [set(nodes.tolist()) for nodes in ref.mesh.nodes_of_element]
    contacts = []
    for i in range(d.ncon):
        c = d.contact[i]
        if geom not in (c.geom[0], c.geom[1]):
            continue
        side = 1 if c.geom[0] == geom else 0  # the flex's side: a vertex or an element of it
        nodes = ({int(c.vert[side])} if c.vert[side] >= 0
                 else set(tets[c.elem[side]].tolist()) if c.elem[side] >= 0 else set())
        element = next((e + 1 for e, mem in enumerate(members) if nodes and nodes <= mem), 0)
        f6 = np.zeros(6)
        mujoco.mj_contactForce(m, d, i, f6)
        normal = c.frame[:3] * (-1.0 if side == 1 else 1.0)  # onto the obstacle (frame: geom 1 to 2)
        contacts.append((c.pos.copy(), element, f6[0], f6[0] * normal, -c.dist))
    sums = _ContactSums()
    sums.add(contacts, 2.0 if ref.mesh.symmetric else 1.0)
    return sums.rest("continuum", tension, tension, np.degrees(angles - angles[0]), at_rest, float(d.time),
                     time.perf_counter() - t0)


def cylinder_contact_continuum(params: GripperParams | None, diameter: float, tension: float,
                               **kwargs) -> ContactRest:
    """The continuum reference closing on :func:`middle_cylinder` of ``diameter`` [m] at
    ``tension`` [N], at rest (:func:`continuum_contact`; about 2-4 minutes on one core)."""
    return continuum_contact(params, tension, middle_cylinder(params, diameter, clearance=FLEX_RADIUS), **kwargs)
