"""The pneumatic drive: paper 001's fibre-reinforced actuator, bent by its chamber pressure.

Its parameters are the ``pneumatic`` section; its command the regulator's pressure set-point
[Pa]; its grip set-point the chamber pressure (``GraspProtocol.grip_pressure``), ramped and
held by :class:`gripper.drives.pneumatic.controller.PressureController`; its datasheet
:class:`gripper.datasheets.regulator.RegulatorDatasheet`.

Example:
    >>> from gripper.core.params import Actuation, GripperParams
    >>> from gripper.drives.pneumatic.drive import PneumaticDrive
    >>> PneumaticDrive(GripperParams(actuation=Actuation(kind="pneumatic"))).names(1).hinges[0]
    'f1_hinge1'
"""

from __future__ import annotations

import mujoco
import numpy as np

from gripper.core.params import GripperParams
from gripper.core.rounding import rounded_sweep
from gripper.datasheets.regulator import RegulatorDatasheet
from gripper.drives.drive import Drive
from gripper.drives.pneumatic.chamber import (
    add_hinge_defaults,
    add_pneumatic_finger,
    add_segment_meshes,
    segment_lengths,
    segment_section,
    segment_vertices,
)
from gripper.drives.pneumatic.controller import PressureController, check_grip_pressure
from gripper.drives.pneumatic.sensing import PressureReading, PressureSensing, PressureSensor
from gripper.parts.names import FingerNames, finger_name
from gripper.parts.pads import hull_vertices

# Pressures at which the free fingers' reach is tabulated: evenly from 0 to the highest set-point.
REACH_POINTS = 23


class PneumaticDrive(Drive):
    """The pneumatic finger and its regulator (see the module docstring)."""

    kind = "pneumatic"
    model_name = "pneumatic_gripper"
    sections = ("pneumatic", "material", "layout", "lift", "sim", "contact", "actuation")
    set_point_field = "grip_pressure"
    set_point_record = "grip_pressure_Pa"
    peak_effort_record = "peak_pressure_Pa"
    command_record = "close_command_Pa"
    sensing_class = PressureSensing
    effort_label = "chamber pressure [kPa]"
    effort_display_scale = 1e-3
    effort_format = "4.0f"
    state_observations = (("chamber_pressure", "-"), ("pressure_setpoint", "-"))
    sensed_observations = (("sensed_pressure", "-"),)

    def __init__(self, params):
        super().__init__(params)
        self._index: tuple[mujoco.MjModel, PressureSensor, np.ndarray] | None = None  # the last model's

    @property
    def datasheet(self) -> RegulatorDatasheet:
        return self.params.pneumatic.datasheet

    @property
    def n_segments(self) -> int:
        return self.params.pneumatic.n_segments

    def derived_parameters(self) -> list[tuple[str, str, str, str]]:
        pf = self.params.pneumatic
        return [
            ("pneumatic", "pitch (hinge spacing)", f"{pf.pitch:.4g}", "m"),
            ("pneumatic", "hinge_stiffness (EI / pitch)", f"{pf.hinge_stiffness:.4g}", "N·m/rad"),
            ("pneumatic", "command_max (highest set-point)", f"{pf.command_max:g}", "Pa"),
        ]

    @property
    def finger_length(self) -> float:
        return self.params.pneumatic.length

    @property
    def finger_height(self) -> float:
        return self.params.pneumatic.height

    @property
    def finger_width(self) -> float:
        return self.params.pneumatic.width

    def names(self, k: int) -> FingerNames:
        return FingerNames(finger_name(k), self.n_segments, first_hinge=1, actuator="chamber")

    def add_defaults(self, spec: mujoco.MjSpec, defaults: dict) -> None:
        add_hinge_defaults(spec, defaults, self.params)

    def add_meshes(self, spec: mujoco.MjSpec) -> None:
        add_segment_meshes(spec, self.params)

    def add_finger(self, spec, parent, k, pos, quat, defaults, pads) -> FingerNames:
        names = self.names(k)
        add_pneumatic_finger(spec, parent, self.params, names, pos, quat, defaults, pads)
        return names

    def configure(self, spec: mujoco.MjSpec) -> None:
        # The chain's short end segments on stiff hinges ring at some 300 Hz: springs integrated
        # explicitly (implicitfast, implicit, rk4) diverged at 1 ms under the random-command check
        # (at 35-76 ms); MuJoCo's discrete integrator, implicit in the springs (the trials'
        # integrator), is stable there and at the trials' 2 ms.
        spec.option.integrator = mujoco.mjtIntegrator.mjINT_DISCRETE

    @property
    def contact_modulus(self) -> float:
        """Paper 001's Yeoh fit at small strain, E = 6 C10 with nu = 0.5: E* = 8 C10."""
        return 6.0 * self.params.material.yeoh_c10 / (1.0 - 0.5 ** 2)

    @property
    def pad_depth(self) -> float:
        """The silicone between the grasping face and the fabric's mid-plane (the neutral layer)."""
        return self.params.pneumatic.neutral_height

    def pad_kinds(self) -> tuple[str, ...]:
        return ("half", "full")

    def pad_vertices(self, kind: str) -> np.ndarray:
        pf = self.params.pneumatic
        length = 0.5 * pf.pitch if kind == "half" else pf.pitch
        return pneumatic_pad_vertices(self.params, segment_section(pf), length)

    def element_vertices(self, j: int) -> np.ndarray:
        pf = self.params.pneumatic
        return segment_vertices(pf, segment_lengths(pf)[j - 1])

    def element_kind(self, j: int) -> str:
        return "full" if 1 < j < self.n_segments else "half"

    def face_area(self, j: int) -> float:
        pf = self.params.pneumatic
        return segment_lengths(pf)[j - 1] * pf.width

    def sensor(self, m, rng=None, sensing=None) -> PressureSensor:
        """The regulators' monitor outputs (``sensing``: a :class:`PressureSensing`, default
        its defaults)."""
        return PressureSensor(m, self.params, sensing, rng=rng)

    def effort_sensors(self, m):
        n = self.params.layout.n_fingers
        adr = np.array([m.sensor_adr[m.sensor(f"{self.actuator_name(k)}_moment").id] for k in range(n)])
        return adr, m.actuator_gainprm[self.actuator_ids(m), 0].copy()  # the moment over the gain

    def command_rate(self, protocol) -> float:
        """The protocol's pressure ramp [Pa/s]."""
        return protocol.pressure_rate

    def reach_commands(self) -> np.ndarray:
        return np.linspace(0.0, self.params.pneumatic.command_max, REACH_POINTS)

    def check_set_point(self, protocol) -> None:
        """The controller only, its pressure set-point within the regulator's range."""
        if protocol.policy != "controller":
            raise ValueError(f"protocol.policy: the pneumatic gripper closes with the controller only "
                             f"(a pressure set-point), got {protocol.policy!r}")
        check_grip_pressure(protocol.grip_pressure, self.params.pneumatic.command_max)

    def grip_controller(self, m, sensor, protocol) -> PressureController:
        return PressureController(m, self.actuator_ids(m), sensor, grip_pressure=protocol.grip_pressure,
                                  rate=protocol.pressure_rate)

    def open_loop_rate(self, protocol) -> float:
        return protocol.pressure_rate

    def format_set_point(self, value: float) -> str:
        return f"{value / 1e3:g} kPa"

    def fingertip_clearance(self, protocol) -> float:
        return protocol.pneumatic_fingertip_clearance

    def _indices(self, m: mujoco.MjModel) -> tuple[PressureSensor, np.ndarray]:
        if self._index is None or self._index[0] is not m:
            self._index = (m, PressureSensor(m, self.params), self.actuator_ids(m))
        return self._index[1], self._index[2]

    def observe_state(self, m, d, sensordata) -> list[np.ndarray]:
        """Chamber pressures and set-points as fractions of the highest set-point."""
        sensor, act = self._indices(m)
        full = float(m.actuator_ctrlrange[act[0], 1])
        return [sensor.true_pressure(sensordata) / full, d.ctrl[act] / full]

    def observe_sensed(self, m, reading: PressureReading) -> list[np.ndarray]:
        _, act = self._indices(m)
        return [reading.pressure / float(m.actuator_ctrlrange[act[0], 1])]


def pneumatic_pad_vertices(p: GripperParams, section: np.ndarray, length: float) -> np.ndarray:
    """A pneumatic segment's collision surface: its section swept over its length, every edge
    (the section's corners and the end faces' rims) rounded to ``contact.pneumatic_edge_radius``
    (the round back is already round). The fingertip grasp runs the tip's end face along the
    table into the part, so its rim meets films first."""
    try:
        return hull_vertices(rounded_sweep(section, length, p.contact.pneumatic_edge_radius, round_ends=True))
    except ValueError as err:
        raise ValueError(f"contact.pneumatic_edge_radius: {p.contact.pneumatic_edge_radius!r} m does not fit "
                         f"this finger's segments ({err})") from None


