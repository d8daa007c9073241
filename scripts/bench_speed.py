"""Speed figures (medians of several runs): the 2 s bending test, and the 4-finger gripper with
a rigid block (scripted descend-close-lift, 3 s simulated, servos to 2 rad) on one core, at the
model's default 1 ms step and at the grasp trials' 2 ms step (discrete integrator, see
GraspProtocol.timestep), and the benchmark's own block trials (servos to stall).

Run: .venv/bin/python scripts/bench_speed.py [--repeats 5]
"""

import argparse
import statistics
import time

import mujoco
import numpy as np
from mujoco import rollout

from gripper.bending import BendingConfig, run_bending_test
from gripper.model import build_scene_spec
from gripper.params import GripperParams
from gripper.protocol import GraspProtocol
from gripper.trial import run_trial


def _scene(p: GripperParams, discrete: bool) -> mujoco.MjModel:
    spec = build_scene_spec(p)
    if discrete:  # as the grasp trials build it (gripper.trial.build_grasp_scene)
        spec.option.integrator = mujoco.mjtIntegrator.mjINT_DISCRETE
    return spec.compile()


def _scripted_controls(p: GripperParams, m: mujoco.MjModel, sim_time: float) -> np.ndarray:
    """Descend for 1 s, close the servos to 2 rad over 0.5 s, lift by 0.1 m at 2.2 s: (n, nu)."""
    n = int(round(sim_time / m.opt.timestep))
    t = np.arange(n) * m.opt.timestep
    u = np.zeros((n, m.nu))
    u[:, : p.layout.n_fingers] = (np.clip((t - 1.0) * 2.0, 0.0, 1.0) * 2.0)[:, None]
    u[:, m.actuator("lift_z").id] = -0.12 * np.minimum(1.0, t) + np.where(t > 2.2, 0.1, 0.0)
    return u


def grasp_rollout(p: GripperParams, sim_time: float = 3.0, discrete: bool = False) -> float:
    """Real-time factor of the scripted grasp with ``mj_step`` called from Python."""
    m = _scene(p, discrete)
    d = mujoco.MjData(m)
    u = _scripted_controls(p, m, sim_time)
    t0 = time.perf_counter()
    for row in u:
        d.ctrl[:] = row
        mujoco.mj_step(m, d)
    return sim_time / (time.perf_counter() - t0)


def grasp_rollout_batch(p: GripperParams, sim_time: float = 3.0, discrete: bool = False) -> float:
    """The same scripted controls, stepped by ``mujoco.rollout`` on this thread in one call (the
    path the grasp trials and environments take): no Python between steps."""
    m = _scene(p, discrete)
    d = mujoco.MjData(m)
    u = _scripted_controls(p, m, sim_time)[None]
    spec_full = mujoco.mjtState.mjSTATE_FULLPHYSICS
    s0 = np.empty((1, mujoco.mj_stateSize(m, spec_full)))
    mujoco.mj_getState(m, d, s0[0], spec_full)
    with rollout.Rollout(nthread=0) as r:
        t0 = time.perf_counter()
        r.rollout([m], [d], s0, u, control_spec=int(mujoco.mjtState.mjSTATE_CTRL))
        wall = time.perf_counter() - t0
    return sim_time / wall


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()
    bend = [run_bending_test(BendingConfig()).wall_time_s for _ in range(args.repeats)]
    print(f"bending test, 2 s at 5e-4 s: median wall {statistics.median(bend):.4f} s "
          f"(runs: {', '.join(f'{x:.4f}' for x in bend)})")
    p = GripperParams()
    rt = [grasp_rollout(p) for _ in range(args.repeats)]
    print(f"4-finger gripper + rigid block, model default dt {p.sim.timestep:g} s: median "
          f"{statistics.median(rt):.1f}x real time (runs: {', '.join(f'{x:.1f}' for x in rt)})")
    dt = GraspProtocol().timestep
    p2 = p.replace(sim=p.sim.replace(timestep=dt))
    rt2 = [grasp_rollout(p2, discrete=True) for _ in range(args.repeats)]
    print(f"4-finger gripper + rigid block, grasp-trial dt {dt:g} s (discrete integrator): median "
          f"{statistics.median(rt2):.1f}x real time (runs: {', '.join(f'{x:.1f}' for x in rt2)})")
    rt3 = [grasp_rollout_batch(p2, discrete=True) for _ in range(args.repeats)]
    print(f"  the same through mujoco.rollout (one thread, no Python between steps): median "
          f"{statistics.median(rt3):.1f}x real time (runs: {', '.join(f'{x:.1f}' for x in rt3)})")
    # The benchmark's own block trial (8.86 s simulated: settle, approach, close to the servo's
    # stall, lift, hold, shake), wall time including the trial's chunked checks. Closed at
    # stall, the fingers curl onto themselves and the palm: about 100 contacts (multi-point
    # mesh contacts) against about 17 in the scripted grasp above, so it runs slower.
    trial = [run_trial("block", seed=0, index=i) for i in range(args.repeats)]
    rt5 = [r["sim_time_s"] / r["wall_time_s"] for r in trial]
    print(f"  benchmark block trials (index 0-{args.repeats - 1}, closed to stall): median "
          f"{statistics.median(rt5):.1f}x real time (runs: {', '.join(f'{x:.1f}' for x in rt5)})")
    # Not the default: same grasp outcomes, but peak forces 11-24 % above the 0.5 ms values
    # (GraspProtocol.timestep).
    p3 = p.replace(sim=p.sim.replace(timestep=0.003))
    rt4 = [grasp_rollout_batch(p3, discrete=True) for _ in range(args.repeats)]
    print(f"  at 3 ms through mujoco.rollout (not the default, see GraspProtocol.timestep): median "
          f"{statistics.median(rt4):.1f}x real time (runs: {', '.join(f'{x:.1f}' for x in rt4)})")


if __name__ == "__main__":
    main()
