"""Calibration benchmark: each reference kind's run time, the fit's time (median of repeats),
the fit's accuracy, and the calibrated hinge model's speed-up, measured in one run.

    .venv/bin/python scripts/bench_calibration.py [--out runs/bench_calibration] [--fit-repeats 3]
        [--kinds continuum,fmbs_per_degree,fmbs_per_radian]

Prints one row per reference kind and writes ``results.json`` (and each calibration folder)
into ``--out``. The continuum row includes its mesh-convergence study (four linear solves).
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path

from gripper.calibration.calfile import apply_calibration
from gripper.calibration.fit import FitConfig, fit_hinges
from gripper.calibration.pipeline import calibrate
from gripper.core.params import GripperParams
from gripper.experiments.bending import BendingConfig, run_bending_test
from gripper.references.fmbs import FmbsConfig

KINDS = {"continuum": ("continuum", None),
         "fmbs_per_degree": ("fmbs", FmbsConfig(reading="per_degree")),
         "fmbs_per_radian": ("fmbs", FmbsConfig(reading="per_radian"))}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", default="runs/bench_calibration")
    ap.add_argument("--fit-repeats", type=int, default=3)
    ap.add_argument("--kinds", default=",".join(KINDS))
    args = ap.parse_args()
    out = Path(args.out)
    p = GripperParams()
    results: dict = {}
    for name in args.kinds.split(","):
        kind, fmbs = KINDS[name]
        t0 = time.perf_counter()
        cal, fit, record = calibrate(out / name, p, kind=kind, fmbs=fmbs, on_progress=print)
        total = time.perf_counter() - t0
        fits = [fit.wall_time_s] + [fit_hinges(record, p, FitConfig()).wall_time_s
                                    for _ in range(args.fit_repeats - 1)]
        calibrated = apply_calibration(p, out / name / "calibration.json")
        hinge = statistics.median(run_bending_test(BendingConfig(r_max=0.1), calibrated).wall_time_s
                                  for _ in range(5))
        m = cal.metrics
        results[name] = {
            "total_s": total, "reference_run_s": record.wall_time_s,
            "convergence_s": None, "fit_median_s": statistics.median(fits), "fit_s": fits,
            "stiffness_Nm_per_rad": list(cal.stiffness), "damping_Nms_per_rad": list(cal.damping),
            "tip_rms_frac": m["tip_rms_frac"],
            "held_out_tip_frac": [h["tip_error_frac"] for h in m["held_out"]],
            "tension_max_N": cal.settings["run"]["tension_max"],
            "speedup": record.wall_time_s / hinge, "warnings": record.warnings}
        conv = out / name / "convergence.json"
        if conv.exists():
            results[name]["convergence_s"] = json.loads(conv.read_text())["wall_time_s"]
    print(f"\n{'reference':>16} {'conv s':>7} {'run s':>7} {'fit s (median)':>15} {'tip RMS':>8} "
          f"{'held-out tip':>13} {'K N·m/rad':>24} {'speed-up':>9}")
    for name, r in results.items():
        k = f"{min(r['stiffness_Nm_per_rad']):.4g}-{max(r['stiffness_Nm_per_rad']):.4g}"
        conv = f"{r['convergence_s']:.0f}" if r["convergence_s"] else "-"
        print(f"{name:>16} {conv:>7} {r['reference_run_s']:7.0f} {r['fit_median_s']:15.1f} "
              f"{100 * r['tip_rms_frac']:7.2f}% "
              f"{', '.join(f'{100 * h:.2f}%' for h in r['held_out_tip_frac']):>13} {k:>24} "
              f"{r['speedup']:8.0f}x")
    out.mkdir(parents=True, exist_ok=True)
    (out / "results.json").write_text(json.dumps(results, indent=2) + "\n")


if __name__ == "__main__":
    main()
