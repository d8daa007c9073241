"""Probes: indices into a grasp scene for what trials read (object pose, finger contact
forces, the drive's effort: cable tension, chamber pressure, ...; flex edge strain), and the
peaks a trial records."""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from gripper.drives import Drive
from gripper.objects.grasp_object import GraspObject
from gripper.objects.kinds import CONTENTS_BODY, OBJECT_BODY
from gripper.parts.names import finger_name


def geom_normal_force(m: mujoco.MjModel, d: mujoco.MjData, geom: int) -> float:
    """Sum of the normal forces of every contact that involves geom ``geom`` [N]."""
    force = np.zeros(6)
    total = 0.0
    for i in range(d.ncon):
        if geom in d.contact.geom[i]:
            mujoco.mj_contactForce(m, d, i, force)
            total += force[0]
    return total


@dataclass
class ObjectProbe:
    """Indices into the model for the quantities the trial reads."""

    model: mujoco.MjModel
    obj: GraspObject
    n_fingers: int
    drive: Drive

    def __post_init__(self):
        m = self.model
        # each finger's drive actuator (a cable's servo, a chamber's regulator, ...)
        self.actuators = self.drive.actuator_ids(m)
        self.lift_x = m.actuator("lift_x").id
        self.lift_z = m.actuator("lift_z").id
        self.palm = m.body("palm").id
        # finger index of every geom (-1: not a finger element), object geoms
        self.geom_finger = np.full(m.ngeom + 1, -1)  # last entry: index -1 (flex side)
        for g in range(m.ngeom):
            name = m.body(m.geom_bodyid[g]).name
            for k in range(self.n_fingers):
                if name.startswith(f"{finger_name(k)}_seg"):
                    self.geom_finger[g] = k
        self.object_geom = np.zeros(m.ngeom + 1, dtype=bool)
        for g in range(m.ngeom):
            name = m.body(m.geom_bodyid[g]).name
            if name == OBJECT_BODY or name.startswith(CONTENTS_BODY):
                self.object_geom[g] = True
        # each finger's true effort (cable tension [N], chamber pressure [Pa], ...): sensor / divisor
        self.effort_adr, self.effort_divisor = self.drive.effort_sensors(m)
        self.flex = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_FLEX, OBJECT_BODY) if self.obj.is_flex else -1
        if self.flex >= 0:
            a, n = m.flex_vertadr[self.flex], m.flex_vertnum[self.flex]
            self.vert = slice(a, a + n)
            a, n = m.flex_edgeadr[self.flex], m.flex_edgenum[self.flex]
            self.edge_verts = m.flex_edge[a:a + n]  # local vertex pairs
            d0 = mujoco.MjData(m)
            mujoco.mj_kinematics(m, d0)
            mujoco.mj_flex(m, d0)
            self.rest_verts = d0.flexvert_xpos[self.vert].copy()
            self.edge_length0 = self._edge_lengths(self.rest_verts)
        self.q_adr = None  # no per-step strain map (set for objects whose damage is a strain)
        if self.flex >= 0 and self.obj.reads_strain:
            self._vertex_map(m, d0)
        tracked = self.obj.object_kind.tracked_body  # the body whose origin is the object's position
        self.body = m.body(tracked).id if tracked is not None else -1
        bodies = [self.body] if self.body >= 0 else []
        if self.flex >= 0:
            bodies += sorted({int(b) for b in m.flex_nodebodyid[
                m.flex_nodeadr[self.flex]:m.flex_nodeadr[self.flex] + m.flex_nodenum[self.flex]]}
                if m.flex_interp[self.flex] else
                {int(b) for b in m.flex_vertbodyid[self.vert]})
        self.object_bodies = np.array([b for b in bodies if b > 0])

    def object_pos(self, d: mujoco.MjData) -> np.ndarray:
        """Reference point of the object [m]: body origin (rigid, bag contents) or flex centroid."""
        if self.body >= 0:
            return d.xpos[self.body].copy()
        return d.flexvert_xpos[self.vert].mean(axis=0)

    def finger_forces(self, d: mujoco.MjData) -> np.ndarray:
        """Normal contact force between each finger and the object [N] (all element faces)."""
        out = np.zeros(self.n_fingers)
        if d.ncon == 0:
            return out
        c = d.contact
        geom, flex, adr = c.geom, c.flex, c.efc_address
        obj = self.object_geom[geom].any(axis=1)
        if self.flex >= 0:
            obj |= (flex == self.flex).any(axis=1)
        fing = np.max(self.geom_finger[geom], axis=1)
        use = obj & (fing >= 0) & (adr >= 0)
        if use.any():
            np.add.at(out, fing[use], d.efc_force[adr[use]])
        return out

    def _vertex_map(self, m: mujoco.MjModel, d0: mujoco.MjData) -> None:
        """The flex's vertex positions as a linear map of its nodes' slide-joint coordinates,
        x = x0 + J (q - q0), so that the edge strain can be read at every step of a chunk from
        the rollout's states. J is probed column by column (exact: slide joints, and
        interpolation weights that are linear in the nodes)."""
        f = self.flex
        nodes = (m.flex_nodebodyid[m.flex_nodeadr[f]:m.flex_nodeadr[f] + m.flex_nodenum[f]]
                 if m.flex_interp[f] else m.flex_vertbodyid[self.vert])
        joints = [j for b in sorted({int(b) for b in nodes})
                  for j in range(m.body_jntadr[b], m.body_jntadr[b] + m.body_jntnum[b])]
        if not joints or any(m.jnt_type[j] != mujoco.mjtJoint.mjJNT_SLIDE for j in joints):
            return  # not a linear map: strain only at chunk ends
        self.q_adr = m.jnt_qposadr[joints]
        self.q0 = d0.qpos[self.q_adr].copy()
        cols = []
        for k in self.q_adr:
            d0.qpos[k] += 1.0e-3
            mujoco.mj_kinematics(m, d0)
            mujoco.mj_flex(m, d0)
            cols.append(((d0.flexvert_xpos[self.vert] - self.rest_verts) / 1.0e-3).ravel())
            d0.qpos[k] -= 1.0e-3
        jac = np.array(cols).T
        jac[np.abs(jac) < 1e-9] = 0.0
        from scipy.sparse import csr_matrix
        self.jac = csr_matrix(jac)
        # state rows start with the time, then qpos (mjSTATE_FULLPHYSICS)
        self.q_col = mujoco.mj_stateSize(m, mujoco.mjtState.mjSTATE_TIME) + self.q_adr

    def edge_strain_steps(self, states: np.ndarray) -> float:
        """Largest tensile edge strain over the rollout ``states`` (n, nstate) [-]."""
        dq = states[:, self.q_col] - self.q0
        x = self.rest_verts.ravel() + (self.jac @ dq.T).T
        x = x.reshape(len(states), -1, 3)
        e = x[:, self.edge_verts[:, 0]] - x[:, self.edge_verts[:, 1]]
        return float(np.max(np.linalg.norm(e, axis=2) / self.edge_length0 - 1.0))

    def _edge_lengths(self, x: np.ndarray) -> np.ndarray:
        return np.linalg.norm(x[self.edge_verts[:, 0]] - x[self.edge_verts[:, 1]], axis=1)

    def edge_strain(self, d: mujoco.MjData) -> float:
        """Largest tensile strain of the object flex's edges against the rest shape [-]."""
        if self.flex < 0:
            return 0.0
        x = d.flexvert_xpos[self.vert]
        return float(np.max(self._edge_lengths(x) / self.edge_length0 - 1.0))


class PeakRecorder:
    """Accumulates the trial's peaks from the per-step sensor arrays and chunk-end checks."""

    def __init__(self, probe: ObjectProbe):
        self.probe = probe
        self.peak_total = 0.0
        self.peak_finger = np.zeros(probe.n_fingers)
        self.peak_effort = 0.0
        self.peak_strain = 0.0
        self.frame_sink = None  # optional: receives (phase, states, sensordata) of every chunk

    def add(self, sensordata: np.ndarray, d: mujoco.MjData, states: np.ndarray | None = None) -> None:
        """Fold in one chunk: ``sensordata`` and ``states`` (the rollout's rows, one per step) and
        ``d`` at the chunk's end. Contact forces are read at the chunk's end only; flex strain
        at every step where ``states`` is given (see :meth:`ObjectProbe.edge_strain_steps`)."""
        per_finger = self.probe.finger_forces(d)
        self.peak_finger = np.maximum(self.peak_finger, per_finger)
        self.peak_total = max(self.peak_total, float(per_finger.sum()))
        effort = sensordata[:, self.probe.effort_adr] / self.probe.effort_divisor
        self.peak_effort = max(self.peak_effort, float(effort.max()))
        if not self.probe.obj.reads_strain:
            return
        if states is not None and self.probe.q_adr is not None:
            self.peak_strain = max(self.peak_strain, self.probe.edge_strain_steps(states))
        else:
            self.peak_strain = max(self.peak_strain, self.probe.edge_strain(d))
