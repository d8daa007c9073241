import pytest

from gripper.core.params import GripperParams
from gripper.datasheets.servo import SERVO_PRESETS
from gripper.drives.cable.datasheet_check import measure_servo


@pytest.mark.parametrize("preset", sorted(SERVO_PRESETS))
def test_servo_matches_datasheet(preset):
    p = GripperParams()
    p = p.replace(servo=p.servo.replace(preset=preset))
    m = measure_servo(p)
    ds = m.datasheet
    assert m.no_load_speed == pytest.approx(ds.no_load_speed, rel=0.03)
    assert m.stall_torque == pytest.approx(ds.stall_torque, rel=0.03)
    assert m.step_60deg_time == pytest.approx(ds.step_60deg_time, rel=0.10)
    # the largest cable tension the servo can hold is stall torque / spool radius
    assert m.max_cable_tension == pytest.approx(ds.stall_torque / p.servo.spool_radius, rel=0.03)
