"""The execution layer shared by the benchmark and the design studies.

Jobs run on Dask ``distributed``: a ``LocalCluster`` of single-threaded worker processes on this
machine, or an existing cluster given by its scheduler address; one local worker runs in this
process. Results are appended to a JSON-lines file in job order (flushed and fsynced one by one),
so an interrupted run leaves a clean prefix that :func:`read_jsonl` reads back on resume.

Example:
    >>> from gripper.bench.execution import run_ordered                              # doctest: +SKIP
    >>> run_ordered([(1,), (2,)], pow_fn, path, workers=2)                       # doctest: +SKIP
"""

from __future__ import annotations

import json
import logging
import os
import signal
import socket
import sys
from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit


def read_jsonl(path: Path, *, repair: bool = True) -> list[dict]:
    """Complete records of a JSON-lines file; a torn last line (a killed writer) is cut off from
    the file (``repair``: only by the run that holds the folder; without it, only ignored)."""
    if not path.is_file():
        return []
    raw = path.read_bytes()
    keep = raw[: raw.rfind(b"\n") + 1]
    if len(keep) != len(raw) and repair:
        torn = keep.count(b"\n") + 1
        print(f"{path}: line {torn} was incomplete (a run stopped while writing it); dropped, "
              "its trial runs again", file=sys.stderr)
        with open(path, "r+b") as f:
            f.truncate(len(keep))
    out = []
    for n, line in enumerate(keep.decode(errors="replace").splitlines(), start=1):
        if not line.strip():
            continue
        try:
            out.append(json.loads(line))
        except json.JSONDecodeError as e:
            raise ValueError(f"--out: {path}: line {n} is not a JSON record ({e.msg}); delete that line "
                             "to resume, or choose a new --out folder") from None
    return out


def check_own_records(records: Sequence[Mapping], path: Path, run_hash: str, key: Callable[[Mapping], Any],
                      what: Callable[[Mapping], str]) -> None:
    """Refuse a run file that holds a record of another run (its ``run_config_hash`` is not
    ``run_hash``: another seed, design or protocol appended by hand or by another tool, or a
    folder whose configuration file was replaced) or the same job twice, naming the first such
    record: a resume then never mixes runs, and a summary never counts another run's record.

    Raises:
        ValueError: one line naming ``--out``, the file, the record and why.
    """
    seen: set = set()
    for n, r in enumerate(records, start=1):
        if r.get("run_config_hash") != run_hash:
            raise ValueError(f"--out: {path}: record {n} ({what(r)}) belongs to another run (configuration "
                             f"{r.get('run_config_hash')}, this run's {run_hash}); choose another --out folder")
        k = key(r)
        if k in seen:
            raise ValueError(f"--out: {path}: record {n} repeats {what(r)}; the folder was written twice: "
                             "choose another --out folder")
        seen.add(k)


def check_same_run(records: Sequence[Mapping], run_hash: str, what: str) -> None:
    """Refuse to summarise a record of another run: one whose ``run_config_hash`` is set and is
    not ``run_hash`` (records made in memory, without one, are the caller's own).

    Raises:
        ValueError: naming the first foreign record.
    """
    for n, r in enumerate(records, start=1):
        h = r.get("run_config_hash")
        if h is not None and h != run_hash:
            raise ValueError(f"{what}: record {n} ({r.get('trial_id', r.get('point', '?'))}) belongs to another run "
                             f"(configuration {h}, this run's {run_hash}); it is not counted in this run's summary")


# How long a --scheduler address may take to accept a connection before it counts as unreachable [s].
SCHEDULER_TIMEOUT_S = 5.0


def check_scheduler(address: str | None, timeout: float = SCHEDULER_TIMEOUT_S) -> None:
    """Refuse, before any work, a Dask scheduler address that is malformed or does not accept a
    TCP connection within ``timeout`` (None: a local cluster, nothing to check).

    Raises:
        ValueError: one line naming ``--scheduler``, the address and the reason.
    """
    if address is None:
        return
    parts = urlsplit(address if "://" in address else f"tcp://{address}")
    try:
        port = parts.port
    except ValueError:
        port = None
    if parts.scheme not in ("tcp", "tls") or not parts.hostname or port is None:
        raise ValueError(f"--scheduler: expected tcp://HOST:PORT, got {address!r}")
    try:
        socket.create_connection((parts.hostname, port), timeout=timeout).close()
    except OSError as e:
        reason = e.strerror or type(e).__name__
        raise ValueError(f"--scheduler: cannot reach {address} within {timeout:g} s ({reason}); start "
                         "one with 'dask scheduler', or leave --scheduler out for a local cluster") from None


# The marker file of each command's run folder: a folder holds one command's runs only.
RUN_MARKERS = {"config.json": "a benchmark", "envelope.json": "an envelope", "study.json": "a study",
               "progress.csv": "a policy training"}  # (gripper train's folder has a config.json too)
LOCK_FILE = ".lock"


@contextmanager
def open_run(out: str | Path, workers: int, scheduler: str | None, filename: str, key: str, h: str,
             payload: dict, what: str, files: tuple[str, ...] = (),
             check_records: Callable[[bool], object] | None = None) -> Iterator[Path]:
    """Check the worker count and the scheduler, then hold ``out`` for this run: its lock
    (:func:`folder_lock`: one writer per folder) and its claim (:func:`claim_run_dir`). A refused
    run leaves no folder behind. ``files``: the run's other files, each of which must be a
    writable regular file where it exists. ``check_records(repair)``: the command's check of the
    folder's records against this run (:func:`check_own_records`), run read-only before the lock
    is taken (a torn last line may be another writer's), so that a refusal writes nothing, not
    even the lock file, and the command runs it again, repairing, once it holds the folder.
    Yields ``out`` as a path; the lock is released when the run ends, however it ends."""
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise ValueError(f"--workers: must be an integer >= 1, got {workers!r}")
    check_scheduler(scheduler)
    out = Path(out)
    from gripper.core.atomic import check_output_dir

    check_output_dir(out, files=(filename, LOCK_FILE, *files))
    other = [m for m in RUN_MARKERS if m != filename and (out / m).is_file()]
    other.sort(key=lambda m: m != "progress.csv")  # a training folder's config.json is not a benchmark's
    if other:
        raise ValueError(f"--out: {out} holds {RUN_MARKERS[other[0]]}'s run ({other[0]}); choose another --out "
                         "folder")
    if (out / filename).is_file():  # read-only, so that a refusal touches nothing
        _check_claim(out / filename, key, h, what)
    if check_records is not None and out.is_dir():
        check_records(False)
    made = not out.exists()
    out.mkdir(parents=True, exist_ok=True)
    try:
        with folder_lock(out):
            claim_run_dir(out, filename, key, h, payload, what, files)
            made = False
            yield out
    finally:
        if made:  # refused before its claim: leave nothing behind
            (out / LOCK_FILE).unlink(missing_ok=True)
            try:
                out.rmdir()
            except OSError:
                pass


@contextmanager
def folder_lock(out: Path) -> Iterator[None]:
    """Hold the run folder's advisory lock (``out/.lock``, the OS's ``flock``) for one writer:
    another process that asks for it while it is held is refused in one line naming the holder;
    the OS releases it when the holder ends, however it ends (a crash, SIGKILL)."""
    import fcntl

    path = out / LOCK_FILE
    with open(path, "a+", encoding="utf-8") as f:
        try:
            fcntl.flock(f.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            f.seek(0)
            holder = f.read().strip() or "unknown"
            raise ValueError(f"--out: {out} is being written by another run (process {holder}); wait for it "
                             "to end, or choose another --out folder") from None
        f.seek(0)
        f.truncate()
        f.write(str(os.getpid()))
        f.flush()
        try:
            yield
        finally:
            fcntl.flock(f.fileno(), fcntl.LOCK_UN)


def claim_run_dir(out: Path, filename: str, key: str, h: str, payload: dict, what: str,
                  files: tuple[str, ...] = ()) -> None:
    """Create ``out`` and record the run's identity in ``out/filename`` ({key}_hash, {key},
    versions); an existing record with another hash is refused (ValueError naming ``--out``)."""
    from gripper.core.atomic import check_output_dir, write_text_atomic
    from gripper.core.provenance import versions

    check_output_dir(out, files=(filename, *files))
    out.mkdir(parents=True, exist_ok=True)
    cfile = out / filename
    if cfile.exists():
        _check_claim(cfile, key, h, what)
        return
    write_text_atomic(cfile, json.dumps({f"{key}_hash": h, key: payload, "versions": versions()},
                                        indent=2, sort_keys=True, default=str))


def _check_claim(cfile: Path, key: str, h: str, what: str) -> None:
    """Refuse a run folder whose identity file ``cfile`` records another run than hash ``h``."""
    from gripper.core.user_files import read_user_text

    try:
        old = json.loads(read_user_text(cfile, "--out:"))
    except (json.JSONDecodeError, RecursionError):
        raise ValueError(f"--out: {cfile} is not valid JSON; use a new folder") from None
    got = old.get(f"{key}_hash") if isinstance(old, dict) else None
    if got != h:
        raise ValueError(f"--out: {cfile.parent} holds {what} (hash {got} vs {h}); choose a new --out folder, or "
                         "delete that folder to start over")


def executor(workers: int, scheduler: str | None):
    """(client, close, distributed): a Dask client, or an in-process stand-in for one worker."""
    if scheduler is None and workers == 1:
        class _Inline:
            def submit(self, fn, *a, **_):
                return fn(*a)
        return _Inline(), (lambda: None), False
    from dask.distributed import Client, LocalCluster

    if scheduler:
        client = Client(scheduler)
        return client, client.close, True
    # The worker processes start with Ctrl-C ignored (a disposition a child process inherits):
    # a terminal's SIGINT reaches the whole process group, and only this process should act on
    # it, closing the cluster once, instead of every worker printing its own traceback.
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=":0",
                               silence_logs=logging.ERROR)  # a failed task is raised here, once
        client = Client(cluster)
    finally:
        signal.signal(signal.SIGINT, previous)

    def close():
        client.close()
        cluster.close()
    return client, close, True


def run_ordered(todo: Sequence[tuple], fn: Callable[..., dict], path: Path, *, workers: int = 1,
                scheduler: str | None = None, on_record: Callable[[dict], None] | None = None,
                progress: tuple[int, int, str] | None = None) -> None:
    """Run ``fn(*job)`` for every job of ``todo`` and append each record to ``path`` in job order.

    ``progress`` = (total, already done, label) shows a tqdm bar. ``fn`` must be importable by
    the workers (a module-level function).
    """
    bar = None
    if progress is not None and todo:
        from tqdm import tqdm
        total, initial, label = progress
        bar = tqdm(total=total, initial=initial, unit="job", desc=label)
    if not todo:
        return
    client, close, distributed = executor(workers, scheduler)
    try:
        with open(path, "a", encoding="utf-8") as f:
            def write(rec):
                f.write(json.dumps(rec, sort_keys=True) + "\n")
                f.flush()
                os.fsync(f.fileno())
                if on_record is not None:
                    on_record(rec)
                if bar is not None:
                    bar.update(1)
            if not distributed:
                for job in todo:
                    write(client.submit(fn, *job))
                return
            from dask.distributed import as_completed
            futures = {client.submit(fn, *job, pure=False): k for k, job in enumerate(todo)}
            pending: dict[int, dict] = {}
            nxt = 0
            for fut in as_completed(futures):
                pending[futures[fut]] = fut.result()
                while nxt in pending:  # write in job order
                    write(pending.pop(nxt))
                    nxt += 1
    finally:
        close()
        if bar is not None:
            bar.close()
