"""Calibration report: reference against fitted bending curves (PNG) and a per-element table.

Example:
    >>> write_report("runs/calibration", record, fit)   # doctest: +SKIP
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from gripper.calibration.fit import FitResult
from gripper.references.continuum import BendingRecord


def error_table(record: BendingRecord, fit: FitResult) -> list[dict]:
    """Per element B2..Bn: RMS and largest angle error over the fitted samples [deg]."""
    ref = record.element_angles_deg - record.element_angles_deg[:, :1]
    got = fit.fitted.element_angles_deg
    rows = []
    for j in range(1, ref.shape[1]):
        d = got[:, j] - ref[:, j]
        ok = np.isfinite(d)
        rows.append({
            "element": f"B{j + 1}",
            "hinge_stiffness_Nm_per_rad": float(fit.stiffness[j - 1]),
            "hinge_stiffness_Nm_per_deg": float(np.radians(fit.stiffness[j - 1])),
            "hinge_damping_Nms_per_rad": float(fit.damping[j - 1]),
            "angle_rms_deg": float(np.sqrt(np.mean(d[ok] ** 2))) if ok.any() else None,
            "angle_max_deg": float(np.abs(d[ok]).max()) if ok.any() else None,
        })
    return rows


def format_table(rows: list[dict]) -> str:
    head = (f"{'element':>7} {'K N·m/rad':>10} {'K N·m/deg':>10} {'c N·m·s/rad':>12} "
            f"{'RMS deg':>8} {'max deg':>8}")
    lines = [head]
    for r in rows:
        rms = "-" if r["angle_rms_deg"] is None else f"{r['angle_rms_deg']:.2f}"
        mx = "-" if r["angle_max_deg"] is None else f"{r['angle_max_deg']:.2f}"
        lines.append(f"{r['element']:>7} {r['hinge_stiffness_Nm_per_rad']:10.4g} "
                     f"{r['hinge_stiffness_Nm_per_deg']:10.3g} "
                     f"{r['hinge_damping_Nms_per_rad']:12.3g} {rms:>8} {mx:>8}")
    return "\n".join(lines)


def write_report(out_dir: str | Path, record: BendingRecord, fit: FitResult,
                 title: str = "reference") -> list[Path]:
    """Write ``report.png`` and ``errors.csv`` into ``out_dir``; return their paths."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    ref = record.element_angles_deg - record.element_angles_deg[:, :1]
    got = fit.fitted.element_angles_deg
    static = record.static
    transient = np.isfinite(got[:, -1]).sum() > len(static)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    ax = axes[0]
    colors = plt.cm.viridis(np.linspace(0, 0.9, ref.shape[1] - 1))
    for j in range(1, ref.shape[1]):
        if transient:
            ax.plot(record.t, ref[:, j], color=colors[j - 1], lw=1.5, label=f"B{j + 1} {title}")
            ax.plot(record.t, got[:, j], "--", color=colors[j - 1], lw=1.2)
        else:
            ax.plot(record.tension_N[static], ref[static, j], "o", color=colors[j - 1],
                    label=f"B{j + 1} {title}")
            ax.plot(record.tension_N[static], got[static, j], "--", color=colors[j - 1])
    ax.set_xlabel("time [s]" if transient else "cable tension [N]")
    ax.set_ylabel("element angle [deg]")
    ax.set_title("element angles: solid/dots = " + title + ", dashed = fitted hinge model")
    ax.legend(fontsize=7, ncol=2)
    ax = axes[1]
    ax.plot(record.tension_N[static], ref[static, -1], "ko", label=f"{title} (static points)")
    ax.plot(record.tension_N[static], got[static, -1], "r--s", label="fitted hinge model")
    for h in fit.config.held_out:
        if 0 <= h < len(static):
            ax.plot(record.tension_N[static[h]], ref[static[h], -1], "o", mfc="none", ms=14,
                    mec="tab:blue", label="held out of the fit")
    ax.set_xlabel("cable tension [N]")
    ax.set_ylabel("bending angle B1→Bn [deg]")
    ax.set_title("bending curve")
    ax.legend(fontsize=8)
    fig.tight_layout()
    png = out / "report.png"
    fig.savefig(png, dpi=110)
    plt.close(fig)
    rows = error_table(record, fit)
    csv_path = out / "errors.csv"
    keys = list(rows[0])
    csv_path.write_text(",".join(keys) + "\n" + "\n".join(
        ",".join("" if r[k] is None else str(r[k]) for k in keys) for r in rows) + "\n")
    return [png, csv_path]
