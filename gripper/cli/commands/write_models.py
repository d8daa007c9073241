"""``gripper write-models``: regenerate the committed MJCF of every shipped gripper."""

from __future__ import annotations

from gripper.cli.options import (
    design,
    with_params,
)
from gripper.core.atomic import check_output_dir


def add(sub) -> None:
    w = with_params(sub.add_parser(
        "write-models", help="regenerate models/ (each gripper's MJCF, as the trials run it)",
        description="Write each shipped gripper's MJCF (<name>.xml, scene.xml) as the trials run it and "
                    "refresh its README's parameter table, into models/<name> (soft_gripper: the cable "
                    "gripper; pneumatic_gripper). With --params or --actuation: that one design, into "
                    "--out or models/<its name>."))
    w.add_argument("--out", metavar="DIR",
                   help="output folder for one design (default: the source checkout's models/<name>; an "
                        "installed package's own copy is never written)")
    w.add_argument("--picture", action="store_true",
                   help="also render each README's picture, <name>.png (headless: MUJOCO_GL=egl)")
    w.set_defaults(func=run)


def run(args) -> int:
    from gripper.sim.model_files import (
        SCENE_FILE,
        default_model_dir,
        gripper_file,
        shipped_grippers,
        write_model_files,
    )

    one = (args.params or args.actuation or args.out or getattr(args, "calibration", None)
           or getattr(args, "springs", "calibrated") != "calibrated")
    designs = [design(args, simulates=False)] if one else list(shipped_grippers().values())
    for p in designs:
        target = args.out or default_model_dir(p)
        if target is None:
            raise ValueError("--out: give a folder (outside a source checkout there is no models/ to refresh, "
                             "and the installed package's copy is not written to)")
        out = check_output_dir(target, files=(gripper_file(p), SCENE_FILE, "README.md"))
        for path in write_model_files(out, p):
            print(f"wrote {path}")
        if args.picture:
            from gripper.render.model_picture import write_model_picture

            print(f"wrote {write_model_picture(p, out / gripper_file(p).replace('.xml', '.png'))}")
    return 0
