"""What the pneumatic fingers' regulators report: each one's present output pressure, from its
monitor output (an analog 1-5 V signal proportional to the pressure its own sensor reads),
digitised by the host, with noise.

The model's present pressure is the chamber actuator's activation (the regulator's filtered
output; :mod:`gripper.drives.pneumatic.chamber`), read through the actuator-force sensor (moment =
pressure x moment per pascal). The reading adds Gaussian noise and rounds to the ADC's
resolution, drawn from the trial's own generator (the same in every process).

Example:
    >>> from gripper.drives.pneumatic.sensing import PressureSensing
    >>> round(PressureSensing().resolution)   # Pa: 500 kPa full scale over 4 V, 12 bits on 0-5 V
    153
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from gripper.core.fields import Validated, param
from gripper.core.params import GripperParams
from gripper.parts.names import finger_name

# Full scale of the monitor output: 1-5 V for 0-F.S. (SMC ITV series); the host's ADC: 12 bits on 0-5 V.
ADC_VOLTS_PER_COUNT = 5.0 / 4096
MONITOR_SPAN_V = 4.0


@dataclass(frozen=True)
class PressureSensing(Validated):
    """Resolution and noise (one standard deviation) of the pressure the controller reads."""

    SECTION = "pressure_sensing"

    resolution: float = param(0.5e6 / MONITOR_SPAN_V * ADC_VOLTS_PER_COUNT, "Pa", gt=0, le=1e5,
                              source="assumed: the ITV0030's 0.5 MPa over its 4 V monitor span, a 12-bit ADC on 0-5 V")
    noise: float = param(1.0e3, "Pa", ge=0, le=1e5,
                         source="assumed: 0.2 % of the 0.5 MPa full scale (the monitor's ±6 % F.S. accuracy is a "
                                "bound on its offset, not on its noise)")

    def to_dict(self) -> dict[str, float]:
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


@dataclass(frozen=True)
class PressureReading:
    """One sample of every finger's regulator: present output pressure [Pa]."""

    pressure: np.ndarray

    @property
    def effort(self) -> np.ndarray:
        """The grip set-point's quantity: the chamber pressure [Pa]."""
        return self.pressure

    def to_dict(self) -> dict[str, list[float]]:
        return {"pressure_Pa": self.pressure.tolist()}


class PressureSensor:
    """Reads every finger's present pressure from a sensor-data row."""

    def __init__(self, m: mujoco.MjModel, p: GripperParams, sensing: PressureSensing | None = None,
                 rng: np.random.Generator | None = None):
        self.cfg = (sensing or PressureSensing()).validate()
        self.rng = rng
        n = p.layout.n_fingers
        chambers = [f"{finger_name(k)}_chamber" for k in range(n)]
        self.moment_adr = np.array([m.sensor_adr[m.sensor(f"{c}_moment").id] for c in chambers])
        self.gain = np.array([m.actuator_gainprm[m.actuator(c).id, 0] for c in chambers])

    def true_pressure(self, row: np.ndarray) -> np.ndarray:
        """The regulators' output pressures in a sensor-data row (or rows) [Pa], noiseless."""
        return np.asarray(row)[..., self.moment_adr] / self.gain

    def read(self, row: np.ndarray, rng: np.random.Generator | None = None) -> PressureReading:
        """The readings of one sensor-data row; noise from ``rng``, else the sensor's own generator."""
        g = rng if rng is not None else self.rng
        if g is None:
            raise ValueError("PressureSensor.read: no random generator for the sensor noise")
        x = self.true_pressure(row)
        if self.cfg.noise > 0:
            x = x + g.normal(0.0, self.cfg.noise, size=x.shape)
        return PressureReading(pressure=np.maximum(0.0, np.round(x / self.cfg.resolution) * self.cfg.resolution))


__all__ = ["PressureReading", "PressureSensing", "PressureSensor"]
