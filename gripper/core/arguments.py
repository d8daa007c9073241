"""Checks of a public function's arguments: errors name the argument, as the command line's do.

Example:
    >>> from gripper.core.arguments import check_int
    >>> check_int("index", 1.5, 0, 10)
    Traceback (most recent call last):
    ...
    TypeError: index: expected an integer in [0, 10], got 1.5
"""

from __future__ import annotations

from typing import Any


def check_int(name: str, value: Any, lo: int, hi: int) -> int:
    """``value`` if it is an int (not a bool) in [lo, hi].

    Raises:
        TypeError: not an integer; ValueError: out of range (both naming ``name``).
    """
    if isinstance(value, bool) or not isinstance(value, int):
        raise TypeError(f"{name}: expected an integer in [{lo:,}, {hi:,}], got {value!r}")
    if not lo <= value <= hi:
        raise ValueError(f"{name}: must be in [{lo:,}, {hi:,}], got {value!r}")
    return value


def check_instance(name: str, value: Any, cls: type | tuple[type, ...], *, optional: bool = True) -> Any:
    """``value`` if it is a ``cls`` (or None, when ``optional``).

    Raises:
        TypeError: naming ``name``, what is expected and the type given.
    """
    if (value is None and optional) or isinstance(value, cls):
        return value
    want = " or ".join(c.__name__ for c in (cls if isinstance(cls, tuple) else (cls,)))
    raise TypeError(f"{name}: expected {want}{' or None' if optional else ''}, got {type(value).__name__} "
                    f"{str(value)[:60]!r}")
