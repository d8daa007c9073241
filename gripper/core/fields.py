"""Validated parameter fields: each field's unit, allowed range and source, stated once.

A parameter is declared with :func:`param`, which stores a :class:`FieldSpec` in the
dataclass field's metadata. That one declaration drives the field's validation (the error
names the field and what is allowed), the model README's parameter table and the command
line's parameter help. Units are SI throughout (:mod:`gripper.core.units`); a name ending in
``_deg`` is in degrees.

Example:
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True)
    ... class Bar(Validated):
    ...     SECTION = "bar"
    ...     length: float = param(0.1, "m", gt=0, source="assumed: a 10 cm bar")
    >>> Bar().replace(length=-1.0)
    Traceback (most recent call last):
    ...
    ValueError: bar.length: must be > 0, got -1.0
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, ClassVar, Self

from gripper.core.ranges import Range

KINDS = ("number", "integer", "bool", "choice", "numbers")


@dataclass(frozen=True)
class FieldSpec:
    """What one parameter field is and allows.

    Attributes:
        unit: SI unit symbol, ``-`` for a dimensionless number or a flag, ``deg`` for angles
            that are given in degrees.
        kind: ``number``, ``integer``, ``bool``, ``choice`` (one of ``choices``) or ``numbers``
            (a non-empty list of numbers, each checked against the bounds).
        lo, hi: bounds (None: unbounded); ``lo_open`` / ``hi_open`` exclude the bound itself.
        choices: the allowed values of a ``choice`` field.
        source: where the default comes from: a paper's table or section, a datasheet, or
            ``assumed: <reason>``.
    """

    unit: str
    kind: str = "number"
    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    choices: tuple[str, ...] | list[str] = ()
    source: str = ""
    allow_empty: bool = False
    why: str = ""  # the reason for the range (gripper.core.ranges)

    def allowed(self) -> str:
        """The allowed values, as error messages and tables state them."""
        if self.kind == "bool":
            return "true or false"
        if self.kind == "choice":
            return "one of " + ", ".join(self.choices)
        lo, hi = self.lo, self.hi
        if lo is not None and hi is not None:
            text = f"{'(' if self.lo_open else '['}{lo:g}, {hi:g}{')' if self.hi_open else ']'}"
            return ("an integer in " if self.kind == "integer" else "in ") + text
        if lo is not None:
            return f"{'>' if self.lo_open else '>='} {lo:g}"
        if hi is not None:
            return f"{'<' if self.hi_open else '<='} {hi:g}"
        return "an integer" if self.kind == "integer" else "finite"

    def check(self, name: str, value: Any) -> None:
        """Raise ValueError naming ``name`` and what is allowed, unless ``value`` is allowed."""
        if self.kind == "bool":
            if not isinstance(value, bool):
                raise ValueError(f"{name}: expected true or false, got {value!r}")
            return
        if self.kind == "choice":
            if value not in self.choices:
                raise ValueError(f"{name}: must be one of {', '.join(self.choices)}, got {value!r}")
            return
        if self.kind == "numbers":
            if not isinstance(value, tuple | list) or (len(value) == 0 and not self.allow_empty):
                kind = "a list" if self.allow_empty else "a non-empty list"
                raise ValueError(f"{name}: expected {kind} of numbers, got {value!r}")
            for i, v in enumerate(value):
                self._check_number(f"{name}[{i}]", v)
            return
        if self.kind == "integer":
            if isinstance(value, bool) or not isinstance(value, int):
                raise ValueError(f"{name}: expected {self.allowed()}, got {value!r}")
            if not self._in_bounds(value):
                raise ValueError(f"{name}: must be {self.allowed()}, got {value!r}")
            return
        self._check_number(name, value)

    def _check_number(self, name: str, value: Any) -> None:
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise ValueError(f"{name}: expected a number, got {value!r}")
        if not math.isfinite(value):
            raise ValueError(f"{name}: must be finite, got {value!r}")
        if not self._in_bounds(value):
            why = f" ({self.why})" if self.why else ""
            raise ValueError(f"{name}: must be {self.allowed()}{why}, got {value!r}")

    def _in_bounds(self, v: float) -> bool:
        if self.lo is not None and (v <= self.lo if self.lo_open else v < self.lo):
            return False
        return not (self.hi is not None and (v >= self.hi if self.hi_open else v > self.hi))


def param(default: Any, unit: str, *, factory: Callable[[], Any] | None = None,
          gt: float | None = None, ge: float | None = None,
          lt: float | None = None, le: float | None = None, integer: bool = False,
          choices: tuple[str, ...] | list[str] = (), numbers: bool = False, allow_empty: bool = False,
          source: str = "", within: Range | None = None) -> Any:
    """A dataclass field with its :class:`FieldSpec` (``gt``/``ge``: lower bound, exclusive or
    inclusive; ``lt``/``le``: upper bound). A bool default makes a flag, ``choices`` a choice,
    ``numbers`` a list of numbers (``allow_empty``: the list may be empty). ``factory`` (with
    ``default`` None) computes the default when an instance is made, not at import: defaults
    read from a committed data file. ``choices`` given as a
    list stays that list (a registry that grows: its current entries are allowed). ``within``: a
    physical range of :mod:`gripper.core.ranges`, its reason stated in errors (``gt``/``ge`` and
    ``lt``/``le`` given as well narrow it)."""
    why = ""
    if within is not None:
        why = within.reason
        if gt is None and ge is None:
            gt, ge = (None, within.lo) if within.lo_closed else (within.lo, None)
        if lt is None and le is None:
            le = within.hi
    if isinstance(default, bool):
        kind = "bool"
    elif choices:
        kind = "choice"
    elif numbers:
        kind = "numbers"
    else:
        kind = "integer" if integer else "number"
    spec = FieldSpec(unit=unit, kind=kind, lo=gt if gt is not None else ge,
                     hi=lt if lt is not None else le, lo_open=gt is not None,
                     hi_open=lt is not None, source=source, allow_empty=allow_empty, why=why,
                     choices=choices if isinstance(choices, list) else tuple(choices))
    if factory is not None:
        return dataclasses.field(default_factory=factory, metadata={"spec": spec})
    return dataclasses.field(default=default, metadata={"spec": spec})


def field_specs(cls: Any) -> dict[str, FieldSpec]:
    """Each declared field's :class:`FieldSpec`, in declaration order."""
    return {f.name: f.metadata["spec"] for f in dataclasses.fields(cls) if "spec" in f.metadata}


def check_fields(obj: Any, prefix: str) -> None:
    """Check every declared field of ``obj`` against its spec (errors name ``prefix.field``)."""
    for name, spec in field_specs(obj).items():
        spec.check(f"{prefix}.{name}", getattr(obj, name))


class Validated:
    """Mixin for frozen dataclasses of :func:`param` fields: ``validate()`` checks every field
    against its spec, then :meth:`check` (the cross-field rules); ``replace()`` validates the
    copy it returns, so no invalid value survives a change."""

    SECTION: ClassVar[str] = ""

    def check(self) -> None:
        """Rules that involve several fields (override); single fields are checked already."""

    def validate(self) -> Self:
        check_fields(self, self.SECTION)
        self.check()
        return self

    def replace(self, **changes: Any) -> Self:
        """A validated copy with ``changes`` applied (``dataclasses.replace``)."""
        return dataclasses.replace(self, **changes).validate()  # type: ignore[type-var]


# A name that becomes part of a file name or a record key: letters, digits and ``_ . -``,
# starting with a letter or digit, at most 64 characters (no path separators, no ``..``).
SAFE_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]{0,63}\Z")


def check_safe_name(name: object, what: str) -> str:
    """``name`` if it matches :data:`SAFE_NAME`; else ValueError naming ``what`` and the rule."""
    if not isinstance(name, str) or not SAFE_NAME.match(name) or ".." in name:
        text = str(name)
        shown = text if len(text) <= 40 else f"{text[:40]}... ({len(text)} characters)"
        raise ValueError(f"{what}: {shown!r} is not allowed: use letters, digits and _ . - (at most 64, "
                         "starting with a letter or digit)")
    return name
