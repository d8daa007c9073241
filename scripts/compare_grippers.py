"""The cable and the pneumatic gripper side by side, from two benchmark run folders (and,
optionally, two envelope run folders): the Markdown tables of ``docs/pneumatic_gripper.md``.

Run (each folder from ``gripper bench``/``gripper envelope``, same objects, trials and seed):

    .venv/bin/gripper bench --trials 50 --seed 1 --out runs/cable50_s1
    .venv/bin/gripper bench --actuation pneumatic --trials 50 --seed 1 --out runs/pneu50_s1
    .venv/bin/gripper envelope default --out runs/env_cable
    .venv/bin/gripper envelope default --actuation pneumatic --out runs/env_pneu
    .venv/bin/python scripts/compare_grippers.py runs/cable50_s1 runs/pneu50_s1 \\
        --envelopes runs/env_cable runs/env_pneu
"""

from __future__ import annotations

import argparse
import json
import statistics
from pathlib import Path

from gripper.bench.execution import read_jsonl


def _bench_rows(folder: Path) -> dict[str, dict]:
    out: dict[str, dict] = {}
    for r in read_jsonl(folder / "trials.jsonl"):
        o = out.setdefault(r["object"], {"n": 0, "ok": 0, "success": 0, "damaged": 0, "forces": [], "grasp": [],
                                         "warnings": 0, "errors": 0})
        o["n"] += 1
        o["warnings"] += r["warnings"]
        if r["status"] != "ok":
            o["errors"] += r["status"] == "error"
            continue
        o["ok"] += 1
        o["success"] += bool(r["success"])
        o["damaged"] += bool(r["damaged"])
        o["forces"].append(r["peak_total_force_N"])
        if r.get("grasp_time_s") is not None:
            o["grasp"].append(r["grasp_time_s"])
    return out


def _med(values: list[float], fmt: str) -> str:
    return format(statistics.median(values), fmt) if values else "-"


def bench_table(cable: Path, pneumatic: Path) -> str:
    a, b = _bench_rows(cable), _bench_rows(pneumatic)
    lines = ["| object | success cable / pneumatic | damaged cable / pneumatic | peak force median [N] cable / "
             "pneumatic | time to grasp median [s] cable / pneumatic | MuJoCo warnings |",
             "|---|---|---|---|---|---|"]
    for obj in a:
        x, y = a[obj], b.get(obj)
        if y is None:
            continue
        lines.append(f"| {obj} | {x['success']}/{x['n']} / {y['success']}/{y['n']} | {x['damaged']} / {y['damaged']} | "
                     f"{_med(x['forces'], '.1f')} / {_med(y['forces'], '.1f')} | "
                     f"{_med(x['grasp'], '.2f')} / {_med(y['grasp'], '.2f')} | {x['warnings']} / {y['warnings']} |")
    return "\n".join(lines)


def envelope_table(cable: Path, pneumatic: Path) -> str:
    a, b = (json.loads((f / "summary.json").read_text()) for f in (cable, pneumatic))
    lines = ["| shape | gripping range at 50 g, cable / pneumatic [mm] | payload cable / pneumatic [kg] |",
             "|---|---|---|"]

    def rng(s):
        r = s["gripping_range_m"]
        return f"{r[0] * 1e3:g}-{r[1] * 1e3:g}" if r else "none"

    def pay(s):
        return f"{s['payload_kg']:g}" if s["payload_kg"] is not None else "none"

    for shape, s in a["shapes"].items():
        t = b["shapes"].get(shape)
        if t is not None:
            lines.append(f"| {shape} | {rng(s)} / {rng(t)} | {pay(s)} / {pay(t)} |")
    return "\n".join(lines)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cable", type=Path)
    ap.add_argument("pneumatic", type=Path)
    ap.add_argument("--envelopes", nargs=2, type=Path, metavar=("CABLE", "PNEUMATIC"))
    args = ap.parse_args()
    print(bench_table(args.cable, args.pneumatic))
    if args.envelopes:
        print()
        print(envelope_table(*args.envelopes))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
