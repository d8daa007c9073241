"""The trial record: typed, its JSON form round-trips and matches its schema, and a bad record
read back is refused naming the key."""

from __future__ import annotations

import dataclasses
import json

import pytest

from gripper.bench.benchmark import read_trials
from gripper.experiments.protocol import GraspProtocol
from gripper.experiments.record import TrialRecord
from gripper.experiments.trial import run_trial

SHORT = GraspProtocol(hold_s=0.2, shake_s=0.2)


@pytest.fixture(scope="module")
def record() -> TrialRecord:
    return run_trial("block", seed=0, index=0, protocol=SHORT)


def test_a_trial_returns_a_typed_record_that_is_also_its_json_mapping(record):
    assert isinstance(record, TrialRecord)
    assert record["success"] is record.success
    assert dict(record) == record.to_dict()
    assert "error" not in record and record.status == "ok"


def test_the_json_form_round_trips_through_the_schema(record):
    line = json.loads(json.dumps(record.to_dict(), sort_keys=True))
    assert TrialRecord.from_dict(line) == record
    schema = TrialRecord.json_schema()
    assert set(line) <= set(schema["properties"])
    assert set(schema["required"]) <= set(line)


def test_an_error_record_omits_the_outcome_and_keeps_the_reason(record):
    err = dataclasses.replace(record, status="error", success=None, failed_phase=None, error="nan at t=1",
                              lift_height_m=None, slip_m=None, max_slip_m=None, damaged=None,
                              damage_measure=None, damage_limit=None, drive={"kind": "cable"},
                              policy=None, contact_time_s=None, grasp_time_s=None, grasp=None, palm_xy_m=None,
                              depth_estimate=None, wrist_yaw_rad=None, pose=None)
    d = err.to_dict()
    assert "lift_height_m" not in d and d["error"] == "nan at t=1"
    assert TrialRecord.from_dict(json.loads(json.dumps(d))) == err


@pytest.mark.parametrize(("change", "message"), [
    ({"success": "yes"}, "success: expected boolean or null"),
    ({"status": "done"}, "status: expected one of ok, error"),
    ({"bogus": 1}, "unknown key 'bogus'"),
    ({"perturbation": {"x_m": 0.0}}, "perturbation: expected object"),
])
def test_a_bad_record_is_refused_naming_the_key(record, change, message):
    with pytest.raises(ValueError, match=message):
        TrialRecord.from_dict({**record.to_dict(), **change}, where="trials.jsonl: record 3")


def test_a_record_without_a_required_key_is_refused(record, tmp_path):
    d = record.to_dict()
    del d["peak_total_force_N"]
    path = tmp_path / "trials.jsonl"
    path.write_text(json.dumps(record.to_dict()) + "\n" + json.dumps(d) + "\n")
    with pytest.raises(ValueError, match=r"trials.jsonl: record 2: missing key 'peak_total_force_N'"):
        read_trials(path)


def test_records_of_0_22_0_are_upgraded_when_read(tmp_path):
    """A benchmark's records written by 0.22.0 (schema 2: the drive's keys at the top level; one
    cable and one pneumatic block trial, tests/data) read as schema 3: every drive key moved,
    unchanged, into the one drive entry, with the drive's kind."""
    from pathlib import Path

    from gripper.experiments.record import SCHEMA_2_DRIVE_KEYS, upgrade_record

    path = Path(__file__).parent / "data" / "records_0.22.0.jsonl"
    old = [json.loads(line) for line in path.read_text().splitlines()]
    cable, pneumatic = read_trials(path, repair=False)
    assert cable.drive == {"kind": "cable", "peak_cable_tension_N": old[0]["peak_cable_tension_N"],
                           "close_command_rad": old[0]["close_command_rad"], "grip_tension_N": 7.5,
                           "at_grasp": old[0]["servo_at_grasp"], "at_hold_end": old[0]["servo_at_hold_end"]}
    assert pneumatic.drive == {"kind": "pneumatic", "peak_pressure_Pa": old[1]["peak_pressure_Pa"],
                               "grip_pressure_Pa": old[1]["grip_pressure_Pa"],
                               "at_grasp": old[1]["servo_at_grasp"], "at_hold_end": old[1]["servo_at_hold_end"]}
    for rec, raw in ((cable, old[0]), (pneumatic, old[1])):
        new = rec.to_dict()
        assert not (set(new) & set(SCHEMA_2_DRIVE_KEYS)) and "actuation" not in new
        # everything else is as it was
        assert {k: v for k, v in new.items() if k != "drive"} == {
            k: v for k, v in raw.items() if k not in SCHEMA_2_DRIVE_KEYS and k != "actuation"}
        assert upgrade_record(new) == new  # schema 3 is left as it is
