"""``gripper crush``: the platen crush test."""

from __future__ import annotations

import json

from gripper.cli.inputs import (
    number,
)
from gripper.cli.options import (
    design,
    object_specs,
    with_params,
)
from gripper.experiments.protocol import (
    CRUSH_DEPTH,
    CRUSH_HOLD_S,
    CRUSH_SPEED,
)


def add(sub) -> None:
    cr = with_params(sub.add_parser(
        "crush", help="press objects between the floor and a plate, report their damage measure",
        description="Platen crush test: a rigid plate presses each object --depth below its top at "
                    "--speed, holds --hold seconds and lifts off; prints the object's damage measure "
                    "(balloon/bag: peak edge strain; paper box: permanent dent; rigid: plate force)."))
    cr.add_argument("--objects", default="balloon,paper_box", help="comma-separated names")
    number(cr, "--depth", float, lo=0, lo_open=True, hi=0.2, default=CRUSH_DEPTH,
           help="press depth below the object's top [m]")
    number(cr, "--speed", float, lo=0, lo_open=True, hi=1.0, default=CRUSH_SPEED, help="plate speed [m/s]")
    number(cr, "--hold", float, lo=0, hi=60, default=CRUSH_HOLD_S, help="hold time at depth [s]")
    cr.add_argument("--json", action="store_true", help="one JSON object per line")
    cr.set_defaults(func=run)


def run(args) -> int:
    from gripper.experiments.crush import crush_test

    params = design(args, cable_only="gripper crush")
    for name in object_specs(args.objects):
        res = crush_test(name, args.depth, speed=args.speed, hold_s=args.hold, params=params)
        if args.json:
            print(json.dumps(res))
            continue
        flag = "DAMAGED" if res["damaged"] else "intact"
        print(f"{name:<10} pressed {res['depth_m'] * 1e3:g} mm: {flag}, {res['damage_measure_name']} "
              f"{res['damage_measure']:.4g} (limit {res['damage_limit']:g}), peak plate force "
              f"{res['peak_plate_force_N']:.2f} N")
    return 0
