"""Speed figures (medians of several runs): the 2 s bending test, and the 4-finger gripper with
a rigid block (scripted descend-close-lift, 3 s simulated, servos to 2 rad) on one core, at the
model's default 1 ms step and at the grasp trials' 2 ms step (discrete integrator, see
GraspProtocol.timestep), and the benchmark's own block trials (servos to stall).

Run: .venv/bin/python scripts/bench_speed.py [--repeats 5] [--knobs]

``--knobs`` times, side by side with the shipped model, the simulation options and model cuts
tried against the 50x goal (see the README, "Speed").
"""

import argparse
import statistics
import time

import mujoco
import numpy as np
from mujoco import rollout

from gripper.core.params import GripperParams
from gripper.experiments.bending import BendingConfig, run_bending_test
from gripper.experiments.protocol import GraspProtocol
from gripper.experiments.smoke import open_loop_grasp_controls
from gripper.experiments.trial import run_trial
from gripper.model.builders import build_scene_spec
from gripper.sim.scene import grasp_scene_spec


def _scene(p: GripperParams, discrete: bool) -> mujoco.MjModel:
    # discrete: as the grasp trials build it, with the scene's default block
    return (grasp_scene_spec(p, with_object=True) if discrete else build_scene_spec(p)).compile()


def grasp_rollout(p: GripperParams, sim_time: float = 3.0, discrete: bool = False) -> float:
    """Real-time factor of the scripted grasp with ``mj_step`` called from Python."""
    m = _scene(p, discrete)
    d = mujoco.MjData(m)
    u = open_loop_grasp_controls(p, m, sim_time)
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
    u = open_loop_grasp_controls(p, m, sim_time)[None]
    spec_full = mujoco.mjtState.mjSTATE_FULLPHYSICS
    s0 = np.empty((1, mujoco.mj_stateSize(m, spec_full)))
    mujoco.mj_getState(m, d, s0[0], spec_full)
    with rollout.Rollout(nthread=0) as r:
        t0 = time.perf_counter()
        r.rollout([m], [d], s0, u, control_spec=int(mujoco.mjtState.mjSTATE_CTRL))
        wall = time.perf_counter() - t0
    return sim_time / wall


PHASES = ("STEP", "POS_KINEMATICS", "POS_INERTIA", "COL_BROAD", "COL_NARROW", "POS_MAKE",
          "VELOCITY", "ACTUATION", "CONSTRAINT", "ADVANCE")


def phase_breakdown(p: GripperParams) -> None:
    """Where a step of the scripted grasp (2 ms, discrete) goes: MuJoCo's own timers, per step."""
    m = _scene(p, discrete=True)
    d = mujoco.MjData(m)
    u = open_loop_grasp_controls(p, m, 3.0)
    ncon = nefc = iters = 0
    for row in u:
        d.ctrl[:] = row
        mujoco.mj_step(m, d)
        ncon, nefc, iters = ncon + d.ncon, nefc + d.nefc, iters + int(d.solver_niter[0])
    n = len(u)
    parts = []
    for name in PHASES:
        t = d.timer[int(getattr(mujoco.mjtTimer, f"mjTIMER_{name}"))]
        parts.append(f"{name.lower()} {1e6 * t.duration / max(t.number, 1):.1f}")
    print(f"  per step (us): {', '.join(parts)}; mean {ncon / n:.1f} contacts, {nefc / n:.1f} "
          f"constraint rows, {iters / n:.2f} solver iterations")


def _variant(p: GripperParams, change) -> mujoco.MjModel:
    spec = grasp_scene_spec(p, with_object=True)
    change(spec)
    return spec.compile()


def _drop_visual_geoms(spec: mujoco.MjSpec) -> None:
    for g in list(spec.geoms):
        if g.name.endswith("_visual"):
            spec.delete(g)


def _exclude_same_finger(spec: mujoco.MjSpec) -> None:
    names = [b.name for b in spec.bodies if "_seg" in b.name]
    for a in names:
        for b in names:
            fa, fb = a.split("_seg"), b.split("_seg")
            if a < b and fa[0] == fb[0] and abs(int(fa[1]) - int(fb[1])) >= 2:
                spec.add_exclude(bodyname1=a, bodyname2=b)


def _islands_on(spec: mujoco.MjSpec) -> None:
    spec.option.disableflags &= ~int(mujoco.mjtDisableBit.mjDSBL_ISLAND)


def _set(attr, value):
    def change(spec):
        setattr(spec.option, attr, value)
    return change


def _flag(bit):
    def change(spec):
        spec.option.disableflags |= int(bit)
    return change


# Simulation options and model cuts tried against the 50x goal, each measured side by side with
# the shipped model in one run (none is shipped: see the README, "Speed").
KNOBS = {
    "pyramidal friction cones": _set("cone", mujoco.mjtCone.mjCONE_PYRAMIDAL),
    "dense constraint Jacobian": _set("jacobian", mujoco.mjtJacobian.mjJAC_DENSE),
    "CG solver": _set("solver", mujoco.mjtSolver.mjSOL_CG),
    "solver tolerance 1e-6": _set("tolerance", 1e-6),
    "no multi-point CCD": _flag(mujoco.mjtDisableBit.mjDSBL_MULTICCD),
    "constraint islands on": _islands_on,
    "no sensors (not allowed: the issue asks for them)": _flag(mujoco.mjtDisableBit.mjDSBL_SENSOR),
    "no visual geoms": _drop_visual_geoms,
    "no contact within a finger beyond neighbours": _exclude_same_finger,
}


_CUTS = [KNOBS[k] for k in list(KNOBS)[-3:]]
KNOBS["the last three together"] = lambda spec: [cut(spec) for cut in _CUTS]


def knob_sweep(p: GripperParams, repeats: int) -> None:
    models = {"shipped": _variant(p, lambda spec: None)}
    models.update({k: _variant(p, f) for k, f in KNOBS.items()})
    runs: dict[str, list[float]] = {k: [] for k in models}
    for _ in range(repeats):  # interleaved, so drifts of the machine hit every variant alike
        for k, m in models.items():
            d = mujoco.MjData(m)
            u = open_loop_grasp_controls(p, m, 3.0)
            t0 = time.perf_counter()
            for row in u:
                d.ctrl[:] = row
                mujoco.mj_step(m, d)
            runs[k].append(3.0 / (time.perf_counter() - t0))
    base = statistics.median(runs["shipped"])
    for k, xs in runs.items():
        print(f"  {k}: median {statistics.median(xs):.1f}x real time, "
              f"{statistics.median(xs) / base:.3f} of the shipped model")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--knobs", action="store_true",
                    help="also time simulation options and model cuts against the shipped model")
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
    phase_breakdown(p2)
    if args.knobs:
        print("  options and cuts, scripted grasp at 2 ms, mj_step:")
        knob_sweep(p2, args.repeats)
    # The benchmark's own block trial (8.86 s simulated: settle, approach, close to the servo's
    # stall, lift, hold, shake), wall time including the trial's chunked checks. Closed at
    # stall, the fingers curl onto themselves and the palm: about 100 contacts (multi-point
    # mesh contacts) against about 17 in the scripted grasp above, so it runs slower.
    trial = [run_trial("block", seed=0, index=i) for i in range(args.repeats)]
    rt5 = [r["sim_time_s"] / r["wall_time_s"] for r in trial]
    print(f"  benchmark block trials (index 0-{args.repeats - 1}, closed to stall): median "
          f"{statistics.median(rt5):.1f}x real time (runs: {', '.join(f'{x:.1f}' for x in rt5)})")
    # Not the default: same grasp outcomes, but peak forces 13-18 % above the 0.5 ms values
    # (GraspProtocol.timestep).
    p3 = p.replace(sim=p.sim.replace(timestep=0.003))
    rt4 = [grasp_rollout_batch(p3, discrete=True) for _ in range(args.repeats)]
    print(f"  at 3 ms through mujoco.rollout (not the default, see GraspProtocol.timestep): median "
          f"{statistics.median(rt4):.1f}x real time (runs: {', '.join(f'{x:.1f}' for x in rt4)})")


if __name__ == "__main__":
    main()
