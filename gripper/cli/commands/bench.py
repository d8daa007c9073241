"""``gripper bench``: the grasp benchmark."""

from __future__ import annotations

from gripper.bench.defaults import DEFAULT_TRIALS
from gripper.cli.inputs import (
    TRIALS_MAX,
    number,
    seed_option,
)
from gripper.cli.options import (
    EXIT_UNSTABLE,
    check_runner,
    design,
    object_specs,
    protocol_and_noise,
    with_params,
    with_protocol,
    with_runner,
)
from gripper.core.atomic import check_output_dir, check_output_file


def add(sub) -> None:
    from gripper.objects.library import DEFAULT_OBJECTS
    bn = with_params(sub.add_parser(
        "bench", help="grasp benchmark: seeded scripted trials on each object",
        description="Run --trials scripted grasp trials per object (settle, approach, close, lift "
                    "0.10 m, hold 2 s, shake ±10 mm at 2 Hz for 2 s) and write trials.jsonl, "
                    "summary.csv and summary.json into --out. Rerunning into the same folder resumes. "
                    "Objects: " + ", ".join(DEFAULT_OBJECTS) + ", or mesh:PATH (STL/OBJ/PLY, metres)."))
    bn.add_argument("--objects", default=",".join(DEFAULT_OBJECTS), help="comma-separated names")
    number(bn, "--trials", int, lo=1, hi=TRIALS_MAX, default=DEFAULT_TRIALS, help="trials per object")
    seed_option(bn, default=0)
    bn.add_argument("--out", default="runs/bench", metavar="DIR", help="output folder (default runs/bench)")
    with_runner(with_protocol(bn))
    bn.add_argument("--plot", metavar="FILE.png", help="also write the success rates with Wilson 95 %% intervals")
    bn.set_defaults(func=run)


def run(args) -> int:
    from gripper.bench.benchmark import RUN_FILES, BenchConfig, format_table, run_benchmark

    check_output_dir(args.out, files=RUN_FILES)
    check_runner(args)
    params = design(args)
    proto, noise = protocol_and_noise(args, params)
    cfg = BenchConfig(objects=object_specs(args.objects), trials=args.trials, seed=args.seed,
                      params=params, protocol=proto, noise=noise).validate()
    if args.plot:
        check_output_file(args.plot, "--plot", (".png",))  # before the run: a bad path must not cost one
    summary = run_benchmark(cfg, args.out, workers=args.workers, scheduler=args.scheduler,
                            progress=not args.no_progress)
    print(format_table(summary))
    print(f"wrote {args.out}/trials.jsonl, summary.csv, summary.json")
    if args.plot:
        from gripper.render.figures import success_plot

        success_plot(summary, args.plot)
        print(f"wrote {args.plot}")
    errors = sum(s["errors"] for s in summary["objects"].values())
    return EXIT_UNSTABLE if errors else 0
