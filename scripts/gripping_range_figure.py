"""The gripping-range study's table (Markdown, to stdout) and figure, from its run folder.

    .venv/bin/gripper study gripping_range --out runs/gripping_range
    .venv/bin/python scripts/gripping_range_figure.py runs/gripping_range --png docs/gripping_range.png

The table has one row per design point: its three dimensions, the gripping range per shape at
50 g (narrowest-widest held at 2 of 3), the payload at the 60 mm box, the everyday parts' and
the five default objects' success, and whether the point meets the study's limits (its
``[objective]``). The figure plots the envelope's total range against the palm radius, one line
per splay and taper, the points that meet the limits filled.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

SHAPES = ("box", "cylinder", "sphere")
OBJECTS = ("balloon", "block", "cylinder", "paper_box", "bag")
PARTS = ("die", "aa_cell", "pen")


def _mm(v) -> str:
    return "-" if v is None else f"{v * 1e3:g}"


def _rate(v) -> str:
    return "-" if v is None else f"{v:.0%}"


def meets(metrics: dict, limits) -> bool:
    """Whether a point meets every ``at_least`` / ``at_most`` limit of the study's objective."""
    for bound, key, value in limits:
        got = metrics.get(key)
        if got is None or (got < value if bound == "at_least" else got > value):
            return False
    return True


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run", type=Path, help="the study's run folder")
    ap.add_argument("--png", type=Path, help="write the figure here")
    args = ap.parse_args(argv)
    from gripper.studies.study_file import load_study

    study = load_study("gripping_range")
    limits = study.limits
    rows = [json.loads(line) for line in (args.run / "results.jsonl").read_text().splitlines() if line.strip()]
    from gripper.core.params import GripperParams

    # the run's own base design (the default of the day it ran), not today's default
    base = GripperParams.from_dict(json.loads((args.run / "study.json").read_text())["study"]["base"])
    head = ("| point | palm radius | splay | tip taper | box | cylinder | sphere | payload, 60 mm box | "
            "die / AA cell / pen | balloon / block / cylinder / paper box / bag | meets |")
    print(head)
    print("|" + "---|" * (head.count("|") - 1))
    points = []
    for r in rows:
        ch = r["changes"]
        radius = ch.get("layout.palm_radius", base.layout.palm_radius)
        tilt = ch.get("layout.mount_tilt_deg", base.layout.mount_tilt_deg)
        taper = ch.get("finger.tip_taper", base.finger.tip_taper)
        m = r.get("metrics", {})
        if r["status"] != "ok":
            print(f"| {r['point']} | {radius * 1e3:g} mm | {tilt:g}° | {taper:g} | error: {r.get('error', '')} |")
            continue
        ok = meets(m, limits)
        ranges = [f"{_mm(m.get(f'envelope_{s}_smallest_m'))}-{_mm(m.get(f'envelope_{s}_largest_m'))}" for s in SHAPES]
        payload = m.get("payload_box_60mm_kg")
        parts = " / ".join(_rate(m.get(f"part_{p}_success_rate")) for p in PARTS)
        objs = " / ".join(_rate(m.get(f"grasp_{o}_success_rate")) for o in OBJECTS)
        print(f"| {r['point']} | {radius * 1e3:g} mm | {tilt:g}° | {taper:g} | {ranges[0]} | {ranges[1]} | "
              f"{ranges[2]} | {'-' if payload is None else f'{payload:g} kg'} | {parts} | {objs} | "
              f"{'yes' if ok else 'no'} |")
        points.append((radius, tilt, taper, m.get("envelope_range_m"), ok))
    if args.png:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(7, 4.2))
        for tilt in sorted({p[1] for p in points}):
            for taper, style in ((1.0, "--"), (0.5, "-")):
                line = sorted(p for p in points if p[1] == tilt and p[2] == taper and p[3] is not None)
                if not line:
                    continue
                xs = [p[0] * 1e3 for p in line]
                ys = [p[3] * 1e3 for p in line]
                (h,) = ax.plot(xs, ys, style, label=f"splay {tilt:g}°, tip taper {taper:g}")
                for p, x, y in zip(line, xs, ys, strict=True):
                    ax.plot(x, y, "o", color=h.get_color(), mfc=h.get_color() if p[4] else "white")
        ax.set_xlabel("palm radius [mm]")
        ax.set_ylabel("envelope range, summed over shapes [mm]")
        ax.set_title("gripping range by design (filled: meets the study's limits)")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(args.png, dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main())
