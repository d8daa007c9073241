"""Write the example bench CSV (``gripper/data/calibration/example_bench.csv``) from a reference run.

Takes the ``reference.json`` that ``gripper calibrate`` writes next to the calibration file and
keeps the end of each tension hold (the quasi-static points), with the angles rounded to 0.1°
and the tip to 0.1 mm, as a protractor and a ruler would read them. Not a physical measurement.

Run: .venv/bin/python scripts/make_example_bench.py runs/calibration/reference.json \\
         gripper/data/calibration/example_bench.csv
"""

import argparse
import json
from pathlib import Path

from gripper.calibration.measured import angle_columns


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("reference", help="reference.json written by gripper calibrate")
    ap.add_argument("out", help="CSV to write")
    args = ap.parse_args()
    rec = json.loads(Path(args.reference).read_text())
    n_seg = len(rec["element_angles_deg"][0])
    lines = [
        "# Example bench data for gripper calibrate --data (format: gripper/calibration/measured.py).",
        "# Made by scripts/make_example_bench.py from the default reference run (gripper calibrate,",
        "# default design and settings): the end of each tension hold, angles rounded to 0.1 deg",
        "# and tip to 0.1 mm, as a protractor and a ruler would read them. Not a physical measurement.",
        "tension_N,r," + ",".join(angle_columns(n_seg)) + ",tip_x_m,tip_z_m",
    ]
    for i in rec["static"]:
        angles = rec["element_angles_deg"][i][1:]
        x, z = rec["tip_xz_m"][i]
        lines.append(f"{rec['tension_N'][i]:.4f},{rec['r'][i]:.4f},"
                     + ",".join(f"{a:.1f}" for a in angles) + f",{x:.4f},{z:.4f}")
    Path(args.out).write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
