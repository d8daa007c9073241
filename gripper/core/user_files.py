"""Reading the text files a user hands the package (parameter, object, study, envelope and
calibration files): one message for a file that cannot be read or is not text.

Example:
    >>> from gripper.core.user_files import read_user_text
    >>> read_user_text("/no/such/file.toml", "parameter file")
    Traceback (most recent call last):
    ...
    ValueError: parameter file: cannot read /no/such/file.toml: No such file or directory
"""

from __future__ import annotations

from pathlib import Path


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
        raise ValueError(f"{what}: {path} is a folder; give a file") from None
    except OSError as e:
        raise ValueError(f"{what}: cannot read {path}: {e.strerror or e}") from None
    except UnicodeDecodeError:
        raise ValueError(f"{what}: {path} is not a text file (not UTF-8)") from None
