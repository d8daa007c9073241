"""The resumable run that the benchmark, the envelope and the design study share.

:class:`ResumableRun` holds the run folder for one writer with the run's identity file
(:func:`gripper.bench.execution.open_run`), reads the records an earlier run left there and
checks that they are this run's own (:func:`gripper.bench.execution.check_own_records`, before
the lock read-only, then again holding it), runs the jobs that have no record yet, in job order
and with a progress bar (:func:`gripper.bench.execution.run_ordered`), and hands back every job's
record in job order while the folder is still held, so that the command writes its tables there.

Usage, in a command's runner (a sketch, not a doctest)::

    run = ResumableRun(marker="envelope.json", key="envelope", other="another envelope",
                       files=RUN_FILES, records="trials.jsonl", label="envelope trials",
                       run_hash=h, identity=env.identity(), jobs=env.jobs(),
                       job_args=lambda job: (env, *job, h), fn=_run_one,
                       record_key=lambda r: (r["point"], r["index"]),
                       describe=lambda r: f"point {r.get('point')}, trial {r.get('index')}")
    with run.open(out, workers=workers, scheduler=scheduler, progress=progress) as done:
        write_table(done.records, done.out / "envelope.csv")
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable, Hashable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from gripper.bench.execution import check_own_records, open_run, read_jsonl, run_ordered
from gripper.core.atomic import write_atomic


@dataclass(frozen=True)
class RunRecords:
    """What :meth:`ResumableRun.open` hands back: the held folder ``out``, every job's record in
    job order, how many of them an earlier run had left (``resumed``) and when this run's jobs
    started (``started``, :func:`time.perf_counter`)."""

    out: Path
    records: list
    resumed: int
    started: float


@dataclass(frozen=True)
class ResumableRun:
    """One command's resumable run (see the module docstring).

    The folder: ``marker``, its identity file, which records ``{key}_hash`` and ``{key}``
    (``identity``) of the run with hash ``run_hash``; ``other``, what a folder of another run is
    called in the refusal; ``files``, the run's files; ``records``, its JSON-lines file of records.
    The jobs: ``jobs``, every job's key in record order; ``fn(*job_args(job))``, the job's record;
    ``label``, the progress bar's. The records: ``read(path, repair=...)`` reads them;
    ``record_key(record)`` is the job a record is of and ``describe(record)`` names it in an error;
    ``check(records, path)``, the command's further check; ``reorder``, rewrite the file in job
    order at the end (a run extended with more jobs appends them after the old ones).
    """

    marker: str
    key: str
    other: str
    files: tuple[str, ...]
    records: str
    label: str
    run_hash: str
    identity: dict
    jobs: Sequence[Hashable]
    job_args: Callable[[Any], tuple]
    fn: Callable[..., dict]
    record_key: Callable[[Mapping], Hashable]
    describe: Callable[[Mapping], str]
    read: Callable[..., list] = read_jsonl
    check: Callable[[list, Path], None] | None = None
    reorder: bool = False

    def own_records(self, path: Path, repair: bool = True) -> list:
        """The records of ``path``, refused (ValueError naming ``--out``) unless all are this run's."""
        records = self.read(path, repair=repair)
        check_own_records(records, path, self.run_hash, self.record_key, self.describe)
        if self.check is not None:
            self.check(records, path)
        return records

    @contextmanager
    def open(self, out: str | Path, *, workers: int, scheduler: str | None,
             progress: bool = True) -> Iterator[RunRecords]:
        """Run (or resume) into ``out``; yield the records while the folder is held.

        Raises:
            ValueError: a bad worker count or scheduler, or a folder of another run or command.
        """
        with open_run(out, workers, scheduler, self.marker, self.key, self.run_hash, self.identity, self.other,
                      self.files, check_records=lambda repair: self.own_records(Path(out) / self.records, repair)
                      ) as folder:
            path = folder / self.records
            done = {self.record_key(r): r for r in self.own_records(path)}  # again, holding the folder
            todo = [j for j in self.jobs if j not in done]
            started = time.perf_counter()
            run_ordered([self.job_args(j) for j in todo], self.fn, path, workers=workers, scheduler=scheduler,
                        on_record=lambda rec: done.__setitem__(self.record_key(rec), rec),
                        progress=(len(self.jobs), len(self.jobs) - len(todo), self.label) if progress else None)
            if self.reorder:
                keep_job_order(path, self.jobs, self.record_key)
            yield RunRecords(folder, [done[j] for j in self.jobs], len(self.jobs) - len(todo), started)


def keep_job_order(path: Path, jobs: Sequence[Hashable], key: Callable[[Mapping], Hashable]) -> None:
    """Rewrite the records file ``path`` in job order (then any other records, in file order) if a
    rerun appended out of order (a run extended with more jobs); atomic, so no record is lost."""
    lines = [ln for ln in path.read_text().splitlines() if ln.strip()] if path.exists() else []
    rank = {j: k for k, j in enumerate(jobs)}
    keyed = [(key(json.loads(ln)), ln) for ln in lines]
    order = sorted(range(len(keyed)), key=lambda k: (rank.get(keyed[k][0], len(rank)), k))
    if order == list(range(len(keyed))):
        return
    write_atomic(path, lambda tmp: Path(tmp).write_text("".join(keyed[k][1] + "\n" for k in order)))
