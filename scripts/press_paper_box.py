"""Mesh convergence of the paper box's face under a finger-sized press.

Prints, per mesh resolution (points along x, y, z), the peak force and the permanent dent of
:func:`gripper.experiments.press.face_press` at 2 and 4 mm.

Usage: ``.venv/bin/python scripts/press_paper_box.py 4x4x5,5x5x6,6x6x7,8x8x11``
"""

from __future__ import annotations

import sys

from gripper.experiments.press import face_press


def main() -> None:
    for t in (sys.argv[1] if len(sys.argv) > 1 else "4x4x5,5x5x6,6x6x7").split(","):
        pts = tuple(int(v) for v in t.split("x"))
        for depth in (0.002, 0.004):
            r = face_press(pts, depth)
            print(f"{t:8s} depth {1e3 * depth:.0f} mm  peak force {r['peak_force_N']:6.1f} N  "
                  f"dent {1e3 * r['dent_m']:6.3f} mm  warnings {r['warnings']}  nv {r['nv']}", flush=True)


if __name__ == "__main__":
    main()
