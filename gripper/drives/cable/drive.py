"""The cable drive: paper 000's cut silicone finger, bent by a cable that a servo reels in.

Its parameters are the ``finger``, ``material``, ``springs``, ``cable`` and ``servo`` sections;
its command is the spool angle [rad]; its grip set-point the cable tension at the spool [N]
(``GraspProtocol.grip_tension``), closed on by :class:`gripper.drives.cable.controller.GripController`;
its datasheet :class:`gripper.datasheets.servo.ServoDatasheet`.

Example:
    >>> from gripper.core.params import DEG, GripperParams
    >>> from gripper.drives.cable.drive import CableDrive
    >>> CableDrive(GripperParams()).names(1).hinges[0]
    'f1_hinge2'
"""

from __future__ import annotations

import mujoco
import numpy as np

from gripper.core.params import GripperParams
from gripper.core.rounding import rounded_prism
from gripper.datasheets.servo import ServoDatasheet
from gripper.drives.cable.closure import teeth_closure_stiffness, tune_closure_limits
from gripper.drives.cable.controller import GripController, check_grip_tension
from gripper.drives.cable.finger import (
    add_cable_drive,
    add_element_meshes,
    add_finger,
    add_hinge_defaults,
    add_servo_default,
    tune_soft_limits,
)
from gripper.drives.cable.geometry import (
    ElementKind,
    element_face,
    element_kind,
    element_profile,
    element_taper,
    element_vertices,
)
from gripper.drives.cable.sensing import ServoReading, ServoSensing, ServoSensor
from gripper.drives.cable.servo import servo_gains
from gripper.drives.drive import Drive
from gripper.parts.names import FingerNames, finger_name
from gripper.parts.pads import hull_vertices

# Spool angles at which the free fingers' reach is tabulated [rad]: 0.1 rad apart up to 2.2 rad,
# past the widest grasp's close command.
REACH_ANGLES = np.linspace(0.0, 2.2, 23)


def _element_kind(kind: str) -> ElementKind:
    if kind not in ("base", "middle", "tip"):
        raise ValueError(f"element kind: must be base, middle or tip, got {kind!r}")
    return kind  # type: ignore[return-value]


class CableDrive(Drive):
    """The cable finger and its servo (see the module docstring)."""

    kind = "cable"
    model_name = "soft_gripper"
    sections = ("finger", "material", "springs", "cable", "servo", "layout", "lift", "sim", "contact", "actuation")
    set_point_field = "grip_tension"
    set_point_record = "grip_tension_N"
    peak_effort_record = "peak_cable_tension_N"
    command_record = "close_command_rad"
    sensing_class = ServoSensing
    effort_label = "cable tension [N]"
    responses = ("bending", "tension_for_angle", "blocked_force", "grasp", "holding_force", "envelope", "payload",
                 "parts")
    state_observations = (("cable_shortening", "m"), ("cable_tension", "N"), ("servo_angle", "rad"),
                          ("servo_setpoint", "rad"))
    sensed_observations = (("sensed_servo_position", "rad"), ("sensed_servo_current", "A"),
                           ("sensed_spool_tension", "N"))

    def __init__(self, params: GripperParams):
        super().__init__(params)
        self._index: tuple[mujoco.MjModel, dict[str, np.ndarray]] | None = None  # the last model's indices

    @property
    def datasheet(self) -> ServoDatasheet:
        return self.params.servo.datasheet

    @property
    def n_segments(self) -> int:
        return self.params.finger.n_segments

    def derived_parameters(self) -> list[tuple[str, str, str, str]]:
        p = self.params
        return [
            ("finger", "closure_angle_deg", f"{p.finger.closure_angle_deg:.2f}", "deg"),
            ("springs", "closed-cut stiffness (teeth estimate)",
             f"{teeth_closure_stiffness(p.finger, p.material):.3g}", "N·m/rad"),
            ("finger", "length", f"{p.finger.length:g}", "m"),
            ("cable", "axial_stiffness (EA)", f"{p.cable.axial_stiffness:.4g}", "N"),
            ("servo", "max_cable_tension", f"{p.servo.max_cable_tension:.4g}", "N"),
        ]

    @property
    def finger_length(self) -> float:
        return self.params.finger.length

    @property
    def finger_height(self) -> float:
        return self.params.finger.height

    @property
    def finger_width(self) -> float:
        return self.params.finger.width

    def names(self, k: int) -> FingerNames:
        return FingerNames(finger_name(k), self.n_segments)

    def add_defaults(self, spec: mujoco.MjSpec, defaults: dict) -> None:
        defaults["servo"] = add_servo_default(spec, defaults["root"], self.params)
        add_hinge_defaults(spec, defaults, self.params)

    def add_meshes(self, spec: mujoco.MjSpec) -> None:
        add_element_meshes(spec, self.params)

    def add_finger(self, spec, parent, k, pos, quat, defaults, pads) -> FingerNames:
        names = add_finger(spec, parent, self.params, finger_name(k), pos, quat, defaults, pads)
        add_cable_drive(spec, self.params, names, defaults["servo"])
        return names

    def tune(self, spec: mujoco.MjSpec) -> None:
        tune_soft_limits(spec, self.params)

    def tune_for_trials(self, spec: mujoco.MjSpec) -> None:
        tune_closure_limits(spec, self.params, spec.compile())

    @property
    def contact_modulus(self) -> float:
        """Paper 000 Table 2's E and nu: E* = E / (1 - nu²)."""
        mat = self.params.material
        return mat.youngs_modulus / (1.0 - mat.poisson_ratio ** 2)

    @property
    def pad_depth(self) -> float:
        """The silicone wall between the grasping face and the cable hole."""
        g = self.params.finger
        return g.height - g.hole_height - 0.5 * g.hole_diameter

    def pad_kinds(self) -> tuple[str, ...]:
        n = self.n_segments
        return tuple(sorted({element_kind(i, n) for i in range(n)}))

    def pad_vertices(self, kind: str) -> np.ndarray:
        return cable_pad_vertices(self.params, _element_kind(kind))

    def element_vertices(self, j: int) -> np.ndarray:
        return element_vertices(self.params.finger, element_kind(j - 1, self.n_segments))

    def element_kind(self, j: int) -> str:
        return element_kind(j - 1, self.n_segments)

    def face_area(self, j: int) -> float:
        """The top between the element's cuts, as :func:`gripper.drives.cable.finger.add_finger` pads it."""
        x0, x1, width = element_face(self.params.finger, element_kind(j - 1, self.n_segments))
        return (x1 - x0) * width

    def sensor(self, m, rng=None, sensing=None) -> ServoSensor:
        return ServoSensor(m, self.params, self.trial_sensing(sensing), rng)

    def effort_sensors(self, m):
        adr = np.array([m.sensor_adr[m.sensor(f"{finger_name(k)}_cable_tension").id]
                        for k in range(self.params.layout.n_fingers)])
        return adr, np.ones(len(adr))

    def command_rate(self, protocol) -> float:
        """The servo's slew rate, its no-load speed [rad/s]."""
        return self.params.servo.slew_rate

    def reach_commands(self) -> np.ndarray:
        return REACH_ANGLES.copy()

    def shortening_command(self, fraction: float) -> float:
        """The spool angle that reels in ``fraction`` × finger length of cable [rad]."""
        return fraction * self.finger_length / self.params.servo.spool_radius

    def check_set_point(self, protocol) -> None:
        """With the controller, the set-point against the servo's stall tension; a per-object
        policy has no set-point."""
        if protocol.policy == "controller":
            check_grip_tension(protocol.grip_tension, self.params.servo.max_cable_tension)

    def grip_controller(self, m, sensor, protocol) -> GripController | None:
        if protocol.policy != "controller":
            return None
        s = self.params.servo
        kp, _ = servo_gains(self.params)
        return GripController(m, self.actuator_ids(m), sensor, grip_tension=protocol.grip_tension,
                              close_rate=self.open_loop_rate(protocol), spool_radius=s.spool_radius, kp=kp)

    def open_loop_rate(self, protocol) -> float:
        """The protocol's cable speed over the spool radius [rad/s]."""
        return protocol.close_speed / self.params.servo.spool_radius

    def controller_outcome(self, grip) -> dict:
        times = grip.contact_time
        return {**super().controller_outcome(grip),
                "contact_time_s": float(np.nanmin(times)) if np.isfinite(times).any() else None}

    def close_command(self, grip) -> float | None:
        return float(grip.goal.max())

    def _indices(self, m: mujoco.MjModel) -> dict[str, np.ndarray]:
        if self._index is None or self._index[0] is not m:
            n = self.params.layout.n_fingers
            self._index = (m, {
                "reel": np.array([m.jnt_qposadr[m.joint(self.names(k).reel).id] for k in range(n)]),
                "tension": self.effort_sensors(m)[0], "act": self.actuator_ids(m)})
        return self._index[1]

    def observe_state(self, m, d, sensordata) -> list[np.ndarray]:
        i = self._indices(m)
        reel = d.qpos[i["reel"]]
        return [reel, sensordata[i["tension"]], reel / self.params.servo.spool_radius, d.ctrl[i["act"]]]

    def observe_sensed(self, m, reading: ServoReading) -> list[np.ndarray]:
        return [reading.position, reading.current, reading.tension]


def cable_pad_vertices(p: GripperParams, kind: ElementKind) -> np.ndarray:
    """A cable element's collision surface: its prism (the tip's tapered), every edge rounded to
    ``contact.edge_radius``.

    Raises:
        ValueError: naming ``contact.edge_radius``, when the rounding does not fit the element.
    """
    g = p.finger
    try:
        return hull_vertices(rounded_prism(element_profile(g, kind), g.width, p.contact.edge_radius,
                                           taper=element_taper(g, kind)))
    except ValueError as err:
        raise ValueError(f"contact.edge_radius: {p.contact.edge_radius!r} m does not fit this finger's "
                         f"elements ({err})") from None


