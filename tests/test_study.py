"""Design studies: workers, resume after SIGKILL, refusal of bad study files, responses."""

import subprocess
import sys

import pytest
from helpers import kill_after_lines, study_records

from gripper.cli.main import main
from gripper.core.params import GripperParams
from gripper.experiments.design_responses import measure_responses
from gripper.studies.study_file import apply_point, gent_modulus, load_study

STUDY = """
[study]
name = "test"
design = "one_at_a_time"

[vary]
"finger.hole_height" = [0.010, 0.011, 0.013, 0.014]

[responses]
bending = { r_max = 0.40 }
tension_for_angle = { angle_deg = 90.0 }
grasp = { objects = ["block"], trials = 1 }

[objective]
minimize = "tension_for_angle_N"
"""


@pytest.fixture(scope="module")
def study_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("study") / "s.toml"
    path.write_text(STUDY)
    return path


@pytest.fixture(scope="module")
def reference(study_file, tmp_path_factory):
    out = tmp_path_factory.mktemp("ref")
    assert main(["study", str(study_file), "--out", str(out), "--workers", "1", "--no-progress"]) == 0
    return out


def test_outputs_and_physics(reference):
    recs = study_records(reference)
    assert [r["point"] for r in recs] == [0, 1, 2, 3, 4] and all(r["status"] == "ok" for r in recs)
    # a longer lever arm (hole further from the hinge) needs less tension for the same bend
    t = {r["changes"].get("finger.hole_height", 0.012): r["metrics"]["tension_for_angle_N"] for r in recs}
    assert t[0.010] > t[0.012] > t[0.014]
    csv = (reference / "results.csv").read_text().splitlines()
    assert csv[0].startswith("point,finger.hole_height,status,calibrated,metric,value")
    assert (reference / "plot_finger_hole_height.png").stat().st_size > 1000
    md = (reference / "recommendations.md").read_text()
    assert "| finger.hole_height | 0.014 |" in md


def test_two_workers_same_results(study_file, reference, tmp_path):
    out = tmp_path / "w2"
    assert main(["study", str(study_file), "--out", str(out), "--workers", "2", "--no-progress"]) == 0
    assert study_records(out) == study_records(reference)


def test_sigkill_then_resume(study_file, reference, tmp_path):
    out = tmp_path / "killed"
    cmd = [sys.executable, "-m", "gripper.cli.main", "study", str(study_file), "--out", str(out), "--workers", "1",
           "--no-progress"]
    assert 2 <= kill_after_lines(cmd, out / "results.jsonl", 2) < 5
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    recs = study_records(out)
    assert [r["point"] for r in recs] == [0, 1, 2, 3, 4]  # every point exactly once
    assert recs == study_records(reference)


@pytest.mark.parametrize("edit, key, line", [
    (('"finger.hole_height"', '"finger.hole_hight"'), "finger.hole_hight", 7),
    (("[0.010, 0.011, 0.013, 0.014]", "[0.010, -0.011]"), "finger.hole_height", 7),
    (("[0.010, 0.011, 0.013, 0.014]", '["a", "b"]'), "finger.hole_height", 7),
    (('design = "one_at_a_time"', 'design = "random"'), "design", 4),
    (("trials = 1", "trials = 0"), "responses.grasp", 12),
    (("trials = 1", "trials = 1001"), "responses.grasp", 12),
    (('grasp = { objects = ["block"], trials = 1 }', 'envelope = { shapes = ["box"], mass = 500.0 }'),
     "responses.envelope", 12),
])
def test_bad_study_is_refused_before_work(tmp_path, capsys, edit, key, line):
    bad = tmp_path / "bad.toml"
    bad.write_text(STUDY.replace(*edit))
    out = tmp_path / "out"
    assert main(["study", str(bad), "--out", str(out), "--no-progress"]) == 2
    err = capsys.readouterr().err.strip()
    assert f"bad.toml:{line}: {key}" in err and "\n" not in err
    assert not out.exists()  # refused before any work started


def test_bridge_rule_and_gent():
    base = GripperParams()
    # Outside the stiffness surrogate's range (2-4 mm... its lower end is the default 1.9 mm):
    # the beam rule, marked uncalibrated.
    t = 0.5 * base.finger.bridge_thickness
    p, reasons = apply_point(base, {"finger.bridge_thickness": t})
    assert p.springs.stiffness[0] == pytest.approx(base.springs.stiffness[0] / 8)  # k ∝ t³
    assert reasons and "surrogate" in reasons[0]
    p, _ = apply_point(base, {"material.shore_a": 20.0})
    assert p.material.youngs_modulus == pytest.approx(base.material.youngs_modulus)
    assert gent_modulus(30.0) > gent_modulus(20.0)
    p, reasons = apply_point(base, {"servo.spool_radius": 0.015})
    assert reasons == [] and p.springs.stiffness == base.springs.stiffness


def test_closure_match_stable_with_a_higher_hole():
    """With the calibrated soft springs the closed-cut match (closure.match_discrete_closure)
    went unstable for a 14 mm hole while its moment was applied as a step; it is ramped in."""
    from gripper.experiments.trial import run_trial

    p, _ = apply_point(GripperParams(), {"finger.hole_height": 0.014})
    assert run_trial("block", 0, 0, params=p)["status"] == "ok"


def test_geometry_points_get_the_continuum_surrogate():
    """Within its ranges a geometry change takes the surrogate's stiffness ratio, checked against
    the reference's own linear solve at that design (the same discretisation, corrected by the
    surrogate's convergence law), and is marked calibrated."""
    from gripper.calibration.surrogate import StiffnessSurrogate, equivalent_stiffness_raw

    base = GripperParams()
    t = 0.003
    p, reasons = apply_point(base, {"finger.bridge_thickness": t})
    assert reasons == []
    s = StiffnessSurrogate.load_default()
    raw_ratio = equivalent_stiffness_raw(p) / equivalent_stiffness_raw(base)
    want = raw_ratio * s.correction_factor(t) / s.correction_factor(base.finger.bridge_thickness)
    assert p.springs.stiffness[0] / base.springs.stiffness[0] == pytest.approx(want, rel=0.02)
    assert s.loo_error.max() <= 0.05
    p, reasons = apply_point(base, {"material.youngs_modulus": 0.88e6})  # K ∝ E, exactly
    assert reasons == [] and p.springs.stiffness[0] == pytest.approx(2 * base.springs.stiffness[0])


def test_committed_surrogate_is_of_the_default_design():
    from gripper.calibration.surrogate import StiffnessSurrogate, equivalent_stiffness_raw

    s = StiffnessSurrogate.load_default()
    assert s.default_stiffness == pytest.approx(equivalent_stiffness_raw(GripperParams()), rel=1e-6)


def test_blocked_force_grows_with_shortening():
    """The study response ``blocked_force``: r is cable shortening over finger length, converted
    by the drive (gripper.experiments.blocked_tip.blocked_tip_force, a stop at the tip)."""
    p = GripperParams()
    f = [measure_responses(p, {"blocked_force": {"r": r}})[0]["blocked_tip_force_N"] for r in (0.05, 0.15)]
    assert 0.0 < f[0] < f[1]


def test_example_studies_load():
    for name in ("one_at_a_time", "latin_hypercube"):
        s = load_study(f"gripper/data/studies/{name}.toml")
        assert len(s.design_points()) > 5


def test_limits_exclude_points_from_recommendations(tmp_path):
    from gripper.studies.study import recommendations
    f = tmp_path / "s.toml"
    f.write_text(STUDY + "at_least = { grasp_block_success_rate = 1.0 }\n")
    study = load_study(f)

    def rec(i, h, tension, success):
        return {"point": i, "status": "ok", "calibrated": False, "calibration_note": "",
                "changes": {} if h is None else {"finger.hole_height": h},
                "metrics": {"tension_for_angle_N": tension, "grasp_block_success_rate": success}}
    md = recommendations([rec(0, None, 3.0, 1.0), rec(1, 0.010, 1.0, 0.0), rec(2, 0.014, 2.0, 1.0)], study)
    assert "| finger.hole_height | 0.014 |" in md and "0.01 excluded by the limits" in md
    f.write_text(STUDY + "at_least = { grasp_sphere_success_rate = 1.0 }\n")
    with pytest.raises(ValueError, match="at_least"):
        load_study(f)


def test_a_shipped_study_loads_by_name():
    from gripper.core.resources import STUDIES_DIR

    assert load_study("one_at_a_time") == load_study(STUDIES_DIR / "one_at_a_time.toml")


def test_an_objective_error_names_its_line(tmp_path):
    f = tmp_path / "s.toml"
    f.write_text('[study]\nname = "s"\n[vary]\n"finger.cut_angle_deg" = [40.0]\n[responses]\n'
                 'bending = { r_max = 0.4 }\n[objective]\nminimize = "nonsense"\n')
    with pytest.raises(ValueError, match=r"s\.toml:8: objective\.minimize: unknown metric 'nonsense'"):
        load_study(f)


def test_every_shipped_study_loads():
    """The studies that replaced the hand-written sweeps (scripts/ of 0.17.0) build every point."""
    from gripper.core.resources import STUDIES_DIR

    names = sorted(p.stem for p in STUDIES_DIR.glob("*.toml") if not p.stem.startswith("envelope_"))
    assert {"step_convergence", "set_point_forces", "set_point_forces_pneumatic", "friction_sensitivity",
            "protocol_ablation", "small_parts", "paper_box_mesh"} <= set(names)
    for name in names:
        assert load_study(name).design_points()


def test_a_study_varies_how_its_trials_run(tmp_path):
    """protocol.* and placement.* keys reach the trials: the squeeze rises with the grip set-point
    (the controller holds each cable at it: docs/controller.md), and a finer step keeps the
    control period."""
    from gripper.studies.study import run_point

    f = tmp_path / "s.toml"
    f.write_text('[study]\nname = "t"\n[fixed]\n"placement.friction_scale" = 1.2\n'
                 '[vary]\n"protocol.grip_tension" = [2.0, 10.0]\n'
                 '[responses]\ngrasp = { objects = ["block"], trials = 1 }\n')
    study = load_study(f)
    proto, placement = study.trial_setup({"protocol.timestep": 0.001})
    assert proto.chunk_steps * proto.timestep == pytest.approx(study.protocol.chunk_steps * study.protocol.timestep)
    assert placement == {"friction_scale": 1.2}
    low, high = (run_point(study, i, pt)["metrics"]["grasp_block_median_peak_force_N"]
                 for i, pt in list(enumerate(study.design_points()))[1:])
    assert high > 2.0 * low


@pytest.mark.parametrize(("vary", "message"), [
    ('"protocol.grip_tension" = [80.0]', "protocol.grip_tension"),
    ('"placement.friction_scale" = [0.0]', "placement.friction_scale"),
    ('"object.mesh_points" = [[4, 4, 5]]', "no deformable object"),
    ('"protocol.no_such" = [1.0]', "unknown parameter"),
])
def test_bad_trial_settings_are_refused_at_load(tmp_path, vary, message):
    f = tmp_path / "s.toml"
    f.write_text(f'[study]\nname = "t"\n[vary]\n{vary}\n[responses]\ngrasp = {{ objects = ["block"], trials = 1 }}\n')
    with pytest.raises(ValueError, match=message):
        load_study(f)


def test_the_envelope_response_finds_a_gripping_range():
    """A 40 mm cylinder is inside the default's envelope (its lower end is 30 mm: docs/envelope.md),
    a 5 mm one below it."""
    from gripper.experiments.design_responses import envelope_response
    from gripper.experiments.protocol import GraspProtocol

    out = envelope_response(GripperParams(), {"shapes": ["cylinder"], "sizes": [0.005, 0.04], "trials": 1}, 0,
                            GraspProtocol())
    assert out == {"envelope_cylinder_smallest_m": 0.04, "envelope_cylinder_largest_m": 0.04}


def test_a_text_field_varies_and_its_results_are_written(tmp_path):
    """A choice field (springs.closure) varies like a number: its points are tabled, plotted at
    their place in the study's order and named in the recommendations (0.18.0 failed on the plot,
    after writing the results)."""
    from gripper.studies.study import recommendations, write_plots, write_table
    f = tmp_path / "s.toml"
    f.write_text('[study]\nname = "closure"\n[vary]\n"springs.closure" = ["stiffness", "rigid"]\n'
                 '[responses]\ntension_for_angle = { angle_deg = 90.0 }\n'
                 '[objective]\nminimize = "tension_for_angle_N"\n')
    study = load_study(f)
    records = [{"point": i, "status": "ok", "calibrated": True, "calibration_note": "", "changes": ch,
                "metrics": {"tension_for_angle_N": t}, "curves": {}}
               for i, (ch, t) in enumerate([({}, 3.0), ({"springs.closure": "stiffness"}, 2.0),
                                            ({"springs.closure": "rigid"}, 4.0)])]
    write_table(records, study, tmp_path / "results.csv")
    assert "stiffness" in (tmp_path / "results.csv").read_text()
    assert [p.name for p in write_plots(records, study, tmp_path)] == ["plot_springs_closure.png"]
    assert "| springs.closure | stiffness |" in recommendations(records, study)


def test_a_study_too_large_to_run_is_refused_at_load(tmp_path):
    f = tmp_path / "s.toml"
    heights = ", ".join(f"{0.010 + 4e-5 * k:.5f}" for k in range(50))
    f.write_text(f'[study]\nname = "big"\n[vary]\n"finger.hole_height" = [{heights}]\n'
                 '[responses]\ngrasp = { objects = ["block", "cylinder"], trials = 1000 }\n')
    with pytest.raises(ValueError, match=r"51 design points × 2,000 trials = 102,000 trials; at most 100,000"):
        load_study(f)
    f.write_text(f'[study]\nname = "big"\n[vary]\n"finger.hole_height" = [{heights}]\n'
                 '[responses]\ngrasp = { objects = ["block", "cylinder"], trials = 900 }\n')
    assert len(load_study(f).design_points()) == 51  # 91,800 trials: allowed
    f.write_text('[study]\nname = "big"\ndesign = "factorial"\n[vary]\n' + "".join(
        f'"finger.{k}" = [{a}, {a * 1.01}, {a * 1.02}, {a * 1.03}]\n' for k, a in
        [("hole_height", 0.012), ("pitch", 0.016), ("width", 0.016), ("height", 0.018), ("cut_angle_deg", 45.0),
         ("bridge_thickness", 0.0019), ("hole_diameter", 0.006)]) + '[responses]\nbending = { r_max = 0.1 }\n')
    with pytest.raises(ValueError, match="16,385 design points; at most 10,000"):
        load_study(f)


def test_a_study_whose_every_point_fails_exits_non_zero(tmp_path, monkeypatch, capsys):
    import gripper.studies.study as study_module

    def fail(*_a, **_k):
        raise RuntimeError("no response")
    monkeypatch.setattr(study_module, "measure_responses", fail)
    f = tmp_path / "s.toml"
    f.write_text('[study]\nname = "fails"\n[vary]\n"finger.hole_height" = [0.011]\n'
                 '[responses]\ntension_for_angle = { angle_deg = 90.0 }\n')
    assert main(["study", str(f), "--out", str(tmp_path / "out"), "--workers", "1", "--no-progress"]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["gripper study: error: every design point failed; the first: RuntimeError: no response"]
