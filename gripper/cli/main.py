"""The ``gripper`` command: the parser, built from one module per command
(:mod:`gripper.cli.commands`), and the one place that turns errors into exit codes.

Errors in input (bad parameter, malformed file) and output that cannot be written (a full disk,
stdout on a full device) print one line on stderr and exit with code 2; an unstable simulation
exits with 3, Ctrl-C with 130 and SIGTERM with 143, each with one line
(:mod:`gripper.cli.options`; the table is in ``docs/cli.md``).
"""

from __future__ import annotations

import argparse
import importlib
import os
import signal
import sys
import threading

from gripper.cli.commands import COMMANDS
from gripper.cli.inputs import OneLineParser
from gripper.cli.options import (
    EXIT_BAD_INPUT,
    EXIT_BROKEN_PIPE,
    EXIT_INTERRUPTED,
    EXIT_TERMINATED,
    EXIT_UNSTABLE,
)


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

        say(f"gripper {version('gripper')} (MuJoCo {mujoco.__version__})", "gripper --version")
        parser.exit()


def say(text: str, who: str) -> None:
    """Print ``text`` to stdout and flush it, so that a write error (a full device, a closed
    pipe) is met here, as one line and exit 2 (1 for a closed pipe), not at the interpreter's
    exit as a traceback."""
    try:
        print(text, flush=True)
    except BrokenPipeError:
        _quiet_stdout()
        raise SystemExit(EXIT_BROKEN_PIPE) from None
    except OSError as e:
        _quiet_stdout()
        print(f"{who}: error: cannot write to stdout ({(e.strerror or str(e)).lower()})", file=sys.stderr)
        raise SystemExit(EXIT_BAD_INPUT) from None


def _quiet_stdout() -> None:
    """Point stdout at devnull, so that the interpreter's final flush of what is left cannot
    fail again (as Python's docs advise for a closed pipe)."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())


class Terminated(BaseException):
    """SIGTERM, raised where the program is, so that ``finally`` clauses run (the worker cluster is
    closed, the run folder's lock released) and the exit is one line, as for Ctrl-C."""


def _on_sigterm(signum, frame):
    # the cluster is torn down mid-task after this: its scheduler then logs the results it can no
    # longer gather, which would add lines to the one the termination prints
    import logging

    logging.getLogger("distributed").setLevel(logging.CRITICAL)
    raise Terminated


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

    main_thread = threading.current_thread() is threading.main_thread()  # (signals go to the main thread)
    previous = signal.signal(signal.SIGTERM, _on_sigterm) if main_thread else None
    stdout, sys.stdout = sys.stdout, _GuardedStdout(sys.stdout)
    try:
        code = args.func(args)
        sys.stdout.flush()  # a write error of what was printed is met here, not at the exit
        return code
    except ValueError as e:
        print(f"gripper {args.command}: error: {e}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except SimulationUnstable as e:
        print(f"gripper {args.command}: unstable simulation: {e}", file=sys.stderr)
        return EXIT_UNSTABLE
    except BrokenPipeError:
        # the reader stopped early (``gripper bend | head``): end quietly
        _quiet_stdout()
        return EXIT_BROKEN_PIPE
    except OSError as e:  # (after BrokenPipeError, one of its kind)
        # a path the system refused that no check above caught (a name too long for the file
        # system, a disk that filled up): one line, not a traceback; the output the user chose
        # cannot be written, so the exit is the input's (2), as for any other path refused
        where = f": {e.filename}" if e.filename and len(str(e.filename)) <= 60 else ""
        if isinstance(e, StdoutError):
            _quiet_stdout()
        print(f"gripper {args.command}: error: {(e.strerror or str(e)).lower()}{where}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except Terminated:
        print(f"gripper {args.command}: terminated (SIGTERM); finished results are kept (rerun to resume)",
              file=sys.stderr)
        return EXIT_TERMINATED
    except KeyboardInterrupt:
        # Ctrl-C: one line, not a traceback. Records are appended and flushed one by one and
        # every summary is written atomically, so what finished is kept and a rerun resumes.
        print(f"gripper {args.command}: interrupted; finished results are kept (rerun to resume)",
              file=sys.stderr)
        return EXIT_INTERRUPTED
    finally:
        sys.stdout = stdout
        if main_thread:
            signal.signal(signal.SIGTERM, previous)


class StdoutError(OSError):
    """stdout refused a write (a full device): the output the user chose cannot be written."""


class _GuardedStdout:
    """stdout, with its write errors (other than a closed pipe) raised as :class:`StdoutError`, so
    that the one line says it was stdout and not a file."""

    def __init__(self, stream):
        self._stream = stream

    def _guard(self, call, *args):
        try:
            return call(*args)
        except BrokenPipeError:
            raise
        except OSError as e:
            raise StdoutError(e.errno, f"{(e.strerror or str(e)).lower()} (cannot write to stdout)") from None

    def write(self, text: str) -> int:
        return self._guard(self._stream.write, text)

    def flush(self) -> None:
        self._guard(self._stream.flush)

    def __getattr__(self, name: str):
        return getattr(self._stream, name)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
