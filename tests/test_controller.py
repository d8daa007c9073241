"""The grasp controller and the servo sensing it reads: the squeeze follows the set-point, the
balloon survives every documented set-point, the readings are the servo's."""

import math
import statistics

import numpy as np
import pytest

from gripper.core.params import GripperParams
from gripper.drives.cable.controller import CONTACT_TENSION, CURRENT_LIMIT_FACTOR, REGRIP_FRACTION
from gripper.drives.cable.sensing import ServoSensing, ServoSensor
from gripper.experiments.protocol import GRIP_TENSION, GRIP_TENSION_RANGE, GraspProtocol
from gripper.experiments.trial import run_trial
from gripper.objects.library import get_object
from gripper.objects.scene_objects import Placement
from gripper.sim.scene import build_grasp_scene


@pytest.fixture(scope="module")
def block_sensor():
    p = GripperParams().validate()
    m = build_grasp_scene(p, get_object("block"), Placement())
    return m, p


def test_motor_constant_is_mujocos_dcmotor_constant(block_sensor):
    """I = τ / K with the K MuJoCo derives from the same datasheet triple (gainprm[1])."""
    m, p = block_sensor
    sensor = ServoSensor(m, p, ServoSensing(), np.random.default_rng(0))
    servo = m.actuator("f0_servo").id
    assert sensor.motor_constant == pytest.approx(m.actuator_gainprm[servo, 1], rel=1e-9)
    # stall current: the stall torque through that constant
    assert sensor.stall_current == pytest.approx(p.servo.datasheet.stall_torque / m.actuator_gainprm[servo, 1])


def test_readings_are_quantised_and_noisy_as_configured(block_sensor):
    m, p = block_sensor
    cfg = ServoSensing()
    sensor = ServoSensor(m, p, cfg, np.random.default_rng(1))
    row = np.zeros(m.nsensordata)
    row[sensor.angle_adr] = 1.2345
    row[sensor.torque_adr] = 0.5
    row[sensor.tension_adr] = 20.0
    reads = [sensor.read(row) for _ in range(4000)]
    pos = np.array([r.position for r in reads]).ravel()
    cur = np.array([r.current for r in reads]).ravel()
    ten = np.array([r.tension for r in reads]).ravel()
    for x, res in ((pos, cfg.position_resolution), (cur, cfg.current_resolution), (ten, cfg.tension_resolution)):
        counts = x / res
        assert np.allclose(counts, np.round(counts), atol=1e-6)  # whole counts only
    # mean: the true value; spread: the noise with the rounding's res²/12 added (16000 samples
    # each: the standard deviation's sampling error is about 0.6 %)
    for x, true, noise, res in ((pos, 1.2345, cfg.position_noise, cfg.position_resolution),
                                (cur, 0.5 / sensor.motor_constant, cfg.current_noise, cfg.current_resolution),
                                (ten, 20.0, cfg.tension_noise, cfg.tension_resolution)):
        assert x.mean() == pytest.approx(true, abs=4 * noise / math.sqrt(x.size) + res / 2)
        assert x.std() == pytest.approx(math.sqrt(noise ** 2 + res ** 2 / 12), rel=0.05)


def test_same_trial_same_readings_and_noise_from_the_trial_seed():
    a = run_trial("block", seed=2, index=1)
    b = run_trial("block", seed=2, index=1)
    c = run_trial("block", seed=2, index=2)
    assert a.drive["at_hold_end"] == b.drive["at_hold_end"]
    assert a.drive["at_hold_end"] != c.drive["at_hold_end"]


@pytest.fixture(scope="module")
def block_sweep():
    """The block at set-points across the documented range, three trials each."""
    lo, hi = GRIP_TENSION_RANGE
    grips = (lo, 0.5 * (lo + hi), hi, 2 * hi)
    return {g: [run_trial("block", seed=0, index=i, protocol=GraspProtocol(grip_tension=g)) for i in range(3)]
            for g in grips}


def test_block_squeeze_rises_with_the_set_point(block_sweep):
    medians = [statistics.median(r.peak_total_force_N for r in recs) for _, recs in sorted(block_sweep.items())]
    assert all(b > a for a, b in zip(medians, medians[1:], strict=False)), medians
    for recs in block_sweep.values():
        assert all(r.status == "ok" and r.warnings == 0 for r in recs)


def test_held_tension_stays_within_the_controllers_band(block_sweep):
    """At the end of the hold every finger's spool tension is between the regrip threshold and
    the servo's current limit (a held finger neither slackens nor is squeezed past the limit),
    allowing the load cell's noise and resolution, and 5 % above the limit for the reel's
    inertia: the hold is not perfectly still, and 0.5 N on the cable is the 2.2 kg reflected
    rotor mass (8.6e-4 kg·m² / r²) accelerating at 0.2 m/s²."""
    tol = 4 * ServoSensing().tension_noise + ServoSensing().tension_resolution
    for g, recs in block_sweep.items():
        for r in recs:
            t = np.array(r.drive["at_hold_end"]["tension_N"])
            assert np.all(t >= REGRIP_FRACTION * g - tol), (g, t)
            assert np.all(t <= 1.05 * CURRENT_LIMIT_FACTOR * g + tol), (g, t)
            assert r.drive["grip_tension_N"] == g
            assert 0 < r.contact_time_s <= r.grasp_time_s < 2.0


def test_controller_squeezes_far_less_than_the_stalled_servo():
    """Per-object mode drives the servos to stall on rigid parts (54 N per cable); the
    controller stops at its set-point."""
    ctrl = run_trial("block", seed=0, index=0)
    stall = run_trial("block", seed=0, index=0, protocol=GraspProtocol(policy="per_object"))
    assert ctrl.success and stall.success
    assert ctrl.peak_total_force_N < 0.6 * stall.peak_total_force_N
    assert ctrl.policy == "controller" and stall.policy == "per_object" \
        and "grip_tension_N" not in stall.drive


@pytest.mark.parametrize("grip", GRIP_TENSION_RANGE + (GRIP_TENSION,))
def test_the_balloon_is_never_burst_in_the_documented_range(grip):
    """At the ends of the documented set-point range and at the default, the balloon's membrane
    strain stays below its burst limit (0.25), three trials each."""
    for i in range(3):
        r = run_trial("balloon", seed=0, index=i, protocol=GraspProtocol(grip_tension=grip))
        assert r.status == "ok" and r.warnings == 0
        assert not r.damaged and r.damage_measure < get_object("balloon").damage_limit, (grip, i, r.damage_measure)


def test_a_set_point_the_servo_cannot_reach_is_refused():
    weak = GripperParams().replace(servo=GripperParams().servo.replace(spool_radius=0.03))  # 36 N at stall
    with pytest.raises(ValueError, match=r"protocol.grip_tension: must be in \(1, 36.0\] N"):
        run_trial("block", protocol=GraspProtocol(grip_tension=40.0), params=weak)
    with pytest.raises(ValueError, match="protocol.grip_tension"):
        run_trial("block", protocol=GraspProtocol(grip_tension=0.5 * CONTACT_TENSION))


class _ServoAngles:
    """A frame sink keeping finger 0's servo angle at the end of every chunk, by phase."""

    def start(self, model, probe):
        self.adr = model.sensor_adr[model.sensor("f0_servo_angle").id]
        self.by_phase = {}

    def add(self, phase, states, sens):
        self.by_phase.setdefault(phase, []).append(float(sens[-1, self.adr]))


def test_release_opens_the_fingers():
    sink = _ServoAngles()
    r = run_trial("block", seed=0, index=0, protocol=GraspProtocol(release=True, hold_s=0.2, shake_s=0.2),
                  frame_sink=sink)
    assert r.status == "ok" and r.success
    held = sink.by_phase["shake"][-1]
    assert held > 1.0  # closed on the block
    assert sink.by_phase["release"][-1] < 0.05 * held  # back to open within the release time
