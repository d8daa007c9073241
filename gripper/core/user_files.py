"""Reading the files a user hands the package (parameter, object, study, envelope and
calibration files, bench data, meshes): one reader with limits, and one message for a file that
cannot be read.

The limits, and why:

- **regular files only**, after following links: a FIFO would block, a device (``/dev/zero``)
  never ends, a folder is not a file. The file is opened without blocking and checked again on
  the open descriptor, so a FIFO swapped in after the check cannot hang the read either.
- **size**: at most :data:`MAX_TEXT_BYTES` for text (the largest text file the package writes,
  a calibration with its history, is under 100 kB; bench data of :data:`CSV_MAX_ROWS` rows is
  under 5 MB) and :data:`MAX_MESH_BYTES` for a mesh (a 10⁶-triangle binary STL is 50 MB).
- **nesting**: at most :data:`MAX_DEPTH` levels of tables and lists (the package's own files nest
  four deep); deeper is refused, whether the parser or the check finds it.
- **numbers**: every number must fit a float: finite, and an integer of at most
  :data:`MAX_INT_DIGITS` digits (a float holds 10³⁰⁸, and Python refuses to read integers of
  more than 4300 digits at all).
- **CSV**: at most :data:`CSV_MAX_ROWS` rows of :data:`CSV_MAX_COLUMNS` cells of
  :data:`CSV_MAX_CELL` characters (a lab's bench log: tens of rows of ten columns).

Example:
    >>> from gripper.core.user_files import read_user_text
    >>> read_user_text("/no/such/file.toml", "parameter file")
    Traceback (most recent call last):
    ...
    ValueError: parameter file /no/such/file.toml: cannot read it (No such file or directory)
"""

from __future__ import annotations

import csv
import json
import math
import os
import stat
import tomllib
from pathlib import Path
from typing import Any

MAX_TEXT_BYTES = 16 * 2**20
MAX_MESH_BYTES = 128 * 2**20
MAX_DEPTH = 32
MAX_INT_DIGITS = 308
CSV_MAX_ROWS = 100_000
CSV_MAX_COLUMNS = 256
CSV_MAX_CELL = 1000


def _kind_of(mode: int) -> str:
    if stat.S_ISDIR(mode):
        return "a folder; give a file"
    if stat.S_ISFIFO(mode):
        return "a FIFO (named pipe), not a regular file"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device, not a regular file"
    if stat.S_ISSOCK(mode):
        return "a socket, not a regular file"
    return "not a regular file"


def read_user_bytes(path: str | Path, what: str, max_bytes: int = MAX_TEXT_BYTES) -> bytes:
    """The bytes of ``path``: a regular file (after following links) of at most ``max_bytes``.

    Raises:
        ValueError: one line naming ``what`` and the file: unreadable (the system's reason), not
            a regular file (a folder, FIFO, device or socket), or larger than ``max_bytes``.
    """
    path = Path(path)
    try:
        st = os.stat(path)  # follows links: a link to /dev/zero is a device
        if not stat.S_ISREG(st.st_mode):
            raise ValueError(f"{what} {path}: {_kind_of(st.st_mode)}")
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except OSError as e:
        raise ValueError(f"{what} {path}: cannot read it ({e.strerror or e})") from None
    try:
        st = os.fstat(fd)  # the file opened, not the one checked: it may have been swapped
        if not stat.S_ISREG(st.st_mode):
            raise ValueError(f"{what} {path}: {_kind_of(st.st_mode)}")
        if st.st_size > max_bytes:
            raise ValueError(f"{what} {path}: {st.st_size:,} bytes; at most {max_bytes:,} are read")
        with os.fdopen(fd, "rb", closefd=True) as f:
            fd = -1
            data = f.read(max_bytes + 1)
    except OSError as e:
        raise ValueError(f"{what} {path}: cannot read it ({e.strerror or e})") from None
    finally:
        if fd >= 0:
            os.close(fd)
    if len(data) > max_bytes:  # it grew while being read
        raise ValueError(f"{what} {path}: more than {max_bytes:,} bytes; at most {max_bytes:,} are read")
    return data


def read_user_text(path: str | Path, what: str, max_bytes: int = MAX_TEXT_BYTES) -> str:
    """The UTF-8 text of ``path`` (:func:`read_user_bytes`' limits).

    Raises:
        ValueError: one line naming ``what`` and the file: any :func:`read_user_bytes` error, or
            not UTF-8 text (a binary file, or one saved in another encoding).
    """
    data = read_user_bytes(path, what, max_bytes)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        raise ValueError(f"{what} {Path(path)}: not a text file (not UTF-8)") from None


class _BigInt(str):
    """A JSON integer too long to be a float, kept as its text until :func:`check_data` names it."""


def _json_int(text: str) -> int | _BigInt:
    return _BigInt(text) if len(text.lstrip("-")) > MAX_INT_DIGITS else int(text)


def _json_constant(text: str) -> float:
    return float(text.replace("Infinity", "inf"))  # NaN, Infinity: refused by check_data with the key


def parse_user_data(text: str, kind: str, where: str) -> Any:
    """Parse TOML or JSON ``text`` (``kind`` ``"toml"`` or ``"json"``) and check it with
    :func:`check_data`; ``where`` begins every error (the file, as ``what path``).

    Raises:
        ValueError: malformed text (the parser's first line), nesting deeper than
            :data:`MAX_DEPTH`, or a number that is not a finite float (naming its key).
    """
    try:
        if kind == "json":
            data = json.loads(text, parse_int=_json_int, parse_constant=_json_constant)
        else:
            data = tomllib.loads(text)
    except (json.JSONDecodeError, tomllib.TOMLDecodeError) as e:
        raise ValueError(f"{where}: not valid {kind.upper()} ({str(e).splitlines()[0]})") from None
    except RecursionError:
        raise ValueError(f"{where}: nested more than {MAX_DEPTH} levels deep") from None
    except ValueError as e:  # an integer past Python's 4300 digits, in TOML
        raise ValueError(f"{where}: a number that does not fit a float ({str(e).splitlines()[0][:80]})") from None
    check_data(data, where)
    return data


def check_data(data: Any, where: str) -> None:
    """Refuse nesting deeper than :data:`MAX_DEPTH` and numbers that are not finite floats,
    naming the key (``section.key[i]``); walked without recursion."""
    stack: list[tuple[Any, str, int]] = [(data, "", 0)]
    while stack:
        value, key, depth = stack.pop()
        if depth > MAX_DEPTH:
            raise ValueError(f"{where}: {key or 'the top level'}: nested more than {MAX_DEPTH} levels deep")
        name = key or "the top level"
        if isinstance(value, _BigInt) or (isinstance(value, int) and not isinstance(value, bool)
                                          and len(str(abs(value))) > MAX_INT_DIGITS):
            digits = len(str(value).lstrip("-"))
            raise ValueError(f"{where}: {name}: a {digits}-digit integer does not fit a float")
        if isinstance(value, float) and not math.isfinite(value):
            raise ValueError(f"{where}: {name}: must be a finite number, got {value!r}")
        if isinstance(value, dict):
            stack.extend((v, f"{key}.{k}" if key else str(k), depth + 1) for k, v in value.items())
        elif isinstance(value, list):
            stack.extend((v, f"{key}[{i}]", depth + 1) for i, v in enumerate(value))


def read_user_data(path: str | Path, what: str, suffixes: tuple[str, ...] = (".toml", ".json")) -> Any:
    """The parsed contents of a TOML or JSON file, chosen by its suffix, within this module's
    limits.

    Raises:
        ValueError: one line naming ``what`` and the file: a suffix not in ``suffixes``, any
            :func:`read_user_text` error, malformed TOML/JSON (with the parser's first line), too
            deep, or a number that is not a finite float.
    """
    path = Path(path)
    if path.suffix.lower() not in suffixes:
        raise ValueError(f"{what} {path}: the name must end in {' or '.join(suffixes)}")
    text = read_user_text(path, what)
    return parse_user_data(text, "json" if path.suffix.lower() == ".json" else "toml", f"{what} {path}")


def read_user_csv(path: str | Path, what: str) -> list[list[str]]:
    """The rows of a CSV file, blank lines and ``#`` comment lines left out, within
    :data:`CSV_MAX_ROWS` rows, :data:`CSV_MAX_COLUMNS` columns and :data:`CSV_MAX_CELL`
    characters a cell.

    Raises:
        ValueError: one line naming ``what``, the file and the row at fault.
    """
    name = Path(path).name
    text = read_user_text(path, what)
    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    if len(lines) > CSV_MAX_ROWS:
        raise ValueError(f"{what} {name}: {len(lines):,} rows; at most {CSV_MAX_ROWS:,}")
    rows: list[list[str]] = []
    try:
        for k, row in enumerate(csv.reader(lines), start=1):
            if len(row) > CSV_MAX_COLUMNS:
                raise ValueError(f"{what} {name}: row {k}: {len(row):,} columns; at most {CSV_MAX_COLUMNS}")
            long = next((c for c in row if len(c) > CSV_MAX_CELL), None)
            if long is not None:
                raise ValueError(f"{what} {name}: row {k}: a cell of {len(long):,} characters; at most "
                                 f"{CSV_MAX_CELL}")
            rows.append(row)
    except csv.Error as e:  # a cell past csv's own limit (131 072 characters), a stray NUL
        raise ValueError(f"{what} {name}: row {len(rows) + 1}: not valid CSV ({e})") from None
    return rows
