"""``gripper write-models``: regenerate the committed MJCF."""

from __future__ import annotations

from gripper.cli.options import (
    design,
    with_params,
)
from gripper.core.atomic import check_output_dir


def add(sub) -> None:
    w = with_params(sub.add_parser(
        "write-models", help="regenerate models/soft_gripper (the MJCF the trials run)",
        description="Write the gripper's MJCF (soft_gripper.xml, scene.xml) for the parameters, as "
                    "the trials run it, and refresh the model README's parameter table, into --out."))
    w.add_argument("--out", metavar="DIR",
                   help="output folder (default: the source checkout's models/soft_gripper; an installed "
                        "package's own copy is never written)")
    w.set_defaults(func=run)


def run(args) -> int:
    from gripper.sim.model_files import GRIPPER_FILE, SCENE_FILE, default_model_dir, write_model_files

    p = design(args, simulates=False)
    if p.pneumatic_fingers and not args.out:
        raise ValueError("--out: give a folder for the pneumatic gripper's files (models/soft_gripper is the "
                         "cable gripper's)")
    target = args.out or default_model_dir()
    if target is None:
        raise ValueError("--out: give a folder (outside a source checkout there is no models/ to refresh, "
                         "and the installed package's copy is not written to)")
    out = check_output_dir(target, files=(GRIPPER_FILE, SCENE_FILE, "README.md"))
    for path in write_model_files(out, p):
        print(f"wrote {path}")
    return 0
