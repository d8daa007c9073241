"""The bad-input campaigns, every case as its own process with a time limit, two at a time:
the hostile inputs of ``tests/hostile_inputs.py`` (by kind) and the typo grid of
``tests/test_bad_input_campaign.py`` (by command). Prints each defect (``-v``: every case) and
the totals by kind and class; exits 1 if any case is a defect.

Run: ``.venv/bin/python scripts/bad_input_campaign.py [-v] [--hostile-only]`` (about 25 minutes
on 2 cores for both; the hostile cases alone take about 5).
"""

from __future__ import annotations

import json
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

import hostile_inputs  # noqa: E402
import test_bad_input_campaign as typos  # noqa: E402


def main() -> int:
    verbose = "-v" in sys.argv
    jobs = [(c.kind, c.name, (lambda c=c: hostile_inputs.run_case(c))) for c in hostile_inputs.CASES]
    if "--hostile-only" not in sys.argv:
        jobs += [(f"typo:{command}", " ".join(argv)[:120],
                  (lambda c=command, a=argv: typos.run_case(c, a, typos.TIMEOUT))) for command, argv in typos._cases()]
    with ThreadPoolExecutor(2) as pool:
        results = list(pool.map(lambda job: job[2](), jobs))
    totals: dict[str, dict[str, int]] = {}
    defects = 0
    for (kind, name, _), (cls, text) in zip(jobs, results, strict=True):
        totals.setdefault(kind, {}).setdefault(cls, 0)
        totals[kind][cls] += 1
        good = cls == "refused" or (kind.startswith("typo:") and cls == "accepted")
        defects += not good
        if not good or verbose:
            print(f"{'ok    ' if good else 'DEFECT'} {cls:9s} {kind}: {name}: {text}")
    by_class: dict[str, int] = {}
    for counts in totals.values():
        for cls, n in counts.items():
            by_class[cls] = by_class.get(cls, 0) + n
    print(json.dumps({"by_kind": totals, "by_class": by_class, "cases": len(jobs), "defects": defects}, indent=1))
    return 1 if defects else 0


if __name__ == "__main__":
    sys.exit(main())
