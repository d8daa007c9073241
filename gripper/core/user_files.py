"""Reading the text files a user hands the package (parameter, object, study, envelope and
calibration files): one message for a file that cannot be read or is not text.

Example:
    >>> from gripper.core.user_files import read_user_text
    >>> read_user_text("/no/such/file.toml", "parameter file")
    Traceback (most recent call last):
    ...
    ValueError: parameter file /no/such/file.toml: cannot read it (No such file or directory)
"""

from __future__ import annotations

import json
import tomllib
from pathlib import Path
from typing import Any


def read_user_text(path: str | Path, what: str) -> str:
    """The UTF-8 text of ``path``.

    Raises:
        ValueError: one line naming ``what`` and the file: unreadable (the system's reason), a
            folder, or not UTF-8 text (a binary file, or one saved in another encoding).
    """
    path = Path(path)
    try:
        return path.read_text(encoding="utf-8")
    except IsADirectoryError:
        raise ValueError(f"{what} {path}: a folder; give a file") from None
    except OSError as e:
        raise ValueError(f"{what} {path}: cannot read it ({e.strerror or e})") from None
    except UnicodeDecodeError:
        raise ValueError(f"{what} {path}: not a text file (not UTF-8)") from None


def read_user_data(path: str | Path, what: str, suffixes: tuple[str, ...] = (".toml", ".json")) -> Any:
    """The parsed contents of a TOML or JSON file, chosen by its suffix.

    Raises:
        ValueError: one line naming ``what`` and the file: a suffix not in ``suffixes``, any
            :func:`read_user_text` error, or malformed TOML/JSON (with the parser's first line).
    """
    path = Path(path)
    if path.suffix.lower() not in suffixes:
        raise ValueError(f"{what} {path}: the name must end in {' or '.join(suffixes)}")
    text = read_user_text(path, what)
    try:
        return json.loads(text) if path.suffix.lower() == ".json" else tomllib.loads(text)
    except (json.JSONDecodeError, tomllib.TOMLDecodeError) as e:
        kind = path.suffix[1:].upper()
        raise ValueError(f"{what} {path}: not valid {kind} ({str(e).splitlines()[0]})") from None
