import json
import math
import subprocess
import sys

import pytest

from gripper.cli.main import main
from gripper.core.fields import field_specs
from gripper.core.params import PAPER_HINGE_STIFFNESS, GripperParams


def test_defaults_valid_and_from_paper():
    p = GripperParams().validate()
    assert p.finger.n_segments == 6 and p.layout.n_fingers == 4
    assert p.finger.cut_angle_deg == 45.0
    # paper 000 Table 2: 1.9e-3 N·m/deg
    assert PAPER_HINGE_STIFFNESS == pytest.approx(1.9e-3 * 180 / math.pi)
    assert p.material.density == 1120.0 and p.material.youngs_modulus == 0.44e6


@pytest.mark.parametrize("suffix", [".json", ".toml"])
def test_file_round_trip(tmp_path, suffix):
    p = GripperParams()
    p = p.replace(finger=p.finger.replace(pitch=0.018),
                  springs=p.springs.replace(stiffness=(0.1, 0.11, 0.12, 0.13, 0.14)))
    path = p.save(tmp_path / f"p{suffix}")
    assert GripperParams.load(path) == p


BAD = [
    ({"finger": {"pitch": 0.0}}, "finger.pitch"),
    ({"finger": {"width": -0.01}}, "finger.width"),
    ({"finger": {"cut_angle_deg": 0.0}}, "finger.cut_angle_deg"),
    ({"finger": {"cut_angle_deg": 90.0}}, "finger.cut_angle_deg"),
    ({"finger": {"n_segments": 1}}, "finger.n_segments"),
    ({"finger": {"height": float("nan")}}, "finger.height"),
    ({"servo": {"preset": "unobtainium"}}, "servo.preset"),
    ({"springs": {"stiffness": [0.1, 0.1]}}, "springs.stiffness"),
    ({"springs": {"closure": "glued"}}, "springs.closure"),
    ({"springs": {"closure_stiffness": 0.0}}, "springs.closure_stiffness"),
    ({"layout": {"n_fingers": 0}}, "layout.n_fingers"),
    ({"finger": {"bogus": 1}}, "finger.bogus"),
    # issue 58: validate() skipped the contact section, so these passed `gripper check`
    ({"contact": {"model": "nonsense"}}, "contact.model"),
    ({"contact": {"pad_radius": -1.0}}, "contact.pad_radius"),
]


@pytest.mark.parametrize(("data", "field"), BAD)
def test_invalid_parameters_name_the_field(data, field):
    with pytest.raises(ValueError, match=field.replace(".", r"\.")) as err:
        GripperParams.from_dict(data)
    assert "\n" not in str(err.value)


def test_every_section_is_validated():
    """validate() walks the section registry: a bad value in any section is refused, and a
    section added to GripperParams without registering it is an error, not a silent skip."""
    import dataclasses

    from gripper.core.params import _SECTIONS

    assert [f.name for f in dataclasses.fields(GripperParams)] == list(_SECTIONS)
    for name, klass in _SECTIONS.items():
        spec = next(iter(field_specs(klass).values()))
        field = next(iter(field_specs(klass)))
        bad = "not-a-choice" if spec.kind == "choice" else float("nan")
        if spec.kind in ("bool", "numbers"):
            continue
        broken = object.__new__(klass)
        for f in dataclasses.fields(klass):
            object.__setattr__(broken, f.name, getattr(klass(), f.name))
        object.__setattr__(broken, field, bad)
        p = dataclasses.replace(GripperParams(), **{name: broken})
        with pytest.raises(ValueError, match=rf"{name}\.{field}"):
            p.validate()

    @dataclasses.dataclass(frozen=True)
    class WithNewSection(GripperParams):
        extra: object = dataclasses.field(default_factory=object)

    with pytest.raises(TypeError, match="extra"):
        WithNewSection().validate()


@pytest.mark.parametrize("field", ["model", "pad_radius"])
def test_cli_check_refuses_bad_contact(tmp_path, capsys, field):
    bad = tmp_path / "bad.toml"
    bad.write_text("[contact]\nmodel = \"nonsense\"\n" if field == "model" else "[contact]\npad_radius = -1.0\n")
    assert main(["check", "--params", str(bad)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and f"contact.{field}" in err[0]


def test_error_gives_allowed_range():
    with pytest.raises(ValueError, match=r"\(0, 90\)"):
        GripperParams.from_dict({"finger": {"cut_angle_deg": 120}})
    with pytest.raises(ValueError, match="hobby_6v"):
        GripperParams.from_dict({"servo": {"preset": "x"}})


def test_malformed_file(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    with pytest.raises(ValueError, match="malformed"):
        GripperParams.load(bad)


def test_cli_bad_input_exit_code_2_one_line(tmp_path, capsys):
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"finger": {"cut_angle_deg": 95}}))
    assert main(["bend", "--params", str(bad)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "finger.cut_angle_deg" in err[0]
    bad.write_text("[[[")
    assert main(["bend", "--params", str(bad)]) == 2


def test_cli_console_script_help():
    out = subprocess.run([sys.executable, "-m", "gripper.cli.main", "--help"], capture_output=True,
                         text=True, check=True).stdout
    for sub in ("bend", "servo", "params", "write-models", "check"):
        assert sub in out
