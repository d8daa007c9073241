"""Calibration inputs: every bad input refused in one line, fits at their bounds reported.

Limits come from the physics in the code: the servo's highest cable tension is its datasheet
stall torque over the spool radius (hobby_6v, MG996R class: 11 kgf·cm at 6 V, 20 mm spool,
53.9 N), a bench's element angles lie between straight (0°) and every cut closed, and the hinge
fit's bounds are ``FitConfig``'s.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest

from gripper.calibration import pipeline
from gripper.calibration.fit import FitConfig, bound_warnings, check_held_out, fit_hinges
from gripper.calibration.measured import MAX_BENDING_DEG, angle_columns, read_measured_csv
from gripper.core.params import GripperParams
from gripper.core.resources import CALIBRATION_EXAMPLES_DIR
from gripper.datasheets.servo import servo_datasheet
from gripper.references.continuum import CLOSED_CUT_MARGIN_DEG, ReferenceConfig

P = GripperParams()
N_SEG = P.finger.n_segments
N_HINGES = P.finger.n_hinges
CLOSURE = P.finger.closure_angle_deg
ARM = P.finger.hole_height - P.finger.hinge_z  # m, the cable's lever about each hinge
KGF_CM = 9.80665 * 0.01  # N·m per kgf·cm
# MG996R datasheet: 11 kgf·cm stall torque at 6 V; the default spool has a 20 mm radius.
T_MAX = 11.0 * KGF_CM / 0.020  # N, 53.94 N
EXAMPLE = CALIBRATION_EXAMPLES_DIR / "example_bench.csv"
HEADER = "tension_N," + ",".join(angle_columns(N_SEG))


def _rows(tensions, stiffness):
    """Bench rows of a rigid-element spring chain: every hinge turns T·arm/K [deg], the element
    angles are their running sums."""
    out = []
    for t in tensions:
        hinge = math.degrees(t * ARM / stiffness)
        out.append(f"{t:.6g}," + ",".join(f"{hinge * (j + 1):.4f}" for j in range(N_HINGES)))
    return out


def _write(tmp_path, lines, name="bench.csv"):
    f = tmp_path / name
    f.write_text("\n".join(lines) + "\n")
    return f


def _read(f):
    return read_measured_csv(f, N_SEG, min_points=N_HINGES, closure_angle_deg=CLOSURE,
                             max_tension_N=P.servo.max_cable_tension)


def _one_line(excinfo):
    msg = str(excinfo.value)
    assert "\n" not in msg, msg
    return msg


def test_servo_range_is_the_datasheet_stall_tension():
    ds = servo_datasheet(P.servo.preset)
    assert ds.stall_torque == pytest.approx(11.0 * KGF_CM, rel=1e-9)
    assert P.servo.max_cable_tension == pytest.approx(T_MAX, rel=1e-9)


# A soft finger (K = 0.007 N·m/rad, about the calibrated default's) at tensions a bench uses.
GOOD = _rows([0.05, 0.10, 0.15, 0.20, 0.25], 0.007)


@pytest.mark.parametrize("lines, pattern", [
    pytest.param([HEADER] + [f"0,{','.join(['0'] * N_HINGES)}"] * 5,
                 r"row 2, column tension_N: 0 N; allowed 0 < tension_N <= 53.94 N", id="all-zero-tension"),
    pytest.param([HEADER] + GOOD[:2] + [f"1e300,{GOOD[2].split(',', 1)[1]}"] + GOOD[3:],
                 r"row 4, column tension_N: 1e\+300 N; allowed 0 < tension_N <= 53.94 N", id="tension-1e300"),
    pytest.param([HEADER] + GOOD[:4] + [f"{1.01 * T_MAX:.4f},{GOOD[4].split(',', 1)[1]}"],
                 r"row 6, column tension_N: 54.48 N; .*servo's maximum cable tension", id="above-servo-range"),
    pytest.param([HEADER] + GOOD[:1] + ["0.1," + ",".join(["-5"] * N_HINGES)] + GOOD[2:],
                 r"row 3, column angle_B2_deg: -5°; allowed 0 to 223.6°", id="negative-angles"),
    pytest.param([HEADER.replace("angle_B4_deg", "angle_B3_deg")] + GOOD,
                 r"column 'angle_B3_deg' appears twice in the header", id="duplicated-column"),
    pytest.param([HEADER + ",tension_N"] + [r + ",0.1" for r in GOOD],
                 r"column 'tension_N' appears twice", id="duplicated-tension"),
    pytest.param([HEADER] + GOOD[:4] + ["0.3," + ",".join(["1e300"] * N_HINGES)],
                 r"row 6, column angle_B2_deg: 1e\+300°; allowed 0 to 223.6°", id="angle-1e300"),
    pytest.param([HEADER] + [f"{t},{r.split(',', 1)[1]}"
                             for t, r in zip((0.25, 0.2, 0.15, 0.1, 0.05), GOOD, strict=True)],
                 r"column angle_B6_deg: the bending does not grow with tension \(least-squares slope -",
                 id="bending-falls-with-tension"),
])
def test_bad_bench_csv_is_refused_in_one_line(tmp_path, lines, pattern):
    f = _write(tmp_path, lines)
    with pytest.raises(ValueError, match=pattern) as e:
        _read(f)
    assert _one_line(e).startswith("data file bench.csv: ")


def test_the_limits_are_the_physical_ones(tmp_path):
    """At the servo's stall tension and with every cut at its closure angle (within the 2°
    reading margin) a row is accepted; just beyond either, refused. Without the design's
    closure angle the angles are bounded by a full turn."""
    stiff = _rows([10.0, 20.0, 30.0, 40.0], 1.0) + _rows([0.999 * T_MAX], 1.0)
    assert len(_read(_write(tmp_path, [HEADER] + stiff)).static) == 5
    closed = CLOSURE + CLOSED_CUT_MARGIN_DEG - 0.05  # deg per hinge, just inside the margin
    full = f"{T_MAX * 0.99:.4f}," + ",".join(f"{closed * (j + 1):.3f}" for j in range(N_HINGES))
    assert len(_read(_write(tmp_path, [HEADER] + stiff[:4] + [full])).static) == 5
    assert N_HINGES * (CLOSURE + CLOSED_CUT_MARGIN_DEG) == pytest.approx(223.6, abs=0.05)
    over = "0.3," + ",".join(f"{(j + 1) * 20 + 300:.0f}" for j in range(N_HINGES))
    f = _write(tmp_path, [HEADER] + GOOD[:4] + [over])
    with pytest.raises(ValueError, match=rf"allowed 0 to {MAX_BENDING_DEG:.1f}° .*a full turn"):
        read_measured_csv(f, N_SEG, min_points=N_HINGES)
    with pytest.raises(ValueError, match=r"tension_N: 60 N; allowed 0 < tension_N <= 53.94 N"):
        read_measured_csv(_write(tmp_path, [HEADER] + GOOD[:4] + ["60" + GOOD[4][4:]]), N_SEG)


def test_example_bench_data_still_reads_and_fits_without_warnings(tmp_path):
    said = []
    cal, fit, rec = pipeline.calibrate(tmp_path / "cal", data=EXAMPLE, on_progress=said.append)
    assert len(rec.static) == 5
    assert cal.metrics["warnings"] == [] and not any(s.startswith("warning:") for s in said)
    assert json.loads((tmp_path / "cal" / "calibration.json").read_text())["metrics"]["warnings"] == []
    lo, hi = FitConfig().stiffness_bounds
    assert all(lo * 10 < k < hi / 10 for k in fit.stiffness)  # well inside the bounds


@pytest.mark.parametrize("factor, side", [(30.0, "upper"), (1 / 30.0, "lower")])
def test_a_fit_driven_to_its_bounds_warns(tmp_path, factor, side):
    """Data of a chain 30 times stiffer than the upper stiffness bound (or 30 times softer than
    the lower) put every hinge at that bound: the calibration says so, in its file and on the
    terminal, one line each."""
    lo, hi = FitConfig().stiffness_bounds
    k_data = hi * factor if side == "upper" else lo * factor
    # tensions that keep the soft chain's cuts open: hinge T·arm/K below half the closure angle
    t_top = min(0.9 * T_MAX, 0.5 * math.radians(CLOSURE) * k_data / ARM)
    f = _write(tmp_path, [HEADER] + _rows(t_top * np.arange(1, 6) / 5, k_data))
    said = []
    cal, fit, _ = pipeline.calibrate(tmp_path / "cal", data=f, fit=FitConfig(fit_damping=False, held_out=()),
                                     on_progress=said.append)
    bound = hi if side == "upper" else lo
    np.testing.assert_allclose(fit.stiffness, bound, rtol=1e-6)
    (line,) = cal.metrics["warnings"]
    assert f"{side} bound {bound:g} N·m/rad" in line and "B1-B2" in line and "\n" not in line
    stored = json.loads((tmp_path / "cal" / "calibration.json").read_text())["metrics"]["warnings"]
    assert stored == [line]
    assert [s for s in said if s.startswith("warning: ")] == [f"warning: {line}"]


def test_bound_warnings_tolerance_and_damping():
    cfg = FitConfig()
    lo, hi = cfg.stiffness_bounds
    k = np.array([hi * (1 - 5e-7), 0.01, 0.01, lo * (1 + 5e-7), 0.01])
    c = np.array([1e-4, cfg.damping_bounds[0], 1e-4, 1e-4, 1e-4])
    w = bound_warnings(k, c, cfg)
    assert len(w) == 3
    assert "hinge B1-B2 ended at the upper bound" in w[1] and "hinge B4-B5 ended at the lower" in w[0]
    assert "damping of hinge B2-B3 ended at the lower bound" in w[2]
    # 1e-4 off a bound is a fitted value, not the bound
    assert bound_warnings(np.array([hi, lo, 0.01, 0.01, 0.01]) * np.array([1 - 1e-4, 1 + 1e-4, 1, 1, 1]),
                          None, cfg) == []
    assert bound_warnings(np.full(5, 0.01), c, FitConfig(damping_bounds=(1e-8, 1.0))) == []


@pytest.mark.parametrize("held, pattern", [
    ((99,), r"--held-out: level 99 does not exist; allowed: distinct levels in 0\.\.4 \(5 load levels\)"),
    ((-1,), r"--held-out: level -1 does not exist; allowed: distinct levels in 0\.\.4"),
    ((2, 2), r"--held-out: level 2 is given twice; allowed: distinct levels in 0\.\.4"),
    ((0, 1, 2, 3, 4), r"--held-out: 5 of 5 levels held out leaves 0 to fit, fewer than 1; allowed"),
    ((1.5,), r"--held-out \(fit.held_out\): must be a list of load level indices"),
])
def test_held_out_out_of_range_is_refused(tmp_path, held, pattern):
    with pytest.raises(ValueError, match=pattern) as e:
        pipeline.calibrate(tmp_path / "cal", data=EXAMPLE, fit=FitConfig(fit_damping=False, held_out=held))
    _one_line(e)
    assert list(tmp_path.iterdir()) == []  # refused before anything was written
    if not isinstance(held[0], float):
        rec = _read(EXAMPLE)
        with pytest.raises(ValueError, match=pattern.split(";")[0]):
            fit_hinges(rec, P, FitConfig(fit_damping=False, held_out=held))


def test_held_out_needs_enough_levels_left_for_a_tip_only_fit():
    """Tip-only bench rows give two residuals each: five hinge springs need three rows."""
    check_held_out((0, 1), 5, min_fit_levels=3)
    with pytest.raises(ValueError, match=r"3 of 5 levels held out leaves 2 to fit, fewer than 3; "
                                         r"allowed: distinct levels in 0\.\.4 \(5 load levels\), at most 2"):
        check_held_out((0, 1, 2), 5, min_fit_levels=3)
    with pytest.raises(ValueError, match=r"allowed: none \(the fit needs all 1 load level"):
        check_held_out((0,), 1)


def test_held_out_is_checked_before_the_reference_run(tmp_path, monkeypatch):
    """The levels are known from ReferenceConfig.n_levels: a bad --held-out stops at once,
    before the convergence study and the reference run (minutes)."""
    import gripper.references.convergence as convergence

    def never(*a, **k):
        raise AssertionError("the slow run started")

    monkeypatch.setattr(pipeline, "run_reference", never)
    monkeypatch.setattr(convergence, "mesh_convergence", never)
    with pytest.raises(ValueError, match=r"--held-out: level 9 does not exist; .* 0\.\.4 \(5 load"):
        pipeline.calibrate(tmp_path / "cal", fit=FitConfig(held_out=(9,)))
    with pytest.raises(ValueError, match=r"--held-out: level 3 does not exist; .* 0\.\.2 \(3 load"):
        pipeline.calibrate(tmp_path / "cal", reference=ReferenceConfig(n_levels=3),
                           fit=FitConfig(held_out=(2, 3)), converge=False)
    assert list(tmp_path.iterdir()) == []


def test_cli_refuses_held_out_99_in_one_line(tmp_path):
    out = tmp_path / "cal"
    proc = subprocess.run([sys.executable, "-m", "gripper.cli.main", "calibrate", "--held-out", "99",
                           "--out", str(out)], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2, proc.stderr
    (line,) = proc.stderr.strip().splitlines()
    assert "--held-out: level 99 does not exist" in line and "0..4" in line
    assert not out.exists()


def test_quick_look_tension_keeps_the_cuts_open():
    """Without the convergence study the continuum run takes its highest tension from its own
    mesh's small-load compliance: the average hinge turns half its closure angle (to the three
    significant figures of the tension), below the 0.25 N default of the 0.5.x design that
    closed the default design's cuts (the --no-converge failure)."""
    from gripper.references.convergence import linear_compliance

    cfg = ReferenceConfig()
    t = pipeline.quick_tension_max(P, cfg)
    res = linear_compliance(P, cfg.mesh, clamp_length=cfg.clamp_length)
    per_hinge = res["compliance_deg_per_N"] / N_HINGES  # deg/N
    assert t * per_hinge == pytest.approx(pipeline.AUTO_CLOSURE_FRACTION * CLOSURE, rel=5e-3)
    largest = max(np.diff(res["element_compliance_deg_per_N"]))  # deg/N, the most compliant hinge
    assert t * largest < 0.6 * CLOSURE < cfg.tension_max * largest


def test_auto_tension_with_a_given_reference(tmp_path, monkeypatch):
    """A caller that passes a ReferenceConfig for other settings (levels) can still have the
    tension set from the design (auto_tension=True); without it, the given tension is run."""
    class Ran(Exception):
        pass

    def capture(p, cfg, **kwargs):
        raise Ran(cfg.tension_max)

    monkeypatch.setattr(pipeline, "run_reference", capture)
    ref = ReferenceConfig(n_levels=4)
    with pytest.raises(Ran) as auto:
        pipeline.calibrate(tmp_path / "cal", reference=ref, converge=False, auto_tension=True)
    assert auto.value.args[0] == pipeline.quick_tension_max(P, ref) < 0.5 * ref.tension_max
    with pytest.raises(Ran) as given:
        pipeline.calibrate(tmp_path / "cal", reference=ref, converge=False)
    assert given.value.args[0] == ref.tension_max
    assert list(tmp_path.iterdir()) == []


@pytest.mark.slow
def test_no_converge_quick_look_runs_with_default_settings(tmp_path):
    """``gripper calibrate --no-converge`` as documented (about 1.5 minutes on 2 cores)."""
    said = []
    cal, _, record = pipeline.calibrate(tmp_path / "calq", converge=False, on_progress=said.append)
    assert cal.settings["run"]["tension_max"] == pipeline.quick_tension_max(P, ReferenceConfig())
    assert (np.diff(record.element_angles_deg, axis=1).max()) < CLOSURE
    assert cal.metrics["warnings"] == []
