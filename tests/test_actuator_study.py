"""Paper 001's case studies on the study layer: the shipped files, refusal of bad actuator
values in one line, and a small actuator study's results at 1 and 2 workers and after a kill."""

import subprocess
import sys

import pytest
from helpers import kill_after_lines, study_records

from gripper.cli.main import main
from gripper.studies.study_file import ActuatorDesign, apply_point, load_study

CASES = ("cladding", "main_body", "neutral_layer", "fibre_diameter", "twist_angle")

STUDY = """
[study]
name = "small actuator study"
model = "actuator"
design = "one_at_a_time"

[fixed]
"actuator.neutral_thickness" = 0.0004

[vary]
"actuator.twist_angle_deg" = [10.0, 15.0]

[responses]
inflation = { pressure_max = 10000.0, steps = 1, refinement = 1 }

[objective]
maximize = "bending_angle_at_max_deg"
"""


@pytest.mark.parametrize("case", CASES)
def test_the_five_case_studies_load_with_the_papers_values(case):
    s = load_study(f"paper001_{case}")
    assert isinstance(s.base, ActuatorDesign) and s.responses["inflation"]["pressure_max"] == 250e3
    a = s.base.actuator
    # paper 001 §2.4.2: main body 2 mm and the fibre at 4° in every case (but the varied one)
    assert a.main_body_thickness == 0.002 and a.twist_angle_deg == 4.0
    points = s.design_points()
    assert len(points) >= 5 and points[0] == {}
    for pt in points:
        design, reasons = apply_point(s.base, pt)
        assert reasons == [] and design.actuator.validate()


@pytest.mark.parametrize("edit, key", [
    (('"actuator.neutral_thickness" = 0.0004', '"actuator.neutral_thickness" = -0.0004'),
     "actuator.neutral_thickness"),
    (('"actuator.neutral_thickness" = 0.0004', '"actuator.duct_radiuss" = 0.005'), "actuator.duct_radiuss"),
    (("[10.0, 15.0]", "[10.0, 50.0]"), "actuator.twist_angle_deg"),
    (("pressure_max = 10000.0", "pressure_max = 1e9"), "responses.inflation"),
    (("steps = 1", "steps = 0"), "responses.inflation"),
    (("inflation = {", "bending = {"), "responses.bending"),
])
def test_bad_actuator_values_are_refused_in_one_line(tmp_path, capsys, edit, key):
    bad = tmp_path / "bad.toml"
    bad.write_text(STUDY.replace(*edit))
    out = tmp_path / "out"
    assert main(["study", str(bad), "--out", str(out), "--no-progress"]) == 2
    err = capsys.readouterr().err.strip()
    assert key in err and "\n" not in err
    assert not out.exists()


@pytest.fixture(scope="module")
def study_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("actuator_study") / "s.toml"
    path.write_text(STUDY)
    return path


@pytest.fixture(scope="module")
def reference(study_file, tmp_path_factory):
    out = tmp_path_factory.mktemp("ref")
    assert main(["study", str(study_file), "--out", str(out), "--workers", "1", "--no-progress"]) == 0
    return out


def test_actuator_study_outputs(reference):
    recs = study_records(reference)
    assert [r["point"] for r in recs] == [0, 1, 2] and all(r["status"] == "ok" for r in recs)
    angle = {r["changes"].get("actuator.twist_angle_deg", 4.0): r["metrics"]["bending_angle_at_max_deg"]
             for r in recs}
    # a steeper winding carries more of the axial stretch (E_f sin⁴α): it bends less (paper 001 Fig. 16)
    assert angle[4.0] > angle[10.0] > angle[15.0] > 0
    assert recs[0]["curves"]["pressure_kPa"] == [0.0, 10.0]
    assert (reference / "plot_actuator_twist_angle_deg.png").stat().st_size > 1000


def test_actuator_study_same_results_at_two_workers(study_file, reference, tmp_path):
    out = tmp_path / "w2"
    assert main(["study", str(study_file), "--out", str(out), "--workers", "2", "--no-progress"]) == 0
    assert study_records(out) == study_records(reference)


@pytest.mark.slow
def test_actuator_study_resumes_after_a_kill(study_file, reference, tmp_path):
    out = tmp_path / "killed"
    cmd = [sys.executable, "-m", "gripper.cli.main", "study", str(study_file), "--out", str(out), "--workers", "1",
           "--no-progress"]
    assert 1 <= kill_after_lines(cmd, out / "results.jsonl", 1) < 3
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    assert study_records(out) == study_records(reference)
