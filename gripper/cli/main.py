"""The ``gripper`` command: the parser, built from one module per command
(:mod:`gripper.cli.commands`), and the one place that turns errors into exit codes.

Errors in input (bad parameter, malformed file) print one line on stderr and exit with code 2;
an unstable simulation exits with 3, Ctrl-C with 130 (:mod:`gripper.cli.options`).
"""

from __future__ import annotations

import argparse
import errno
import importlib
import os
import sys

from gripper.cli.commands import COMMANDS
from gripper.cli.inputs import OneLineParser
from gripper.cli.options import EXIT_BAD_INPUT, EXIT_BROKEN_PIPE, EXIT_FAILED, EXIT_INTERRUPTED, EXIT_UNSTABLE

# OSError numbers that mean the user named a path the system cannot use: bad input (exit 2)
BAD_PATH_ERRNOS = {errno.ENAMETOOLONG, errno.ENOENT, errno.ENOTDIR, errno.EISDIR, errno.EACCES, errno.EPERM,
                   errno.EROFS, errno.EINVAL, errno.ELOOP, errno.EEXIST}


class _Version(argparse.Action):
    """``--version``: the package's and MuJoCo's versions, looked up only when asked for (argparse's
    own version action takes the text when the parser is built, which would import MuJoCo for
    every command's ``--help``)."""

    def __init__(self, option_strings, dest=argparse.SUPPRESS, default=argparse.SUPPRESS,
                 help="show the package's and MuJoCo's versions and exit"):
        super().__init__(option_strings, dest=dest, default=default, nargs=0, help=help)

    def __call__(self, parser, namespace, values, option_string=None):
        from importlib.metadata import version

        import mujoco

        print(f"gripper {version('gripper')} (MuJoCo {mujoco.__version__})")
        parser.exit()


def build_parser() -> argparse.ArgumentParser:
    parser = OneLineParser(
        prog="gripper",
        description="Simulate a four-finger soft gripper in MuJoCo: the cable gripper (paper 000's cut "
                    "silicone fingers, a cable each reeled in by a servo; the default) or the pneumatic "
                    "gripper (paper 001's fibre-reinforced actuators): --actuation cable|pneumatic on "
                    "bench, envelope, video, check, pullout, crush, params and write-models (a study sets "
                    "actuation.kind). All quantities in "
                    "SI units unless a name says otherwise.")
    parser.add_argument("--version", action=_Version)
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND",
                                title="commands (gripper COMMAND --help for each)")
    for name in COMMANDS:
        importlib.import_module(f"gripper.cli.commands.{name}").add(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as e:  # --help, --version (0) or a usage error (2, one line said already)
        return int(e.code or 0)
    from gripper.sim.stability import SimulationUnstable  # after parsing: --help stays quick

    try:
        return args.func(args)
    except ValueError as e:
        print(f"gripper {args.command}: error: {e}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except SimulationUnstable as e:
        print(f"gripper {args.command}: unstable simulation: {e}", file=sys.stderr)
        return EXIT_UNSTABLE
    except BrokenPipeError:
        # the reader stopped early (``gripper bend | head``): end quietly, as Python's docs
        # advise, with stdout pointed at devnull so the interpreter's final flush cannot fail
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return EXIT_BROKEN_PIPE
    except OSError as e:  # (after BrokenPipeError, one of its kind)
        # a path the system refused that no check above caught (a name too long for the file
        # system, a disk that filled up): one line, not a traceback
        where = f": {e.filename}" if e.filename and len(str(e.filename)) <= 60 else ""
        print(f"gripper {args.command}: error: {(e.strerror or str(e)).lower()}{where}", file=sys.stderr)
        return EXIT_BAD_INPUT if e.errno in BAD_PATH_ERRNOS else EXIT_FAILED
    except KeyboardInterrupt:
        # Ctrl-C: one line, not a traceback. Records are appended and flushed one by one and
        # every summary is written atomically, so what finished is kept and a rerun resumes.
        print(f"gripper {args.command}: interrupted; finished results are kept (rerun to resume)",
              file=sys.stderr)
        return EXIT_INTERRUPTED


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
