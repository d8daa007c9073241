"""Shared test helpers."""

import os
import signal
import subprocess
import time
from pathlib import Path


def kill_after_lines(cmd: list[str], path: Path, lines: int, timeout: float = 120.0) -> int:
    """Start ``cmd`` in its own session, SIGKILL it once ``path`` holds ``lines`` lines, and
    return how many complete lines it had written."""
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    deadline = time.time() + timeout
    while time.time() < deadline:
        if path.exists() and path.read_text().count("\n") >= lines:
            break
        time.sleep(0.05)
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    return path.read_text().count("\n")
