"""``gripper servo``: the servo model against its datasheet."""

from __future__ import annotations

from gripper.cli.options import (
    design,
    with_params,
)


def add(sub) -> None:
    s = with_params(sub.add_parser(
        "servo", help="servo model against its datasheet",
        description="Measure the servo model (the gripper's dcmotor actuator and its position loop) as "
                    "a bench would: no-load speed, stall torque, and the cable tension they give, each "
                    "against the datasheet of the --params servo preset."))
    s.set_defaults(func=run)


def run(args) -> int:
    from gripper.drives.cable.datasheet_check import measure_servo

    m = measure_servo(design(args, cable_only="gripper servo"))
    print(f"servo preset {m.datasheet.name}: {m.datasheet.description}")
    print(f"{'figure':<24} {'model':>10} {'datasheet':>10} {'error':>8}")
    for name, model, sheet in m.rows():
        print(f"{name:<24} {model:10.4f} {sheet:10.4f} {100 * (model / sheet - 1):7.2f}%")
    print(f"max cable tension: {m.max_cable_tension:.2f} N (stall torque / spool radius)")
    return 0
