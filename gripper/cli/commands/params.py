"""``gripper params``: write a parameter file."""

from __future__ import annotations

import argparse
import textwrap

from gripper.cli.options import (
    design,
    with_params,
)
from gripper.core.atomic import check_output_file
from gripper.core.params import parameter_help


def add(sub) -> None:
    p = with_params(sub.add_parser(
        "params", help="write a parameter file (defaults or --params)",
        description=textwrap.fill("Write the gripper parameters (the defaults, or --params with any "
                                  "--springs or --calibration applied) to a .json or .toml file. Every "
                                  "field, its unit, allowed range and source:", 78),
        epilog=parameter_help(), formatter_class=argparse.RawDescriptionHelpFormatter))
    p.add_argument("--out", required=True, metavar="FILE", help=".json or .toml")
    p.set_defaults(func=run)


def run(args) -> int:
    check_output_file(args.out, "--out", (".json", ".toml"))
    path = design(args, simulates=False).save(args.out)
    print(f"wrote {path}")
    return 0
