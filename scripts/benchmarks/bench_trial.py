"""Trial-runner overhead against plain ``mj_step`` on the same model and controls, side by side.

For each object: one scripted trial through :func:`gripper.experiments.trial.run_trial` (rollout chunks,
stability/slip/force checks), then the same compiled model stepped with ``mj_step`` under the
same open-loop controls, recorded from the trial. Medians of --repeats runs.

Run: .venv/bin/python scripts/bench_trial.py [--objects block,cylinder] [--repeats 3]
"""

import argparse
import statistics
import time

import mujoco
import numpy as np

import gripper.experiments.trial as T
from gripper.core.params import GripperParams
from gripper.experiments.protocol import GraspProtocol, TrialNoise
from gripper.objects.library import get_object
from gripper.sim.scene import build_grasp_scene
from gripper.sim.stepping import ChunkStepper


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--objects", default="block,cylinder")
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    proto = GraspProtocol()
    for name in args.objects.split(","):
        obj = get_object(name)
        ratios, runner, plain = [], [], []
        for _ in range(args.repeats):
            controls = []
            real_step = ChunkStepper.step

            def spy(self, u, controls=controls, real_step=real_step):
                controls.append(np.array(u))
                return real_step(self, u)
            ChunkStepper.step = spy
            t0 = time.perf_counter()
            rec = T.run_trial(obj, 0, 0, protocol=proto)
            t_runner = time.perf_counter() - t0
            ChunkStepper.step = real_step
            p = GripperParams()
            p = p.replace(sim=p.sim.replace(timestep=proto.timestep))
            u = np.concatenate(controls)
            t0 = time.perf_counter()
            m2 = build_grasp_scene(p, obj, T.sample_placement(obj, TrialNoise(), 0, 0))
            d = mujoco.MjData(m2)
            for row in u:
                d.ctrl[:] = row
                mujoco.mj_step(m2, d)
            t_plain = time.perf_counter() - t0
            runner.append(t_runner)
            plain.append(t_plain)
            ratios.append(t_runner / t_plain - 1)
            assert rec["status"] == "ok"
        print(f"{name:<10} trial runner {statistics.median(runner):.3f} s, plain mj_step (incl. compile) "
              f"{statistics.median(plain):.3f} s, overhead median {100 * statistics.median(ratios):.1f} % "
              f"(runs: {', '.join(f'{100 * r:.1f}' for r in ratios)})")


if __name__ == "__main__":
    main()
