"""``gripper envelope``: the capability envelope."""

from __future__ import annotations

import math
from pathlib import Path

from gripper.cli.inputs import (
    TRIALS_MAX,
    field_option,
    names,
    number,
    numbers,
    seed_option,
)
from gripper.cli.options import (
    EXIT_UNSTABLE,
    GRIP_PRESSURE_RANGE,
    check_runner,
    with_runner,
)
from gripper.core.atomic import check_output_dir
from gripper.core.params import ACTUATIONS, GripperParams
from gripper.drives import drive_for
from gripper.experiments.protocol import (
    GraspProtocol,
)


def add(sub) -> None:
    ev = sub.add_parser(
        "envelope", help="capability envelope: shapes x sizes x masses x frictions under the controller",
        description="Grasp rigid spheres, cylinders and boxes over a grid of sizes, masses and frictions "
                    "with the grasp controller at one set-point; write trials.jsonl, envelope.csv, "
                    "summary.json (gripping range and payload per shape) and map_<shape>.png into --out. "
                    "Rerunning resumes.")
    ev.add_argument("file", nargs="?", default="default", metavar="FILE.toml",
                    help="an envelope file, or the shipped one by name: default (the default)")
    ev.add_argument("--out", required=True, metavar="DIR", help="run folder (new, or the envelope's own to resume)")
    ev.add_argument("--shapes", metavar="S[,S...]", help="sphere, cylinder, box (default: the file's)")
    ev.add_argument("--sizes", metavar="M[,M...]", help="widths [m], sphere: diameter (default: the file's)")
    ev.add_argument("--masses", metavar="KG[,KG...]", help="masses [kg] (default: the file's)")
    ev.add_argument("--frictions", metavar="MU[,MU...]", help="friction coefficients (default: the file's)")
    number(ev, "--trials", int, lo=1, hi=TRIALS_MAX, help="trials per point; default: the file's")
    seed_option(ev, help="base seed; default: the file's")
    field_option(ev, "--grip-tension", GraspProtocol, "grip_tension", "set-point [N]; default: the file's, "
                 "else the protocol's", metavar="N", default=None)
    field_option(ev, "--grip-pressure", GraspProtocol, "grip_pressure", "the pneumatic gripper's set-point [Pa]; "
                 "default: the file's, else the protocol's", metavar="PA", default=None, range_help=GRIP_PRESSURE_RANGE)
    ev.add_argument("--actuation", choices=ACTUATIONS, default="cable",
                    help="the fingers: cable (default) or pneumatic (docs/pneumatic_gripper.md)")
    with_runner(ev)
    ev.set_defaults(func=run)


def run(args) -> int:
    from gripper.studies.envelope import RUN_FILES, load_envelope, run_envelope

    check_output_dir(args.out, files=RUN_FILES)
    lists = {key: (names(v, "--shapes") if key == "shapes" else numbers(v, f"--{key}", lo=0, lo_open=True))
             for key in ("shapes", "sizes", "masses", "frictions") if (v := getattr(args, key)) is not None}
    p = GripperParams()
    p = p.replace(actuation=p.actuation.replace(kind=args.actuation)).validate()
    env = load_envelope(args.file, trials=args.trials, seed=args.seed, grip_tension=args.grip_tension,
                        grip_pressure=args.grip_pressure, params=p, **lists)
    check_runner(args)
    summary = run_envelope(env, args.out, workers=args.workers, scheduler=args.scheduler,
                           progress=not args.no_progress)
    drive = drive_for(env.params)
    grip = drive.format_set_point(summary[drive.set_point_record])
    need = math.ceil(summary["held_fraction"] * env.trials - 1e-9)
    print(f"{env.params.actuation.kind} gripper's capability envelope at a grip of {grip} "
          f"(held: at least {need} of {env.trials} trials)")
    for shape, s in summary["shapes"].items():
        rng = s["gripping_range_m"]
        grip = f"{rng[0] * 1e3:g}-{rng[1] * 1e3:g} mm" if rng else "none held"
        pay = f"{s['payload_kg']:g} kg" if s["payload_kg"] is not None else "none held"
        print(f"{shape:<10} gripping range {grip:<14} payload {pay}")
    out = Path(args.out)
    wrote = [f for f in RUN_FILES if (out / f).is_file()] + sorted(p.name for p in out.glob("map_*.png"))
    print(f"{summary['errors']} unstable trials, {summary.get('no_object', 0)} with no object seen, "
          f"{summary['warnings']} MuJoCo warnings; wrote {out}/: {', '.join(wrote)}")
    return EXIT_UNSTABLE if summary["errors"] else 0
