"""Write output files atomically: a temporary file beside the target, moved into place when done.

Example:
    >>> from pathlib import Path
    >>> from gripper.core.atomic import write_atomic
    >>> write_atomic(Path("/tmp/x.txt"), lambda tmp: Path(tmp).write_text("hi"))  # doctest: +SKIP
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable
from pathlib import Path


def write_atomic(out: Path, write: Callable[[str], object]) -> None:
    """Call ``write(tmp_path)`` on a temporary file in ``out``'s folder, then give it normal
    permissions (mkstemp makes it 0600) and move it onto ``out``; on any failure the temporary
    file is removed and ``out`` is left as it was."""
    out = Path(out)
    fd, tmp = tempfile.mkstemp(prefix=f".{out.stem}-", suffix=out.suffix, dir=out.parent)
    os.close(fd)
    try:
        write(tmp)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, out)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def _nearest_existing(path: Path) -> Path:
    anc = path
    while not anc.exists() and anc != anc.parent:
        anc = anc.parent
    return anc


def check_output_dir(path: str | Path, flag: str = "--out") -> Path:
    """Refuse, before any work, an output folder that is an existing file, that cannot be
    created (a file in the way) or that is not writable; create nothing.

    Raises:
        ValueError: one line naming ``flag``, the path and what is wrong.
    """
    out = Path(path)
    if out.exists() and not out.is_dir():
        raise ValueError(f"{flag}: {out} is an existing file; give a folder (new or a run's own)")
    anc = _nearest_existing(out)
    if not anc.is_dir():
        raise ValueError(f"{flag}: cannot create {out}: {anc} is a file, not a folder")
    if not os.access(anc, os.W_OK | os.X_OK):
        raise ValueError(f"{flag}: cannot write in {anc}: permission denied; choose another folder")
    return out


def check_output_file(path: str | Path, flag: str, suffixes: tuple[str, ...] = ()) -> Path:
    """Refuse, before any work, an output file that is an existing folder, has a suffix not in
    ``suffixes`` (if given), or whose folder does not exist or is not writable.

    Raises:
        ValueError: one line naming ``flag``, the path and what is wrong.
    """
    out = Path(path)
    if suffixes and out.suffix.lower() not in suffixes:
        raise ValueError(f"{flag}: {out} must end in {' or '.join(suffixes)}")
    if out.is_dir():
        raise ValueError(f"{flag}: {out} is a folder; give a file name")
    folder = out.parent if str(out.parent) else Path(".")
    if folder.exists() and not folder.is_dir():
        raise ValueError(f"{flag}: cannot write {out}: {folder} is a file, not a folder")
    if not folder.is_dir():
        raise ValueError(f"{flag}: folder {folder} does not exist; create it first")
    if not os.access(folder, os.W_OK | os.X_OK) or (out.exists() and not os.access(out, os.W_OK)):
        raise ValueError(f"{flag}: cannot write {out}: permission denied")
    return out
