"""Plots of a design study: each response against each varied parameter.

Example:
    >>> from gripper.render.study_plots import parameter_plots  # doctest: +SKIP
"""

from __future__ import annotations

from functools import partial
from pathlib import Path
from typing import Any

import numpy as np

from gripper.core.atomic import write_atomic

# The bending curves' abscissas: a cable finger's shortening rate, or an actuator's pressure
CURVE_AXES = {"r": "cable shortening rate r [-]", "pressure_kPa": "pressure [kPa]"}


def parameter_plots(series: dict[str, list[tuple[float, dict]]], names: list[str], out: Path, *, title: str,
                    connect: bool) -> list[Path]:
    """One PNG per varied parameter: each scalar response (``names``) against the parameter,
    plus the bending curves of its points (against the cable's shortening or the actuator's
    pressure: paper 001 Figs. 12-16 style). ``series``: per
    parameter, (value, point record) in value order; ``connect``: join the points (a
    one-at-a-time sweep) or scatter them."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    files = []
    for key, pts in series.items():
        if not pts:
            continue
        has_curve = any(r["curves"] for _, r in pts)
        n = len(names) + int(has_curve)
        ncol = min(n, 4)
        nrow = -(-n // ncol)
        fig, axes = plt.subplots(nrow, ncol, figsize=(3.6 * ncol, 3.2 * nrow), squeeze=False)
        flat = list(axes.ravel())
        for ax in flat[n:]:
            ax.axis("off")
        xs = [v for v, _ in pts]
        for ax, name in zip(flat, names, strict=False):
            ys = [r["metrics"].get(name) for _, r in pts]
            ys = [np.nan if y is None else y for y in ys]
            ax.plot(xs, ys, "o-" if connect else "o")
            ax.set_xlabel(key)
            ax.set_title(name, fontsize=9)
            ax.grid(alpha=0.3)
        if has_curve:
            ax = flat[n - 1]
            x_key, x_label = next((k, lbl) for k, lbl in CURVE_AXES.items() if any(k in r["curves"] for _, r in pts))
            for v, r in pts:
                if r["curves"]:
                    ax.plot(r["curves"][x_key], r["curves"]["bending_angle_deg"], "o-" if connect else "-",
                            ms=3, label=f"{v:g}")
            ax.set_xlabel(x_label)
            ax.set_ylabel("bending angle [deg]")
            if len(pts) <= 12:
                ax.legend(title=key, fontsize=7, title_fontsize=7)
            ax.grid(alpha=0.3)
        fig.suptitle(f"{title}: {key}")
        fig.tight_layout()
        path = out / f"plot_{key.replace('.', '_')}.png"
        write_atomic(path, partial(_save_png, fig))
        plt.close(fig)
        files.append(path)
    return files


def _save_png(fig: Any, tmp: Path) -> None:
    fig.savefig(tmp, dpi=90, format="png")
