"""The object-agnostic grasp controller: force-limited closing from the servo's own sensing.

One knob, the grip set-point ``GraspProtocol.grip_tension`` [N of cable tension]. Each finger's
servo runs as a smart servo does in current-based position mode: the host moves the goal
position and the servo's own current limit caps its torque. Per finger, at every control
period (one trial chunk, 40 ms at the defaults, 25 Hz: a bus polling rate for four servos):

1. **closing**: the goal advances at the protocol's cable speed (``close_speed``), never past
   the servo's travel;
2. **contact**: the first sample where the spool tension reaches :data:`CONTACT_TENSION` or the
   present position lags the goal by :data:`CONTACT_LAG` is the finger's contact time;
3. **grip**: once the spool tension reaches the set-point, the goal is set to the present
   position plus the position error at which the servo's PD gives the set-point torque
   (τ = T r, error = τ / kp): the finger holds its place and keeps that squeeze, and it no
   longer follows an object that yields;
4. **regrip**: a held finger whose tension falls below :data:`REGRIP_FRACTION` of the
   set-point closes again (a slipping or relaxing object);
5. **release** on command: every goal back to zero.

The servo's current limit is :data:`CURRENT_LIMIT_FACTOR` times the set-point torque, so a
stiff object hit between two samples cannot be squeezed beyond that, whatever the polling
rate. The controller needs knowledge of its own gripper only (the spool radius, the servo's
travel and gains), nothing of the object.

Example:
    >>> from gripper.drives.cable.controller import CONTACT_TENSION
    >>> CONTACT_TENSION
    1.0
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from gripper.core.units import DEG
from gripper.drives.cable.sensing import ServoReading, ServoSensor

# Contact threshold on the spool tension [N]. Free closing of the calibrated default fingers
# needs at most 0.42 N of cable tension up to 2.0 rad of spool (measured at the 2 rad/s close
# rate, no object); 1 N is clear of that and of the 0.05 N load-cell noise.
CONTACT_TENSION = 1.0
# Contact threshold on the lag of the present position behind the goal [rad]. Free closing at
# 2 rad/s lags by 0.016 rad (0.9°, measured); 3° is three times that.
CONTACT_LAG = 3.0 * DEG
# A held finger closes again when its tension falls below this fraction of the set-point.
REGRIP_FRACTION = 0.5
# The servo's current limit as a multiple of the set-point torque: caps the squeeze between two
# samples on a stiff object (the goal runs 0.08 rad ahead in one 40 ms period at 2 rad/s, and
# the position loop saturates within 0.6°).
CURRENT_LIMIT_FACTOR = 1.5

CLOSING, HOLDING = 0, 1


class GripController:
    """The per-finger state machine of the module docstring, stepped once per chunk."""

    def __init__(self, m: mujoco.MjModel, servo_ids: np.ndarray, sensor: ServoSensor, *,
                 grip_tension: float, close_rate: float, spool_radius: float, kp: float):
        self.m = m
        self.servo = np.asarray(servo_ids)
        self.sensor = sensor
        self.grip_tension = float(grip_tension)
        self.rate = float(close_rate)
        self.travel = float(m.actuator_ctrlrange[self.servo[0], 1])
        self.hold_offset = grip_tension * spool_radius / kp
        self.torque_limit = CURRENT_LIMIT_FACTOR * grip_tension * spool_radius
        n = len(self.servo)
        self.goal = np.zeros(n)
        self.state = np.full(n, CLOSING)
        self.contact_time = np.full(n, math.nan)
        self.grip_time = math.nan
        self.t0 = math.nan
        self.last: ServoReading | None = None
        self.released = False

    def start(self, d: mujoco.MjData) -> None:
        """Begin closing now: set the servos' current limit and note the start time."""
        self.m.actuator_forcelimited[self.servo] = 1
        self.m.actuator_forcerange[self.servo] = [-self.torque_limit, self.torque_limit]
        self.t0 = self.t_prev = float(d.time)

    def goals(self, t: np.ndarray) -> np.ndarray:
        """The goal positions (len(t), fingers) over the next chunk, ``t`` from its start [s]."""
        g = np.repeat(self.goal[None], len(t), axis=0)
        closing = self.state == CLOSING
        g[:, closing] += self.rate * np.asarray(t)[:, None]
        return np.minimum(g, self.travel)

    def update(self, d: mujoco.MjData) -> None:
        """Read the servos at the chunk's end and move every finger's state on (the goals
        advance by the steps the chunk took, whatever its length)."""
        h = self.m.opt.timestep
        steps = round((float(d.time) - self.t_prev) / h)
        self.t_prev = float(d.time)
        r = self.sensor.read(d.sensordata)
        self.last = r
        if self.released:
            return
        closing = self.state == CLOSING
        self.goal[closing] = np.minimum(self.travel, self.goal[closing] + self.rate * (steps * h))
        t = float(d.time) - self.t0
        touched = closing & np.isnan(self.contact_time) & (
            (r.tension >= CONTACT_TENSION) | (self.goal - r.position >= CONTACT_LAG))
        self.contact_time[touched] = t
        gripped = closing & (r.tension >= self.grip_tension)
        self.goal[gripped] = np.minimum(self.travel, r.position[gripped] + self.hold_offset)
        self.state[gripped] = HOLDING
        slack = (self.state == HOLDING) & (r.tension < REGRIP_FRACTION * self.grip_tension)
        self.state[slack] = CLOSING
        if math.isnan(self.grip_time) and self.settled():
            self.grip_time = t

    def settled(self) -> bool:
        """Every finger holds its set-point or has reached the end of the servo's travel."""
        return bool(np.all((self.state == HOLDING) | (self.goal >= self.travel)))

    def release(self) -> None:
        """Open: every goal back to zero, and no more regrips."""
        self.goal[:] = 0.0
        self.state[:] = HOLDING
        self.released = True


def check_grip_tension(grip_tension: float, max_tension: float) -> None:
    """Refuse a set-point the servo cannot reach: above its stall tension (stall torque / spool
    radius), or at or below the contact threshold (the controller could not tell contact from
    its set-point).

    Raises:
        ValueError: naming ``protocol.grip_tension`` and the allowed range.
    """
    if not CONTACT_TENSION < grip_tension <= max_tension:
        raise ValueError(f"protocol.grip_tension: must be in ({CONTACT_TENSION:g}, {max_tension:.1f}] N (above "
                         f"the contact threshold, at most the servo's stall tension), got {grip_tension!r}")
