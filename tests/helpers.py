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


def run_into_fresh_folder(tmp_path_factory, argv: list[str], *, text: str, filename: str) -> tuple[Path, Path]:
    """Write ``text`` to a new ``filename`` and run ``gripper <argv> FILE --out DIR --workers 1
    --no-progress`` into a new folder; return (file, folder). For module-scoped references."""
    from gripper.cli.main import main

    path = tmp_path_factory.mktemp("spec") / filename
    path.write_text(text)
    out = tmp_path_factory.mktemp("ref") / "run"
    assert main([*argv, str(path), "--out", str(out), "--workers", "1", "--no-progress"]) == 0
    return path, out


def study_records(out: Path) -> list[dict]:
    """A study run's records without their wall times (which differ from run to run)."""
    import json

    recs = [json.loads(x) for x in (out / "results.jsonl").read_text().splitlines()]
    return [{k: v for k, v in r.items() if k != "wall_time_s"} for r in recs]
