"""The pneumatic gripper's grasp controller: a pressure set-point, ramped and held.

A pneumatic gripper is closed the way a lab closes one: every regulator's set-point rises at the
protocol's rate (``GraspProtocol.pressure_rate``) to the grip pressure (``grip_pressure``) and is
held there; the finger bends until the chamber's moment balances its springs and whatever it
touches, so the squeeze on an object is set by the pressure, never by the object. The
controller reads what the regulators report (:mod:`gripper.drives.pneumatic.sensing`): the grasp is
made (``grip_time``) when every finger's present pressure is within ``SETTLED_FRACTION`` of the
set-point. It knows its own gripper only (the regulators' range), nothing of the object. It has
no contact sensing: ``contact_time`` stays unknown (NaN).

Example:
    >>> from gripper.drives.pneumatic.controller import SETTLED_FRACTION
    >>> SETTLED_FRACTION
    0.98
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from gripper.drives.pneumatic.sensing import PressureReading, PressureSensor

# The grasp is made when every finger's reported pressure is within this fraction of the set-point
# (2 %: above the monitor's noise of 1 kPa at the 250 kPa default, twice the regulator's linearity).
SETTLED_FRACTION = 0.98


class PressureController:
    """Ramp-and-hold of the module docstring, stepped once per chunk (the trial's control period)."""

    def __init__(self, m: mujoco.MjModel, drive_ids: np.ndarray, sensor: PressureSensor, *,
                 grip_pressure: float, rate: float):
        self.m = m
        self.drive = np.asarray(drive_ids)
        self.sensor = sensor
        self.grip_pressure = float(grip_pressure)
        self.rate = float(rate)
        self.travel = float(m.actuator_ctrlrange[self.drive[0], 1])
        n = len(self.drive)
        self.goal = np.zeros(n)
        self.contact_time = np.full(n, math.nan)
        self.grip_time = math.nan
        self.t0 = self.t_prev = math.nan
        self.last: PressureReading | None = None
        self.released = False

    def start(self, d: mujoco.MjData) -> None:
        """Begin the ramp now."""
        self.t0 = self.t_prev = float(d.time)

    def goals(self, t: np.ndarray) -> np.ndarray:
        """The set-points (len(t), fingers) over the next chunk, ``t`` from its start [s]."""
        if self.released:
            return np.zeros((len(t), len(self.goal)))
        g = self.goal[None] + self.rate * np.asarray(t)[:, None]
        return np.minimum(g, self.grip_pressure)

    def update(self, d: mujoco.MjData) -> None:
        """Read the regulators at the chunk's end and move the set-points on."""
        dt = float(d.time) - self.t_prev
        self.t_prev = float(d.time)
        self.last = self.sensor.read(d.sensordata)
        if self.released:
            return
        self.goal = np.minimum(self.grip_pressure, self.goal + self.rate * dt)
        if math.isnan(self.grip_time) and self.settled():
            self.grip_time = float(d.time) - self.t0

    def settled(self) -> bool:
        """Every set-point at the grip pressure and every reported pressure within ``SETTLED_FRACTION`` of it."""
        return bool(self.last is not None and np.all(self.goal >= self.grip_pressure)
                    and np.all(self.last.pressure >= SETTLED_FRACTION * self.grip_pressure))

    def release(self) -> None:
        """Vent: every set-point to zero."""
        self.goal[:] = 0.0
        self.released = True


def check_grip_pressure(grip_pressure: float, command_max: float) -> None:
    """Refuse a set-point the regulator cannot give or the calibration does not cover.

    Raises:
        ValueError: naming ``protocol.grip_pressure`` and the allowed range.
    """
    if not 0.0 < grip_pressure <= command_max:
        raise ValueError(f"protocol.grip_pressure: must be in (0, {command_max:g}] Pa (the pneumatic finger's "
                         f"pressure_max within its regulator's range), got {grip_pressure!r}")
