"""``gripper bend``: paper 000's bending test of one finger."""

from __future__ import annotations

import json
import sys

from gripper.cli.inputs import (
    field_option,
)
from gripper.cli.options import (
    design,
    with_params,
)
from gripper.experiments.protocol import (
    BendingConfig,
)


def add(sub) -> None:
    b = with_params(sub.add_parser(
        "bend", help="paper 000's bending test of one finger",
        description="Ramp the cable shortening rate r from 0 to r_max over the run (dynamic) or "
                    "hold each of --points set-points until at rest (quasi_static); record "
                    "hinge angles, bending angle, tip position and cable tension."))
    b.add_argument("--json", action="store_true",
                   help="print a JSON object with arrays r, tension_N, joint_angles_deg, "
                        "bending_angle_deg, tip_xyz_m")
    b.add_argument("--mode", choices=("dynamic", "quasi_static"), default=BendingConfig().mode,
                   help="dynamic: one ramp, as paper 000 ran it; quasi_static: each set-point held until at rest "
                        "(default %(default)s)")
    b.add_argument("--figure", metavar="FILE.png",
                   help="also write a PNG: side-view montage of the finger at six shortening rates "
                        "and the bending-angle curve")
    field_option(b, "--r-max", BendingConfig, "r_max", "final shortening rate")
    field_option(b, "--duration", BendingConfig, "duration", "ramp time [s]")
    field_option(b, "--timestep", BendingConfig, "timestep", "step [s], paper 000 §IV")
    field_option(b, "--points", BendingConfig, "n_points", "samples or set-points")
    b.set_defaults(func=run)


def run(args) -> int:
    from gripper.experiments.bending import BendingConfig, run_bending_test

    cfg = BendingConfig(r_max=args.r_max, duration=args.duration, timestep=args.timestep,
                        mode=args.mode, n_points=args.points)
    if args.figure:
        from gripper.render.figures import bending_figure

        res = bending_figure(args.figure, cfg, design(args, cable_only="gripper bend"))
        print(f"wrote {args.figure}", file=sys.stderr if args.json else sys.stdout)
    else:
        res = run_bending_test(cfg, design(args, cable_only="gripper bend"))
    if args.json:
        json.dump(res.to_json_dict(), sys.stdout)
        sys.stdout.write("\n")
        return 0
    print(f"bending test ({cfg.mode}, {cfg.duration:g} s at {cfg.timestep:g} s step, "
          f"wall {res.wall_time_s:.3f} s, {res.warnings} MuJoCo warnings)")
    print(f"{'r':>7} {'tension N':>10} {'bend deg':>9}  tip x,y,z [mm]")
    stride = max(1, len(res.r) // 10)
    for i in sorted({*range(0, len(res.r), stride), len(res.r) - 1}):
        tip = ", ".join(f"{v * 1e3:6.1f}" for v in res.tip_xyz_m[i])
        print(f"{res.r[i]:7.3f} {res.tension_N[i]:10.3f} {res.bending_angle_deg[i]:9.2f}  {tip}")
    return 0
