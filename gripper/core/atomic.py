"""Write output files atomically: a temporary file beside the target, moved into place when done.

Example:
    >>> from pathlib import Path
    >>> from gripper.core.atomic import write_atomic
    >>> write_atomic(Path("/tmp/x.txt"), lambda tmp: Path(tmp).write_text("hi"))  # doctest: +SKIP
"""

from __future__ import annotations

import csv
import os
import tempfile
from collections.abc import Callable, Iterable, Sequence
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
    except OSError as e:
        Path(tmp).unlink(missing_ok=True)
        if e.filename is None:  # a write that failed (a full disk) names the file it was for
            raise OSError(e.errno, e.strerror or str(e), str(out)) from None
        raise
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def write_text_atomic(out: str | Path, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``out`` atomically (:func:`write_atomic`)."""
    out = Path(out)
    write_atomic(out, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))
    return out


def write_csv_atomic(out: str | Path, header: Sequence[str], rows: Iterable[Sequence]) -> Path:
    """Write a CSV of ``header`` and ``rows`` to ``out`` atomically (:func:`write_atomic`)."""
    out = Path(out)

    def write(tmp: str) -> None:
        with open(tmp, "w", newline="", encoding="utf-8") as f:
            w = csv.writer(f)
            w.writerow(header)
            w.writerows(rows)
    write_atomic(out, write)
    return out


def _nearest_existing(path: Path) -> Path:
    anc = path
    while not anc.exists() and anc != anc.parent:
        anc = anc.parent
    return anc


def _why(err: OSError) -> str:
    return (err.strerror or str(err)).lower()


def _probe_folder(folder: Path, flag: str, shown: Path) -> None:
    """Create ``folder`` (and its missing parents) and a temporary file in it, as the real
    writes will, then remove everything this made: the check leaves the tree as it found it."""
    made: list[Path] = []
    try:
        missing = []
        anc = folder
        while not anc.exists():
            missing.append(anc)
            if anc == anc.parent:
                break
            anc = anc.parent
        for d in reversed(missing):
            d.mkdir()
            made.append(d)
        fd, tmp = tempfile.mkstemp(prefix=".gripper-probe-", dir=folder)
        os.close(fd)
        os.unlink(tmp)
    except OSError as e:
        raise ValueError(f"{flag}: cannot write in {shown}: {_why(e)}") from None
    finally:
        for d in reversed(made):
            try:
                d.rmdir()
            except OSError:
                pass


def _stat_or_refuse(path: Path, flag: str) -> None:
    """Refuse a path the system cannot even look up (a name over 255 bytes, a path over 4096),
    which ``Path.exists`` raises on instead of answering."""
    try:
        os.stat(path)
    except (FileNotFoundError, NotADirectoryError):
        return
    except OSError as e:
        shown = str(path) if len(str(path)) <= 60 else f"{str(path)[:60]}... ({len(str(path))} characters)"
        raise ValueError(f"{flag}: cannot use {shown}: {_why(e)}") from None


def _refuse_empty(path: str | Path, flag: str) -> Path:
    if not str(path).strip():
        raise ValueError(f"{flag}: empty path; give a file or folder name")
    return Path(path)


def check_output_dir(path: str | Path, flag: str = "--out", files: tuple[str, ...] = ()) -> Path:
    """Refuse, before any work, an output folder that cannot be written: an empty path, an
    existing file, a path that cannot be created (tried: the folder and a temporary file in it
    are made and removed again, so it holds as root and on read-only mounts too), or a run
    folder where one of the run's own ``files`` is a folder or cannot be opened for writing.
    Leaves the file tree as it was.

    Raises:
        ValueError: one line naming ``flag``, the path and what is wrong.
    """
    out = _refuse_empty(path, flag)
    _stat_or_refuse(out, flag)
    if out.exists() and not out.is_dir():
        raise ValueError(f"{flag}: {out} is an existing file; give a folder (new or a run's own)")
    anc = _nearest_existing(out)
    if not anc.is_dir():
        raise ValueError(f"{flag}: cannot create {out}: {anc} is a file, not a folder")
    _probe_folder(out, flag, out)
    for name in files:
        f = out / name
        if f.is_symlink() or (f.exists() and not f.is_file()):
            raise ValueError(f"{flag}: {f} is not a regular file; move it away or choose another folder")
        if f.exists():
            try:
                with open(f, "ab"):
                    pass
            except OSError as e:
                raise ValueError(f"{flag}: cannot write {f}: {_why(e)}") from None
    return out


def check_output_file(path: str | Path, flag: str, suffixes: tuple[str, ...] = ()) -> Path:
    """Refuse, before any work, an output file that cannot be written: an empty path, a suffix
    not in ``suffixes`` (if given), an existing folder, a folder that does not exist, or one
    where a temporary file cannot be made (tried and removed again, as :func:`write_atomic`
    will make one).

    Raises:
        ValueError: one line naming ``flag``, the path and what is wrong.
    """
    out = _refuse_empty(path, flag)
    _stat_or_refuse(out, flag)
    if suffixes and out.suffix.lower() not in suffixes:
        raise ValueError(f"{flag}: {out} must end in {' or '.join(suffixes)}")
    if out.is_dir():
        raise ValueError(f"{flag}: {out} is a folder; give a file name")
    folder = out.parent if str(out.parent) else Path(".")
    if folder.exists() and not folder.is_dir():
        raise ValueError(f"{flag}: cannot write {out}: {folder} is a file, not a folder")
    if not folder.is_dir():
        raise ValueError(f"{flag}: folder {folder} does not exist; create it first")
    if out.exists() and not out.is_file():
        raise ValueError(f"{flag}: {out} is not a regular file")
    _probe_folder(folder, flag, folder)
    return out
