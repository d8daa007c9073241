"""``gripper study``: a design-parameter study."""

from __future__ import annotations

import sys
from pathlib import Path

from gripper.cli.options import (
    EXIT_FAILED,
    check_runner,
    with_runner,
)
from gripper.core.atomic import check_output_dir


def add(sub) -> None:
    st = sub.add_parser(
        "study", help="design-parameter study from a TOML file (paper 001's method)",
        description="Vary design parameters (one at a time, factorial or Latin hypercube), compute the "
                    "responses of every design point on Dask, and write results.jsonl, results.csv, one "
                    "plot per parameter and recommendations.md into --out. Rerunning resumes.")
    st.add_argument("file", metavar="FILE.toml",
                    help="a study file, or a shipped study by name: one_at_a_time, latin_hypercube")
    st.add_argument("--out", required=True, metavar="DIR", help="run folder (new, or the study's own to resume)")
    with_runner(st)
    st.set_defaults(func=run)


def run(args) -> int:
    from gripper.studies.study import RUN_FILES, run_study
    from gripper.studies.study_file import load_study

    check_output_dir(args.out, files=RUN_FILES)
    study = load_study(args.file)
    check_runner(args)
    records = run_study(study, args.out, workers=args.workers, scheduler=args.scheduler,
                        progress=not args.no_progress)
    failed = [r for r in records if r["status"] != "ok"]
    print(Path(args.out, "recommendations.md").read_text().rstrip())
    print(f"{len(records)} design points ({len(failed)} failed); wrote {args.out}/results.jsonl, results.csv, "
          "plot_*.png, recommendations.md")
    if records and len(failed) == len(records):
        print(f"gripper study: error: every design point failed; the first: {failed[0].get('error', '')[:200]}",
              file=sys.stderr)
        return EXIT_FAILED
    return 0
