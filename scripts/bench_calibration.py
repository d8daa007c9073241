"""Calibration benchmark: reference and fit wall times, the hinge model's speed-up measured in
the same run, the uniform-beam check and the mesh-convergence table.

    .venv/bin/python scripts/bench_calibration.py [--out runs/bench_calibration] [--skip-fine]

Prints figures and writes ``results.json`` (plus the calibration report) into ``--out``.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path

import numpy as np

from gripper.bending import BendingConfig, run_bending_test
from gripper.calibration.calfile import apply_calibration
from gripper.calibration.fit import STATIC_SETTLE_TAU, HingeSimulator
from gripper.calibration.mesh import MeshResolution
from gripper.calibration.pipeline import calibrate
from gripper.calibration.reference import beam_end_moment_check, static_bend
from gripper.params import GripperParams


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", default="runs/bench_calibration")
    ap.add_argument("--skip-fine", action="store_true", help="skip the finer mesh (slow)")
    ap.add_argument("--checks-only", action="store_true",
                    help="only the beam check and the convergence table")
    args = ap.parse_args()
    out = Path(args.out)
    results: dict = {}
    p = GripperParams()

    if not args.checks_only:
        reference_and_fit(out, p, results)
    checks(p, results, args.skip_fine)
    out.mkdir(parents=True, exist_ok=True)
    (out / ("checks.json" if args.checks_only else "results.json")).write_text(
        json.dumps(results, indent=2) + "\n")


def reference_and_fit(out: Path, p: GripperParams, results: dict) -> None:
    t0 = time.perf_counter()
    cal, fit, record = calibrate(out, p, on_progress=print)
    results["calibrate_total_s"] = time.perf_counter() - t0
    results["reference_wall_s"] = record.wall_time_s
    results["fit_wall_s"] = fit.wall_time_s
    results["metrics"] = cal.metrics
    results["stiffness_Nm_per_rad"] = list(cal.stiffness)
    results["damping_Nms_per_rad"] = list(cal.damping)
    print(f"reference bending test {record.wall_time_s:.1f} s, fit {fit.wall_time_s:.1f} s")
    m = cal.metrics
    print(f"fit over the record: tip RMS {100 * m['tip_rms_frac']:.2f} % of length, element-angle "
          f"RMS {', '.join(f'{a:.2f}' for a in m['angle_rms_deg'])} deg; held-out "
          + ", ".join(f"{100 * h['tip_error_frac']:.2f} % tip, {100 * h['bending_error_frac']:.2f} "
                      f"% bending" for h in m["held_out"]))
    print(f"fitted finger at rest at the static points: tip RMS "
          f"{100 * m['settled']['tip_rms_frac']:.2f} % of length, bending errors "
          + ", ".join(f"{100 * lv['bending_error_frac']:.1f} %" for lv in m["settled"]["levels"]))
    results["rest_check"] = hinge_at_rest(p, fit.stiffness, 0.15)

    calibrated = apply_calibration(p, out / "calibration.json")
    cfg = BendingConfig(r_max=0.1)  # the paper's 2 s at 5e-4 s, same step as the reference
    hinge = [run_bending_test(cfg, calibrated).wall_time_s for _ in range(5)]
    results["hinge_bending_median_s"] = statistics.median(hinge)
    results["speedup"] = record.wall_time_s / statistics.median(hinge)
    print(f"calibrated hinge bending test median {statistics.median(hinge):.4f} s: "
          f"{results['speedup']:.0f}x faster than the reference")



def hinge_at_rest(p: GripperParams, stiffness, tension: float) -> float:
    """Bending angle [deg] of the calibrated hinge finger at rest under ``tension`` [N],
    to set beside the reference's static bend at the same tension."""
    sim = HingeSimulator(p, 5e-4)
    k = np.asarray(stiffness)
    (ang, _, _), = sim.run(k[:, None], (STATIC_SETTLE_TAU * k)[:, None], np.full(200, tension),
                           np.array([199]), static=True)
    return float(ang[0, -1])


# The convergence check's finer mesh: 1.5x the cells along each element, where the bridges bend
# (refining along x changed the bending most; a full scale-2 mesh has 8x the cells and is too slow).
FINER = MeshResolution(along=6)


def checks(p: GripperParams, results: dict, skip_fine: bool) -> None:
    results["beam"] = {}
    for name, mesh in {"default": MeshResolution(),
                       "kuhn6 (locking)": MeshResolution(split="kuhn6")}.items():
        b = beam_end_moment_check(p, mesh)
        results["beam"][name] = b
        print(f"beam, {name} mesh ({b['nodes']} nodes): neutral-axis curvature / closed form "
              f"{b['curvature_ratio']:.3f}, loaded-face rotation / closed form {b['ratio']:.3f}, "
              f"tip error {100 * b['tip_error_frac']:.1f} % of length ({b['wall_time_s']:.0f} s)")
    meshes = {"default": MeshResolution()}
    if not skip_fine:
        meshes["finer"] = FINER
    results["convergence"] = {}
    for name, mesh in meshes.items():
        s = static_bend(p, mesh)
        results["convergence"][name] = s
        print(f"finger at 0.15 N, {name} mesh ({s['nodes']} nodes): bending "
              f"{s['bending_angle_deg']:.2f} deg, tip {s['tip_xz_m']} m, at rest after "
              f"{s['settle_time_s']:.1f} s within {s['max_speed']:.1e} m/s "
              f"({s['wall_time_s']:.0f} s)")
    if "rest_check" in results:
        print(f"calibrated hinge finger at rest at 0.15 N: {results['rest_check']:.2f} deg; "
              f"reference at rest: {results['convergence']['default']['bending_angle_deg']:.2f} deg")
    if "finer" in results["convergence"]:
        a = results["convergence"]["default"]["bending_angle_deg"]
        b = results["convergence"]["finer"]["bending_angle_deg"]
        results["convergence_change"] = abs(b - a) / abs(b)
        print(f"bending (tip) angle change default -> finer: "
              f"{100 * results['convergence_change']:.1f} %")


if __name__ == "__main__":
    main()
