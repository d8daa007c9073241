"""``gripper check``: step the scene under random servo commands."""

from __future__ import annotations

from gripper.cli.inputs import (
    MAX_SIMULATED_S,
    number,
    seed_option,
)
from gripper.cli.options import (
    design,
    with_params,
)


def add(sub) -> None:
    c = with_params(sub.add_parser(
        "check", help="step the scene under random drive commands (servos or chambers)",
        description="A smoke test of a design: step the gripper scene with every actuator given a "
                    "uniform random command over its range, renewed every 0.1 s; fail on any MuJoCo "
                    "warning or non-finite state."))
    number(c, "--duration", float, lo=0, lo_open=True, hi=MAX_SIMULATED_S, default=2.0, help="simulated time [s]")
    seed_option(c, help="seed of the random commands", default=0)
    c.set_defaults(func=run)


def run(args) -> int:
    from gripper.core.timesteps import check_step_budget
    from gripper.experiments.smoke import random_control_rollout

    p = design(args)
    check_step_budget(args.duration, p.sim.timestep, "--duration")
    res = random_control_rollout(p, duration=args.duration, seed=args.seed)
    print(f"{res['steps']} steps, {res['sim_time_s']:.2f} s simulated in {res['wall_time_s']:.2f} "
          f"s wall ({res['realtime_factor']:.1f}× real time), MuJoCo warnings: 0, state finite")
    return 0
