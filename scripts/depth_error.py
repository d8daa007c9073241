"""The palm camera's estimate against ground truth over a benchmark run's placements.

Reads a run's ``trials.jsonl`` (``gripper bench ... --out DIR``) and prints, per object, the
median and largest error of the sensed centroid against the sampled placement (x, y), of the
sensed height against the object file's height, and of the sensed support against the floor
(z = 0). The truth is the placement the trial drew before the object settled (rigid parts stay
where they land; the deformables sag a little under gravity, which shows as a lower height).

    .venv/bin/python scripts/depth_error.py runs/bench
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

from gripper.objects.library import get_object


def main(run: str) -> None:
    rows: dict[str, list[tuple[float, float, float]]] = {}
    for line in (Path(run) / "trials.jsonl").read_text().splitlines():
        r = json.loads(line)
        est = r.get("depth_estimate")
        if r.get("status") != "ok" or not est:
            continue
        obj = get_object(r["object"])
        dxy = float(np.hypot(est["x_m"] - r["perturbation"]["x_m"], est["y_m"] - r["perturbation"]["y_m"]))
        rows.setdefault(r["object"], []).append((dxy, est["height_m"] - obj.height, est["support_z_m"]))
    print("| object | trials | centroid error, median / max | height error, median / max | support, median |")
    print("|---|---|---|---|---|")
    for name, v in rows.items():
        a = np.asarray(v)
        i = int(np.argmax(np.abs(a[:, 1])))
        print(f"| {name} | {len(a)} | {np.median(a[:, 0]) * 1e3:.2f} / {a[:, 0].max() * 1e3:.2f} mm "
              f"| {np.median(a[:, 1]) * 1e3:+.2f} / {a[i, 1] * 1e3:+.2f} mm | {np.median(a[:, 2]) * 1e3:+.2f} mm |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "runs/bench")
