"""``gripper pullout``: holding force."""

from __future__ import annotations

from gripper.cli.inputs import (
    number,
    numbers,
)
from gripper.cli.options import (
    GRIP_PRESSURE_RANGE,
    check_applies,
    design,
    object_specs,
    with_params,
)
from gripper.core.atomic import check_output_file
from gripper.experiments.protocol import (
    POLICIES,
    PULL_MAX,
    PULL_RATE,
    GraspProtocol,
)


def add(sub) -> None:
    po = with_params(sub.add_parser(
        "pullout", help="holding force: pull the held object until it slips 5 mm",
        description="Grasp and lift as in a trial, then pull the object straight down at --rate until it "
                    "slips 5 mm; with the controller, once per --grip-tension (cable) or --grip-pressure "
                    "(pneumatic) set-point."))
    po.add_argument("--objects", default="block,cylinder", help="comma-separated names")
    po.add_argument("--policy", choices=POLICIES, default=GraspProtocol().policy,
                    help="controller (default) or per_object closing")
    po.add_argument("--grip-tension", default=None, metavar="N[,N...]",
                    help=f"the cable gripper's controller set-points [N], comma-separated (default "
                         f"{GraspProtocol().grip_tension:g})")
    po.add_argument("--grip-pressure", default=None, metavar="PA[,PA...]",
                    help=f"the pneumatic gripper's set-points [Pa], comma-separated (default "
                         f"{GraspProtocol().grip_pressure:g}; each {GRIP_PRESSURE_RANGE})")
    po.add_argument("--plot", metavar="FILE.png", help="also write holding force against set-point")
    number(po, "--rate", float, lo=0, lo_open=True, hi=1000, default=PULL_RATE, help="pull ramp [N/s]")
    number(po, "--max-force", float, lo=0, lo_open=True, hi=1000, default=PULL_MAX, help="largest pull [N]")
    po.set_defaults(func=run)


def run(args) -> int:
    from gripper.drives import drive_for
    from gripper.experiments.protocol import GraspProtocol
    from gripper.experiments.pullout import run_pullout

    objects = object_specs(args.objects)
    policy = args.policy
    base = GraspProtocol(policy=policy)
    params = design(args)
    check_applies(args, params)
    drive = drive_for(params)
    pneumatic = params.actuation.kind == "pneumatic"  # which set-point option applies
    if pneumatic and args.grip_tension is not None:
        raise ValueError("--grip-tension: the cable gripper's set-point; the pneumatic gripper takes --grip-pressure")
    if not pneumatic and args.grip_pressure is not None:
        raise ValueError("--grip-pressure: the pneumatic gripper's set-point; the cable gripper takes --grip-tension")
    if pneumatic:
        grips = numbers(args.grip_pressure or str(base.grip_pressure), "--grip-pressure", lo=0, lo_open=True)
        protos = [base.replace(grip_pressure=g) for g in grips]
    elif policy == "controller":
        grips = numbers(args.grip_tension or str(base.grip_tension), "--grip-tension", lo=0, lo_open=True)
        protos = [base.replace(grip_tension=g) for g in grips]
    else:
        if args.grip_tension is not None:
            raise ValueError("--grip-tension: a controller set-point; --policy per_object closes by each "
                             "object's own command")
        protos = [base]
    for proto in protos:
        drive.check_set_point(proto.validate())
    if args.plot:
        check_output_file(args.plot, "--plot", (".png",))
    results = []
    for name in objects:
        for proto in protos:
            res = run_pullout(name, params=params, protocol=proto, rate=args.rate, max_force=args.max_force)
            results.append(res)
            bound = ">=" if res["held_at_max"] else ""
            note = "" if res.get("lifted", True) else " (not lifted: holds nothing)"
            set_point = res.get(drive.set_point_record)
            grip = f"grip {drive.format_set_point(set_point)}: " if set_point is not None else "per_object: "
            print(f"{name:<10} {grip}holding force {bound}{res['holding_force_N']:.2f} N "
                  f"(pull ramp {res['rate_N_per_s']:g} N/s until {res['slip_m'] * 1e3:g} mm slip){note}")
    if args.plot:
        from gripper.render.figures import holding_force_plot

        holding_force_plot(results, args.plot)
        print(f"wrote {args.plot}")
    return 0
