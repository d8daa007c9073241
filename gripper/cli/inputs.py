"""The command line's input rules: bounded numbers, lists of names, one-line errors.

Every numeric option is declared with its allowed range (:func:`number`), which argparse
enforces before any work and which the option's help states, so nothing can run backwards
or hang (a 10⁹ s rollout, a negative seed). A usage error is one line, as every other input
error of the command line is.

Ranges and their reasons:

- seeds: integers in [0, 2³² − 1], the range NumPy's and Python's seeding share;
- trial counts: [1, 100 000] (a day of block trials on one core);
- worker processes: [1, 256];
- simulated durations: at most :data:`MAX_SIMULATED_S`; pixels: [16, 4096] (MuJoCo's
  offscreen buffer is sized to the frame).
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Callable

from gripper.core.fields import field_specs
from gripper.core.ranges import SEED_MAX, TRIALS_MAX  # noqa: F401  (TRIALS_MAX: the commands import it here)

WORKERS_MAX = 256
MAX_SIMULATED_S = 600.0  # s: ten minutes of simulated time, hours of wall time for a flex object
PIXELS = (16, 4096)


class OneLineParser(argparse.ArgumentParser):
    """argparse with its usage errors on one line (the usage itself is ``--help``'s), and no
    empty values: ``--plot ''`` or ``--params ''`` is a slip, not a request for the default."""

    def _get_values(self, action, arg_strings):
        if action.option_strings and any(isinstance(a, str) and not a.strip() for a in arg_strings):
            hint = "" if action.required else "; leave the option out for its default"
            self.error(f"argument {'/'.join(action.option_strings)}: empty value{hint}")
        if action.option_strings:
            self._given.add(action.dest)
        return super()._get_values(action, arg_strings)

    def parse_known_args(self, args=None, namespace=None):
        """As argparse's, and the namespace's ``given`` holds the dests of the options the
        command line gave (:func:`given`), so an option that does not apply can be refused."""
        self._given: set[str] = set()
        ns, extras = super().parse_known_args(args, namespace)
        ns.__dict__.setdefault("given", set()).update(self._given)
        return ns, extras

    def error(self, message: str):
        print(f"{self.prog}: error: {message} (see {self.prog} --help)", file=sys.stderr)
        raise SystemExit(2)


def _bounded(kind: type, lo: float | None, hi: float | None, lo_open: bool,
             hi_open: bool = False) -> Callable[[str], float]:
    word = "an integer" if kind is int else "a number"

    def parse(text: str):
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected {word}, got {text!r}") from None
        if kind is float and not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"expected a finite number, got {text!r}")
        below = lo is not None and (value <= lo if lo_open else value < lo)
        above = hi is not None and (value >= hi if hi_open else value > hi)
        if below or above:
            raise argparse.ArgumentTypeError(f"must be {_range_text(kind, lo, hi, lo_open, hi_open)}, got {text}")
        return value
    parse.__name__ = kind.__name__  # argparse names the type in its messages
    return parse


def _range_text(kind: type, lo: float | None, hi: float | None, lo_open: bool, hi_open: bool = False) -> str:
    fmt = (lambda v: f"{v:,}") if kind is int else (lambda v: f"{v:g}")
    if lo is not None and hi is not None:
        return f"in {'(' if lo_open else '['}{fmt(lo)}, {fmt(hi)}{')' if hi_open else ']'}"
    if lo is not None:
        return f"{'>' if lo_open else '>='} {fmt(lo)}"
    return f"{'<' if hi_open else '<='} {fmt(hi)}"


def given(args: argparse.Namespace, dest: str) -> bool:
    """Whether the command line gave option ``dest`` (not just its default)."""
    return dest in getattr(args, "given", set())


def number(p: argparse.ArgumentParser, flag: str, kind: type, *, lo: float | None = None,
           hi: float | None = None, lo_open: bool = False, hi_open: bool = False, help: str = "",
           range_help: str = "", **kw) -> None:
    """Add option ``flag`` of ``kind`` (int or float) bounded to [lo, hi] (``lo_open``,
    ``hi_open``: the bound itself excluded); its help ends with the range (``range_help``, where
    the command narrows it further) and the default."""
    rng = range_help or _range_text(kind, lo, hi, lo_open, hi_open)
    default = "" if kw.get("default") is None else "; default %(default)s"
    p.add_argument(flag, type=_bounded(kind, lo, hi, lo_open, hi_open),
                   help=f"{help} ({rng}{default})".lstrip(), **kw)


def field_option(p: argparse.ArgumentParser, flag: str, cls: type, name: str, help: str, **kw) -> None:
    """Add option ``flag`` for field ``name`` of the validated dataclass ``cls``: its kind, range
    and default are the field's own (:func:`gripper.core.fields.param`), stated once there."""
    spec = field_specs(cls)[name]
    kw.setdefault("default", getattr(cls(), name))
    number(p, flag, int if spec.kind == "integer" else float, lo=spec.lo, hi=spec.hi, lo_open=spec.lo_open,
           hi_open=spec.hi_open, help=help, **kw)


def seed_option(p: argparse.ArgumentParser, flag: str = "--seed", help: str = "base seed", **kw) -> None:
    number(p, flag, int, lo=0, hi=SEED_MAX, help=help, **kw)


def names(text: str, flag: str) -> tuple[str, ...]:
    """Comma-separated names: at least one, none twice."""
    out = tuple(n.strip() for n in text.split(",") if n.strip())
    if not out:
        raise ValueError(f"{flag}: give at least one name")
    twice = sorted({n for n in out if out.count(n) > 1})
    if twice:
        raise ValueError(f"{flag}: {', '.join(twice)} listed more than once; give each once")
    return out


def numbers(text: str, flag: str, *, lo: float | None = None, hi: float | None = None,
            lo_open: bool = False) -> tuple[float, ...]:
    """Comma-separated finite numbers in the range, none twice."""
    check = _bounded(float, lo, hi, lo_open)
    try:
        vals = tuple(check(v.strip()) for v in text.split(",") if v.strip())
    except argparse.ArgumentTypeError as e:
        raise ValueError(f"{flag}: {e}") from None
    if not vals:
        raise ValueError(f"{flag}: give at least one number")
    if len(set(vals)) != len(vals):
        raise ValueError(f"{flag}: a value is listed more than once; give each once")
    return vals
