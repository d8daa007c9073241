"""Bench measurements as a bending record: the CSV format the fit accepts.

One row per quasi-static load point (the finger at rest under a held cable tension). Columns
(header names exactly as below, SI units, comma-separated, ``#`` lines are comments):

============== ======= ==========================================================
column         unit    meaning
============== ======= ==========================================================
tension_N      N       cable tension at the reel (required)
r              -       cable shortening rate (optional; recorded, not fitted)
angle_B2_deg   deg     rotation of element B2 from straight, positive curling to
...                    the grasping face; one column per element B2..Bn
tip_x_m        m       tip point (neutral axis at the distal face) along the finger
tip_z_m        m       tip point towards the grasping face
============== ======= ==========================================================

Either all element-angle columns or both tip columns (or both sets) must be present. Tension is
required: shortening alone fixes the kinematics, not the stiffness (any stiffness scale gives
the same angles at equal shortening), so the fit needs the load.

What a bench can measure, checked row by row (each refusal one line naming file, row, column
and the allowed range): column names unique; tension finite, > 0 (a row at zero tension carries
no stiffness) and at most the servo's maximum cable tension (stall torque / spool radius, 53.9 N
for the default ``hobby_6v`` preset and 20 mm spool); element angles finite, >= 0 (the cable
curls the finger towards its grasping face) and at most the finger's full closure (every hinge
at the cut's closure angle plus the reading margin, ``closure_angle_deg``) or, without the
design's closure angle, ``MAX_BENDING_DEG``; and the bending (angle of the last element) growing
with tension overall (positive least-squares slope).

Example:
    >>> rec = read_measured_csv("gripper/data/calibration/example_bench.csv", 6)   # doctest: +SKIP
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from gripper.core.user_files import read_user_csv
from gripper.references.continuum import CLOSED_CUT_MARGIN_DEG, BendingRecord

# Largest element angle accepted when the caller gives no closure angle [deg]: a full turn, past
# which the finger would pass through its own base. With the design's closure angle the limit is
# every hinge closed (n_hinges x (closure + CLOSED_CUT_MARGIN_DEG), 224° for the default cut).
MAX_BENDING_DEG = 360.0


def angle_columns(n_segments: int) -> list[str]:
    return [f"angle_B{j}_deg" for j in range(2, n_segments + 1)]


def read_measured_csv(path: str | Path, n_segments: int, *, min_points: int = 1,
                      closure_angle_deg: float | None = None,
                      max_tension_N: float | None = None) -> BendingRecord:
    """Read a bench CSV into a static :class:`BendingRecord` (missing observables are NaN).

    ``closure_angle_deg``: the design's closure angle [deg]; given, a row whose element angles
    put a hinge more than ``CLOSED_CUT_MARGIN_DEG`` past it is refused. The fit finds the hinge
    springs of the open cuts; past closure the squeezed teeth carry the load (gripper.drives.cable.closure),
    and fitting springs to such rows would make them too stiff.

    ``max_tension_N``: the highest tension the servo can pull [N], ``ServoParams.max_cable_tension``
    (stall torque / spool radius) of the design; None: the default design's servo (53.9 N).

    Raises:
        ValueError: one line naming the file, row and column at fault: unreadable file,
            missing or duplicated column, non-numeric or non-finite cell, fewer rows than
            ``min_points``, a tension not in (0, max_tension_N], an element angle not in
            [0, full closure], bending that does not grow with tension, or a row with a closed
            cut.
    """
    path = Path(path)
    name = path.name
    rows = read_user_csv(path, "data file")
    header = _checked_header(name, rows)
    ang_cols = angle_columns(n_segments)
    has_ang, has_tip = _observed_sets(name, header, ang_cols)
    wanted = ["tension_N"] + (["r"] if "r" in header else [])
    wanted += ang_cols if has_ang else []
    wanted += ["tip_x_m", "tip_z_m"] if has_tip else []
    values = _read_values(name, rows[1:], header, wanted)
    n = len(rows) - 1
    if n < min_points:
        raise ValueError(f"data file {name}: {n} data rows, fewer than the {min_points} "
                         f"parameters to fit")
    tension = np.array(values["tension_N"])
    _check_tensions(name, tension, max_tension_N)
    angles = np.full((n, n_segments), np.nan)
    angles[:, 0] = 0.0
    if has_ang:
        angles[:, 1:] = np.column_stack([values[c] for c in ang_cols])
        _check_angles(name, angles, ang_cols, closure_angle_deg)
        _check_bending_grows(name, angles[:, -1], tension, ang_cols[-1])
    tip = np.full((n, 2), np.nan)
    if has_tip:
        tip[:] = np.column_stack([values["tip_x_m"], values["tip_z_m"]])
    order = np.argsort(tension, kind="stable")
    rate = np.array(values["r"]) if "r" in values else np.full(n, np.nan)
    return BendingRecord(t=np.arange(n, dtype=float), tension_N=tension[order], r=rate[order],
                         element_angles_deg=angles[order], tip_xz_m=tip[order],
                         static=np.arange(n))


def _checked_header(name: str, rows: list[list[str]]) -> list[str]:
    """The header row of data file ``name``: present, its column names unique, with
    ``tension_N``."""
    if not rows:
        raise ValueError(f"data file {name}: empty; need a header row with tension_N")
    header = [h.strip() for h in rows[0]]
    seen: set[str] = set()
    for h in header:
        if h and h in seen:
            raise ValueError(f"data file {name}: column {h!r} appears twice in the header; every "
                             f"column name must be unique")
        seen.add(h)
    if "tension_N" not in header:
        raise ValueError(f"data file {name}: missing column 'tension_N' (cable tension [N]); "
                         f"shortening alone cannot fix the stiffness")
    return header


def _observed_sets(name: str, header: list[str], ang_cols: list[str]) -> tuple[bool, bool]:
    """Whether ``header`` has every element angle column and both tip columns; a partial set,
    or neither set, is refused."""
    has_ang = [c in header for c in ang_cols]
    has_tip = [c in header for c in ("tip_x_m", "tip_z_m")]
    if any(has_ang) and not all(has_ang):
        missing = [c for c, h in zip(ang_cols, has_ang, strict=True) if not h]
        raise ValueError(f"data file {name}: missing column {missing[0]!r} (need every element "
                         f"angle {ang_cols[0]}..{ang_cols[-1]} or none)")
    if any(has_tip) and not all(has_tip):
        raise ValueError(f"data file {name}: missing column "
                         f"{'tip_z_m' if has_tip[0] else 'tip_x_m'!r} (need both tip columns)")
    if not any(has_ang) and not any(has_tip):
        raise ValueError(f"data file {name}: missing columns: need {ang_cols[0]}..{ang_cols[-1]} "
                         f"or tip_x_m and tip_z_m")
    return all(has_ang), all(has_tip)


def _read_values(name: str, data_rows: list[list[str]], header: list[str], wanted: list[str]
                 ) -> dict[str, list[float]]:
    """The ``wanted`` columns of the data rows as finite numbers (the first data row is the
    file's row 2)."""
    col = {c: header.index(c) for c in wanted}
    values: dict[str, list[float]] = {c: [] for c in wanted}
    for lineno, row in enumerate(data_rows, start=2):
        if len(row) != len(header):
            raise ValueError(f"data file {name}: row {lineno} has {len(row)} cells, the header "
                             f"has {len(header)}")
        for c in wanted:
            cell = row[col[c]].strip()
            try:
                v = float(cell)
            except ValueError:
                raise ValueError(f"data file {name}: row {lineno}, column {c}: {cell!r} is not "
                                 f"a number") from None
            if not math.isfinite(v):
                raise ValueError(f"data file {name}: row {lineno}, column {c}: {cell!r} is not "
                                 f"a finite number")
            values[c].append(v)
    return values


def _check_tensions(name: str, tension: np.ndarray, max_tension_N: float | None) -> None:
    """Every tension in (0, ``max_tension_N``] [N]; None: the default design's servo's."""
    if max_tension_N is None:
        from gripper.core.params import GripperParams

        max_tension_N = GripperParams().servo.max_cable_tension
    t_range = f"allowed 0 < tension_N <= {max_tension_N:.4g} N"
    bad_t = np.flatnonzero((tension <= 0) | (tension > max_tension_N))
    if len(bad_t):
        i = int(bad_t[0])
        why = ("a bench pulls the cable: a row at zero or negative tension carries no stiffness"
               if tension[i] <= 0 else
               "the servo's maximum cable tension, stall torque / spool radius")
        raise ValueError(f"data file {name}: row {i + 2}, column tension_N: {tension[i]:.4g} N; "
                         f"{t_range} ({why})")


def _check_angles(name: str, angles: np.ndarray, ang_cols: list[str],
                  closure_angle_deg: float | None) -> None:
    """Every element angle [deg] in [0, full closure] (``MAX_BENDING_DEG`` without the design's
    closure angle) and, with it, no hinge past its cut's closure."""
    n_segments = angles.shape[1]
    if closure_angle_deg is not None:
        top = (n_segments - 1) * (closure_angle_deg + CLOSED_CUT_MARGIN_DEG)
        what = (f"every cut closed, {n_segments - 1} x ({closure_angle_deg:.1f} + "
                f"{CLOSED_CUT_MARGIN_DEG:g})°")
    else:
        top, what = MAX_BENDING_DEG, "a full turn"
    bad_a = np.argwhere((angles[:, 1:] < 0) | (angles[:, 1:] > top))
    if len(bad_a):
        r, j = (int(v) for v in bad_a[0])
        raise ValueError(
            f"data file {name}: row {r + 2}, column {ang_cols[j]}: {angles[r, j + 1]:.4g}°; "
            f"allowed 0 to {top:.1f}° (the cable curls the finger towards its grasping face, "
            f"at most {what})")
    if closure_angle_deg is not None:
        hinge = np.diff(angles, axis=1)
        closed = hinge > closure_angle_deg + CLOSED_CUT_MARGIN_DEG
        if closed.any():
            r, j = (int(v) for v in np.argwhere(closed)[0])
            raise ValueError(
                f"data file {name}: row {r + 2}: hinge B{j + 1}-B{j + 2} at {hinge[r, j]:.1f}°, "
                f"past the cut's closure angle {closure_angle_deg:.1f}°; the fit needs open "
                f"cuts, drop rows with closed cuts")


def _check_bending_grows(name: str, bend: np.ndarray, tension: np.ndarray, column: str) -> None:
    """The bending (angle of the last element, ``column``) [deg] grows with tension [N]."""
    # Overall growth: the sign of the covariance of bending (last element) and tension,
    # i.e. of their least-squares slope; noise may make single steps fall.
    n = len(bend)
    if n >= 2 and np.ptp(tension) > 0:
        dt = tension - tension.mean()
        cov = float(np.mean(dt * (bend - bend.mean())))
        if not cov > 0:
            with np.errstate(all="ignore"):
                slope = cov / float(np.mean(dt * dt))
            raise ValueError(
                f"data file {name}: column {column}: the bending does not grow with "
                f"tension (least-squares slope {slope:.3g} deg/N over {n} rows); a pull on "
                f"the cable bends the finger further, so the slope must be > 0: check the "
                f"rows' tensions and angles")


def write_measured_csv(path: str | Path, record: BendingRecord, *, comment: str = "") -> Path:
    """Write the static points of ``record`` in the bench CSV format."""
    path = Path(path)
    n_seg = record.element_angles_deg.shape[1]
    header = ["tension_N", "r"] + angle_columns(n_seg) + ["tip_x_m", "tip_z_m"]
    lines = [f"# {ln}" for ln in comment.splitlines()] + [",".join(header)]
    for i in record.static:
        ang = record.element_angles_deg[i] - record.element_angles_deg[i, 0]
        cells = [f"{record.tension_N[i]:.4f}", f"{record.r[i]:.4f}"]
        cells += [f"{a:.1f}" for a in ang[1:]]
        cells += [f"{record.tip_xz_m[i, 0]:.4f}", f"{record.tip_xz_m[i, 1]:.4f}"]
        lines.append(",".join(cells))
    path.write_text("\n".join(lines) + "\n")
    return path
