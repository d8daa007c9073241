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
