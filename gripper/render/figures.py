"""Pictures: the bending montage (paper 000's Fig. 5 style) and the benchmark success plot.

Plots use matplotlib's headless ``Agg`` backend; files are written atomically (temporary name,
then moved into place).

Example:
    >>> from gripper.render.figures import bending_figure
    >>> bending_figure("bend.png")                # doctest: +SKIP
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from gripper.core.atomic import check_output_file, write_atomic

# Cable shortening rates shown in the montage: six evenly spaced points from straight to the
# bending test's r_max.
MONTAGE_PANELS = 6


def check_png_path(out: str | Path, flag: str) -> Path:
    """The output path if a PNG can be written there, else ValueError naming ``flag``."""
    return check_output_file(out, flag, (".png",))


def _save(fig, out: Path) -> None:
    write_atomic(out, lambda tmp: fig.savefig(tmp, dpi=100, format="png"))


def bending_figure(out: str | Path, config=None, params=None, *, width: int = 320, height: int = 240):
    """Run the bending test, render the finger at :data:`MONTAGE_PANELS` shortening rates from
    above (the bending plane) and plot the bending angle against r; write ``out`` (PNG).

    Returns the :class:`gripper.experiments.bending.BendingResult`.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import mujoco

    from gripper.experiments.bending import BendingConfig, run_bending_test
    from gripper.render.renderer import FreeView, SceneRenderer

    out = check_png_path(out, "--figure")
    cfg = (config or BendingConfig()).validate()
    states: list[np.ndarray] = []
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    holder = {}

    def keep(model, data):
        holder["model"] = model
        s = np.empty(mujoco.mj_stateSize(model, spec))
        mujoco.mj_getState(model, data, s, spec)
        states.append(s)

    res = run_bending_test(cfg, params, on_sample=keep)
    m = holder["model"]
    # straight down on the horizontal bending plane, framing the 96 mm finger clamped at the
    # origin (it lies along +x at 0.1 m height and curls towards +y)
    view = FreeView(lookat=(0.045, 0.025, 0.1), distance=0.17, azimuth=90.0, elevation=-90.0)
    renderer = SceneRenderer(m, width=width, height=height, camera="top", view=view)
    d = mujoco.MjData(m)
    picks = np.linspace(0, len(states) - 1, MONTAGE_PANELS).round().astype(int)
    images = []
    try:
        for i in picks:
            mujoco.mj_setState(m, d, states[i], spec)
            mujoco.mj_forward(m, d)
            images.append(renderer.render(d))
    finally:
        renderer.close()
    fig = plt.figure(figsize=(12, 6.4))
    grid = fig.add_gridspec(2, MONTAGE_PANELS, height_ratios=[1, 1.2])
    for k, i in enumerate(picks):
        ax = fig.add_subplot(grid[0, k])
        ax.imshow(images[k])
        ax.set_title(f"r = {res.r[i]:.2f}\n{res.bending_angle_deg[i]:.0f}°, {res.tension_N[i]:.1f} N", fontsize=9)
        ax.axis("off")
    ax = fig.add_subplot(grid[1, :])
    ax.plot(res.r, res.bending_angle_deg, lw=2, label="bending angle (base to tip element)")
    ax.plot(res.r[picks], res.bending_angle_deg[picks], "o", color="C3", label="montage above")
    ax.set_xlabel("cable shortening rate r [-]")
    ax.set_ylabel("bending angle [deg]")
    ax.grid(alpha=0.3)
    ax2 = ax.twinx()
    ax2.plot(res.r, res.tension_N, color="C2", lw=1, ls="--", label="cable tension")
    ax2.set_ylabel("cable tension [N]")
    ax.legend(loc="upper left", fontsize=9)
    ax2.legend(loc="lower right", fontsize=9)
    fig.suptitle(f"Bending test ({cfg.mode}, {cfg.duration:g} s, r up to {cfg.r_max:g})")
    fig.tight_layout()
    try:
        _save(fig, out)
    finally:
        plt.close(fig)
    return res


def success_plot(summary: dict, out: str | Path) -> None:
    """Success rate per object with its Wilson 95 % interval (from ``summary.json``); PNG."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = check_png_path(out, "--plot")
    names = list(summary["objects"])
    rates = np.array([summary["objects"][n]["success_rate"] or 0.0 for n in names])
    lo = np.array([summary["objects"][n]["ci95"][0] for n in names])
    hi = np.array([summary["objects"][n]["ci95"][1] for n in names])
    trials = [summary["objects"][n]["trials"] for n in names]
    fig, ax = plt.subplots(figsize=(1.4 * len(names) + 2.5, 4))
    x = np.arange(len(names))
    ax.bar(x, rates, color="C0", alpha=0.8)
    # clip: the interval's bounds can sit a rounding error inside the rate (e.g. 0.9999999 at 1)
    err = np.clip([rates - lo, hi - rates], 0.0, None)
    ax.errorbar(x, rates, yerr=err, fmt="none", ecolor="k", capsize=6, lw=1.5)
    ax.set_xticks(x, [f"{n}\n(n = {t})" for n, t in zip(names, trials, strict=True)])
    ax.set_ylim(0, 1.05)
    ax.set_ylabel("grasp success rate")
    ax.axhline(0.9, color="C3", ls=":", lw=1, label="90 % goal")
    ax.set_title("Grasp benchmark: success with Wilson 95 % intervals")
    ax.legend(loc="lower right", fontsize=9)
    fig.tight_layout()
    try:
        _save(fig, out)
    finally:
        plt.close(fig)


def holding_force_plot(results: list[dict], out: str | Path) -> None:
    """Holding force against the controller's grip set-point (cable tension, or chamber pressure for
    the pneumatic gripper), one line per object (from
    :func:`gripper.experiments.pullout.run_pullout` results); PNG. Points held at the pull's
    upper bound are drawn hollow (the holding force is at least that)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = check_png_path(out, "--plot")
    fig, ax = plt.subplots(figsize=(5.5, 3.8))
    names = list(dict.fromkeys(r["object"] for r in results))
    # the set-point of whichever drive ran (its record key; the drive's label and display unit)
    from gripper.drives.drive import drive_class, registered_drives

    drive = next((drive_class(k) for k in registered_drives()
                  if any(r.get(drive_class(k).set_point_record) is not None for r in results)), drive_class("cable"))
    key, scale = drive.set_point_record, drive.effort_display_scale
    for k, name in enumerate(names):
        rs = sorted((r for r in results if r["object"] == name and r.get(key) is not None), key=lambda r: r[key])
        if not rs:
            continue
        x = [r[key] * scale for r in rs]
        y = [r["holding_force_N"] for r in rs]
        ax.plot(x, y, "-", color=f"C{k}", label=name)
        for xi, yi, r in zip(x, y, rs, strict=True):
            ax.plot(xi, yi, "o", color=f"C{k}", mfc="none" if r["held_at_max"] else f"C{k}")
    ax.set_xlabel(f"grip set-point per finger: {drive.effort_label}")
    ax.set_ylabel("holding force (pull to 5 mm slip) [N]")
    ax.set_title("Pull-out under the grasp controller")
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=9)
    fig.tight_layout()
    try:
        _save(fig, out)
    finally:
        plt.close(fig)
