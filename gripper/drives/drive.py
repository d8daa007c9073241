"""A drive: one kind of finger and what bends it, as one component.

Everything above this layer (the model's assembly, trials, the environment, the envelope, video
and studies) asks the gripper's drive (:func:`drive_for`) and never tests its kind. A drive says
what it adds to the model (its fingers, their actuators and sensors, its default classes), what
it senses (a sensor with the hardware's resolution and noise), how it is commanded (one command
per finger: a spool angle, a pressure, ...) and closed on an object (its grip controller and
set-point), and where its datasheet is.

The two drives: :class:`gripper.drives.cable.drive.CableDrive` (paper 000's finger, a cable
reeled in by a servo) and :class:`gripper.drives.pneumatic.drive.PneumaticDrive` (paper 001's
actuator, its chamber fed by a pressure regulator). A third registers itself with
:func:`register_drive` under a new ``actuation.kind`` (``tests/test_drives.py`` builds and runs
a trial with one defined in the test file).

Example:
    >>> from gripper.core.params import GripperParams
    >>> from gripper.drives import drive_for
    >>> drive = drive_for(GripperParams())
    >>> drive.kind, drive.set_point_field, drive.names(0).drive
    ('cable', 'grip_tension', 'f0_servo')
"""

from __future__ import annotations

import importlib
from abc import ABC, abstractmethod
from typing import Any, ClassVar, Protocol

import mujoco
import numpy as np

from gripper.core.fields import Validated
from gripper.core.params import ACTUATIONS, GripperParams
from gripper.parts.names import FingerNames


class DriveReading(Protocol):
    """What a drive's sensor reports at one instant: ``effort`` is the per-finger quantity the
    grip set-point is in (cable tension [N], chamber pressure [Pa])."""

    @property
    def effort(self) -> np.ndarray: ...


class DriveSensor(Protocol):
    """Reads a drive's hardware from one MuJoCo sensor row (quantised and noisy as the real one)."""

    def read(self, sensordata: np.ndarray, rng: np.random.Generator | None = None) -> DriveReading: ...


class GripControl(Protocol):
    """A grip controller the trial steps once per control period (chunk)."""

    goal: np.ndarray
    grip_time: float

    def start(self, d: mujoco.MjData) -> None: ...
    def goals(self, t: np.ndarray) -> np.ndarray: ...
    def update(self, d: mujoco.MjData) -> None: ...
    def settled(self) -> bool: ...
    def release(self) -> None: ...


class Drive(ABC):
    """One kind of finger and its actuator (see the module docstring). Built from the whole
    gripper's parameters; reads its own sections of them."""

    #: the ``actuation.kind`` that selects this drive
    kind: ClassVar[str]
    #: the gripper model's name: its MJCF ``model``, root default class and ``models/`` folder
    model_name: ClassVar[str]
    #: the parameter sections the drive's gripper reads (its model README's table)
    sections: ClassVar[tuple[str, ...]] = ("material", "layout", "lift", "sim", "contact", "actuation")
    #: the :class:`gripper.experiments.protocol.GraspProtocol` field holding the grip set-point
    #: ("": the drive has no grip controller, only per-object commands)
    set_point_field: ClassVar[str] = ""
    #: the drive entry's key for the set-point a controller gripped at (SI units in its name)
    set_point_record: ClassVar[str] = "set_point"
    #: the drive entry's keys for the trial's peak effort and for the closing command reached
    #: (SI units in their names; ``gripper.experiments.record``)
    peak_effort_record: ClassVar[str] = "peak_effort"
    command_record: ClassVar[str] = "close_command"
    #: the settings of what the drive reports (a validated dataclass: resolution, noise), or
    #: None for a drive without any (its sensor then reads the model as it is)
    sensing_class: ClassVar[type[Validated] | None] = None
    #: label of the sensed effort in videos, and the factor from SI to its unit there
    effort_label: ClassVar[str]
    effort_display_scale: ClassVar[float] = 1.0
    effort_format: ClassVar[str] = "4.1f"
    #: design-study responses this drive can run (``gripper.studies.study_file.RESPONSES``)
    responses: ClassVar[tuple[str, ...]] = ("grasp", "holding_force", "envelope", "payload", "parts")
    #: the environment's observation parts of this drive, (name, unit) with one entry per finger
    #: each: after the hinge velocities, and at the end (what the hardware reports)
    state_observations: ClassVar[tuple[tuple[str, str], ...]] = ()
    sensed_observations: ClassVar[tuple[tuple[str, str], ...]] = ()

    def __init__(self, params: GripperParams):
        self.params = params

    @property
    def datasheet(self) -> Any:
        """The actuator's datasheet (:mod:`gripper.datasheets`), or None for a drive without one."""
        return None

    # --- the finger -------------------------------------------------------------------------
    @property
    @abstractmethod
    def n_segments(self) -> int:
        """Rigid bodies in one finger's chain (each carries a pad) [-]."""

    @property
    @abstractmethod
    def finger_length(self) -> float:
        """From the palm face to the fingertip, straight [m]."""

    @property
    @abstractmethod
    def finger_height(self) -> float:
        """From the finger's back to its grasping face [m]."""

    @property
    @abstractmethod
    def finger_width(self) -> float:
        """Across the finger, at its base [m]."""

    @abstractmethod
    def names(self, k: int) -> FingerNames:
        """Finger ``k``'s element names in the model."""

    def derived_parameters(self) -> list[tuple[str, str, str, str]]:
        """(section, name, value, unit) of figures derived from the parameters, for the model README."""
        return []

    def actuator_name(self, k: int) -> str:
        return self.names(k).drive

    def actuator_ids(self, m: mujoco.MjModel) -> np.ndarray:
        """Each finger's drive actuator in ``m``."""
        return np.array([m.actuator(self.actuator_name(k)).id for k in range(self.params.layout.n_fingers)])

    # --- the model --------------------------------------------------------------------------
    def add_defaults(self, spec: mujoco.MjSpec, defaults: dict) -> None:
        """Add the drive's own default classes under ``defaults["root"]`` into ``defaults`` (none by default)."""
        return None

    @abstractmethod
    def add_meshes(self, spec: mujoco.MjSpec) -> None:
        """The meshes of the finger's bodies."""

    @abstractmethod
    def add_finger(self, spec: mujoco.MjSpec, parent: mujoco.MjsBody, k: int, pos, quat, defaults: dict,
                   pads) -> FingerNames:
        """Finger ``k`` with its actuator and sensors under ``parent`` at ``pos``/``quat`` (its
        finger frame: x from the palm to the tip, z towards the grasping face); ``pads``: a
        :class:`gripper.parts.pads.PadMaker` or None."""

    def configure(self, spec: mujoco.MjSpec) -> None:
        """Change the physics options the drive needs (after :func:`gripper.parts.defaults.set_options`;
        none by default)."""
        return None

    def tune(self, spec: mujoco.MjSpec) -> None:
        """Set what depends on the compiled model (soft limits from physical stiffnesses; nothing by default)."""
        return None

    def tune_for_trials(self, spec: mujoco.MjSpec) -> None:
        """Match what depends on the trials' integrator (``spec`` has it set; nothing by default)."""
        return None

    # --- contact (gripper.parts.pads) -----------------------------------------------------
    @property
    @abstractmethod
    def contact_modulus(self) -> float:
        """The finger surface's effective modulus E* = E / (1 - nu²) in Hertz's law [Pa]."""

    @property
    @abstractmethod
    def pad_depth(self) -> float:
        """How far a pad can be pressed in before it bottoms out [m]."""

    @abstractmethod
    def pad_vertices(self, kind: str) -> np.ndarray:
        """The rounded collision surface of a pad of element kind ``kind`` (finger frame) [m]."""

    @abstractmethod
    def pad_kinds(self) -> tuple[str, ...]:
        """The element kinds that need a pad mesh ``pad_{kind}``."""

    @abstractmethod
    def element_vertices(self, j: int) -> np.ndarray:
        """The convex body of element ``j`` (1-based) in its own frame [m]."""

    @abstractmethod
    def element_kind(self, j: int) -> str:
        """Element ``j``'s kind (1-based), the suffix of its meshes."""

    @abstractmethod
    def face_area(self, j: int) -> float:
        """Element ``j``'s grasping face, the area its pad covers [m²]."""

    # --- sensing and command ----------------------------------------------------------------
    @abstractmethod
    def sensor(self, m: mujoco.MjModel, rng: np.random.Generator | None = None, sensing=None) -> DriveSensor:
        """What the drive reports (``sensing``: the hardware's settings, drive-specific)."""

    def trial_sensing(self, sensing: Any = None) -> Any:
        """The sensing settings a trial runs this drive with: ``sensing``, which must be this
        drive's :attr:`sensing_class`, else its defaults; None for a drive without settings.

        Raises:
            ValueError: another drive's settings, naming the ones this drive takes.
        """
        want = self.sensing_class
        if sensing is None:
            return want().validate() if want is not None else None
        if want is None or not isinstance(sensing, want):
            allowed = want.__name__ if want is not None else "none"
            raise ValueError(f"sensing: the {self.kind} drive takes {allowed}, got {type(sensing).__name__}")
        return sensing.validate()

    @abstractmethod
    def effort_sensors(self, m: mujoco.MjModel) -> tuple[np.ndarray, np.ndarray]:
        """Sensor addresses and divisors: each finger's true effort (in the set-point's unit: N of
        cable tension, Pa of chamber pressure) is its sensor value over its divisor."""

    @abstractmethod
    def command_rate(self, protocol) -> float:
        """How fast the command moves in velocity control [command unit/s] (``protocol``: a
        :class:`gripper.experiments.protocol.GraspProtocol`, for drives whose rate is the grasp's)."""

    @abstractmethod
    def reach_commands(self) -> np.ndarray:
        """Commands at which the free fingers' reach is tabulated (``gripper.experiments.approach``)."""

    def shortening_command(self, fraction: float) -> float:
        """The command that draws in ``fraction`` × finger length of the drive's cable (a design
        study's ``blocked_force.r``); a drive without a cable refuses."""
        raise ValueError(f"actuation.kind: the {self.kind} drive has no cable to shorten")

    # --- closing on an object ---------------------------------------------------------------
    def set_point(self, protocol) -> float:
        return float(getattr(protocol, self.set_point_field))

    def check_set_point(self, protocol) -> None:
        """Refuse a protocol this drive cannot run (one line naming the field). By default a
        drive without a grip set-point (:attr:`set_point_field` empty) runs the per-object
        policy only."""
        if not self.set_point_field and protocol.policy != "per_object":
            raise ValueError(f"protocol.policy: the {self.kind} gripper closes by each object's command only "
                             "(policy = \"per_object\"): it has no grip controller")

    def grip_controller(self, m: mujoco.MjModel, sensor: DriveSensor, protocol) -> GripControl | None:
        """The protocol's grip controller, or None when the protocol ramps a per-object command
        (the default: a drive without a controller)."""
        return None

    @abstractmethod
    def open_loop_rate(self, protocol) -> float:
        """The per-object ramp's rate [command unit/s] (without a grip controller)."""

    def controller_outcome(self, grip: GripControl) -> dict:
        """What the trial records of its grip controller beside the drive's entry: when the
        grasp was made (and, where the drive detects it, the first contact)."""
        return {"grasp_time_s": None if np.isnan(grip.grip_time) else grip.grip_time}

    def command_outcome(self, grip: GripControl | None, close_command: float) -> dict:
        """The drive entry's closing command: the per-object ``close_command`` (no grip
        controller), or the controller's set-point and the command it reached."""
        if grip is None:
            return {self.command_record: close_command}
        reached = self.close_command(grip)
        return {self.set_point_record: self.set_point_of(grip),
                **({self.command_record: reached} if reached is not None else {})}

    def format_set_point(self, value: float) -> str:
        """A set-point for people: in the unit of ``set_point_record``'s name."""
        return f"{value:g} {self.set_point_record.rsplit('_', 1)[-1]}"

    def set_point_of(self, grip: GripControl) -> float:
        return float(getattr(grip, self.set_point_field))

    def close_command(self, grip: GripControl) -> float | None:
        """The closing command a grip controller reached (the drive entry's ``command_record``),
        if the drive has one."""
        return None

    def fingertip_clearance(self, protocol) -> float:
        """The fingertip grasp's gap between the fingertips and the support [m] (by default the
        protocol's ``fingertip_clearance``)."""
        return protocol.fingertip_clearance

    def trial_outcome(self, peak_effort: float) -> dict:
        """The drive's entry in a trial record (its ``drive`` key): its kind and the trial's
        peak effort, under the drive's own key."""
        return {"kind": self.kind, self.peak_effort_record: peak_effort}

    # --- the environment ------------------------------------------------------------------
    def observe_state(self, m: mujoco.MjModel, d: mujoco.MjData, sensordata: np.ndarray) -> list[np.ndarray]:
        """The parts named in ``state_observations``, in order (one entry per finger each)."""
        return []

    def observe_sensed(self, m: mujoco.MjModel, reading) -> list[np.ndarray]:
        """The parts named in ``sensed_observations``, in order, from the sensor's reading."""
        return []


_DRIVES: dict[str, str | type[Drive]] = {
    "cable": "gripper.drives.cable.drive:CableDrive",
    "pneumatic": "gripper.drives.pneumatic.drive:PneumaticDrive",
}
# The drives the package ships (``models/`` holds a gripper of each); they stay registered.
SHIPPED_DRIVES = tuple(_DRIVES)


def register_drive(kind: str, drive: str | type[Drive]) -> None:
    """Make ``actuation.kind = kind`` select ``drive`` (a :class:`Drive` subclass, or its
    ``"module:Class"`` path, imported on first use)."""
    if not kind.isidentifier():
        raise ValueError(f"actuation.kind: a drive's name must be an identifier, got {kind!r}")
    _DRIVES[kind] = drive
    if kind not in ACTUATIONS:
        ACTUATIONS.append(kind)


def unregister_drive(kind: str) -> None:
    """Undo :func:`register_drive` for a drive that is not shipped."""
    if kind in SHIPPED_DRIVES:
        raise ValueError(f"actuation.kind: {kind!r} is a shipped drive and stays registered")
    _DRIVES.pop(kind, None)
    if kind in ACTUATIONS:
        ACTUATIONS.remove(kind)


def drive_class(kind: str) -> type[Drive]:
    """The drive registered as ``kind``."""
    if kind not in _DRIVES:
        raise ValueError(f"actuation.kind: must be one of {', '.join(_DRIVES)}, got {kind!r}")
    entry = _DRIVES[kind]
    if isinstance(entry, str):
        module, name = entry.split(":")
        entry = _DRIVES[kind] = getattr(importlib.import_module(module), name)
    return entry


def drive_for(params: GripperParams) -> Drive:
    """The drive of ``params`` (``params.actuation.kind``)."""
    return drive_class(params.actuation.kind)(params)


def registered_drives() -> list[str]:
    """The names of every registered drive."""
    return list(_DRIVES)


__all__ = ["SHIPPED_DRIVES", "Drive", "DriveReading", "DriveSensor", "GripControl", "drive_class", "drive_for",
           "register_drive", "registered_drives", "unregister_drive"]
