"""Servo sensing as a smart servo reports it: present position, present current (the load), and
the cable tension at the spool, quantised and noisy.

The model is a Dynamixel X-series class servo (protocol 2.0 control table) with a load cell
under the spool:

- present position: the output-shaft encoder, 4096 counts per turn;
- present current: the motor current in 2.69 mA units. It is computed from MuJoCo's
  ``dcmotor`` force through the motor constant, I = τ / K, with K = V / ω₀ from the datasheet's
  supply voltage and no-load speed (the same constant MuJoCo's ``nominal`` attribute derives);
  the present load is that current over the stall current;
- cable tension at the spool: the tendon's limit force (the rope is taut only at its limit).

Every reading is rounded to its resolution after Gaussian noise is added. The noise is drawn
from the trial's own generator, so a trial's readings are the same whichever process runs it.

Example:
    >>> from gripper.drives.cable.sensing import ServoSensing
    >>> round(ServoSensing().position_resolution, 6)
    0.001534
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from gripper.core.fields import Validated, param
from gripper.core.params import GripperParams
from gripper.parts.names import finger_name

ENCODER_COUNTS = 4096  # ROBOTIS X-series e-Manual: Present Position, 4096 pulses per revolution


@dataclass(frozen=True)
class ServoSensing(Validated):
    """Resolution and noise (one standard deviation) of what the grasp controller reads."""

    SECTION = "sensing"

    position_resolution: float = param(2 * math.pi / ENCODER_COUNTS, "rad", gt=0, le=0.1,
                                       source="ROBOTIS X-series e-Manual: 4096 counts per turn (0.088°)")
    position_noise: float = param(2 * math.pi / ENCODER_COUNTS, "rad", ge=0, le=0.1,
                                  source="assumed: one count of encoder jitter")
    current_resolution: float = param(2.69e-3, "A", gt=0, le=0.1,
                                      source="ROBOTIS XM430-W350 e-Manual: Present Current unit 2.69 mA")
    current_noise: float = param(5.4e-3, "A", ge=0, le=0.5,
                                 source="assumed: two counts of current-sense noise")
    tension_resolution: float = param(0.02, "N", gt=0, le=5,
                                      source="assumed: a 100 N spool load cell read with 12 bits")
    tension_noise: float = param(0.05, "N", ge=0, le=5, source="assumed: load-cell amplifier noise")

    def to_dict(self) -> dict[str, float]:
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


@dataclass(frozen=True)
class ServoReading:
    """One sample of every finger's servo: present position [rad], present current [A], present
    load (current over stall current) [-] and cable tension at the spool [N]."""

    position: np.ndarray
    current: np.ndarray
    load: np.ndarray
    tension: np.ndarray

    @property
    def effort(self) -> np.ndarray:
        """The grip set-point's quantity: the cable tension at the spool [N]."""
        return self.tension

    def to_dict(self) -> dict[str, list[float]]:
        return {"position_rad": self.position.tolist(), "current_A": self.current.tolist(),
                "load": self.load.tolist(), "tension_N": self.tension.tolist()}


class ServoSensor:
    """Reads every finger's servo from a sensor-data row, as :class:`ServoSensing` says."""

    def __init__(self, m: mujoco.MjModel, p: GripperParams, sensing: ServoSensing,
                 rng: np.random.Generator | None = None):
        self.cfg = sensing.validate()
        self.rng = rng
        n = p.layout.n_fingers

        def adr(suffix: str) -> np.ndarray:
            return np.array([m.sensor_adr[m.sensor(f"{finger_name(k)}_{suffix}").id] for k in range(n)])

        self.angle_adr = adr("servo_angle")
        self.torque_adr = adr("servo_torque")
        self.tension_adr = adr("cable_tension")
        ds = p.servo.datasheet
        self.motor_constant = ds.voltage / ds.no_load_speed  # [N·m/A] at the output shaft
        self.stall_current = ds.stall_torque / self.motor_constant  # [A]

    @staticmethod
    def _sense(x: np.ndarray, noise: float, resolution: float, rng: np.random.Generator) -> np.ndarray:
        if noise > 0:
            x = x + rng.normal(0.0, noise, size=x.shape)
        return np.round(x / resolution) * resolution

    def read(self, row: np.ndarray, rng: np.random.Generator | None = None) -> ServoReading:
        """The readings of one sensor-data row (the last step of a chunk); the noise comes from
        ``rng``, else from the sensor's own generator."""
        c = self.cfg
        g = rng if rng is not None else self.rng
        if g is None:
            raise ValueError("ServoSensor.read: no random generator for the sensor noise")
        pos = self._sense(row[self.angle_adr], c.position_noise, c.position_resolution, g)
        cur = self._sense(row[self.torque_adr] / self.motor_constant, c.current_noise, c.current_resolution, g)
        ten = np.maximum(0.0, self._sense(row[self.tension_adr], c.tension_noise, c.tension_resolution, g))
        return ServoReading(position=pos, current=cur, load=cur / self.stall_current, tension=ten)
