"""Open-loop stepping in chunks with ``mujoco.rollout``, with stability checks between chunks."""

from __future__ import annotations

import mujoco
import numpy as np
from mujoco import rollout

from gripper.sim.stability import SimulationUnstable, check_stable

STATE_SPEC = mujoco.mjtState.mjSTATE_FULLPHYSICS


CTRL_SPEC = int(mujoco.mjtState.mjSTATE_CTRL)


class ChunkStepper:
    """Steps one ``MjData`` in open-loop chunks with ``mujoco.rollout`` (no thread pool).

    The rollout object and its output buffers are kept for the whole trial and the wrapper's
    shape checks are skipped (the buffers are built here with the right shapes), so the cost
    per chunk beyond the physics is a few microseconds.
    """

    def __init__(self, m: mujoco.MjModel, d: mujoco.MjData):
        self.m, self.d = m, d
        self.roll = rollout.Rollout(nthread=0)
        self.state0 = np.empty((1, mujoco.mj_stateSize(m, STATE_SPEC)))
        mujoco.mj_getState(m, d, self.state0[0], STATE_SPEC)
        self.warm0 = np.empty((1, m.nv))
        self._out: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        self.last_states = self.state0

    def step(self, u: np.ndarray) -> np.ndarray:
        """Apply the controls ``u`` (n, nu) for n steps; return the sensor data (n, nsensordata).

        ``d`` must not be changed between calls: each chunk starts from the previous chunk's
        last state row (the same numbers ``mj_getState`` would read from ``d``).
        """
        n = len(u)
        if n not in self._out:
            self._out[n] = (np.empty((1, n, self.state0.shape[1])), np.empty((1, n, self.m.nsensordata)))
        state, sens = self._out[n]
        self.last_states = state[0]
        # the solver's warm start is not part of the physics state: pass it on so that the
        # result does not depend on where chunks are cut (bitwise equal to plain mj_step)
        self.warm0[0] = self.d.qacc_warmstart
        self.roll.rollout([self.m], [self.d], self.state0, np.ascontiguousarray(u[None]),
                          control_spec=CTRL_SPEC, skip_checks=True, nstep=n,
                          initial_warmstart=self.warm0, state=state, sensordata=sens)
        self.state0[0] = state[0, -1]  # the next chunk's start
        return sens[0]

    def finite(self) -> bool:
        """Whether the last chunk's final state (time, qpos, qvel, act, ...) is finite."""
        return bool(np.isfinite(self.last_states[-1]).all())

    def close(self) -> None:
        self.roll.close()


def run_phase(stepper, probe, rec, ctrl_fn, duration, chunk, what, on_chunk=None) -> None:
    """Step ``duration`` seconds with controls ``ctrl_fn(t_phase) -> (n, nu)`` in chunks."""
    m, d = stepper.m, stepper.d
    n_total = int(round(duration / m.opt.timestep))
    done = 0
    while done < n_total:
        n = min(chunk, n_total - done)
        t = (done + np.arange(n)) * m.opt.timestep
        sens = stepper.step(ctrl_fn(t))
        done += n
        if not stepper.finite() or d.warning.number.any():
            check_stable(m, d, what)  # raises, naming the warnings
            raise SimulationUnstable(f"{what}: non-finite state at t = {d.time:.4f} s")
        rec.add(sens, d, stepper.last_states)
        if rec.frame_sink is not None:
            rec.frame_sink.add(what, stepper.last_states, sens)
        if on_chunk is not None and on_chunk(d):
            return
