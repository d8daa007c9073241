"""Parameters of the soft gripper: frozen dataclasses, SI units, ``validate()``, JSON/TOML files.

Every field states its unit. Numbers from paper 000 ("Dynamic Modeling and Grasping Application
of a Cable-Driven Soft Actuator") and paper 001 cite their table; dimensions the papers do not
give (their figures are lost) are chosen here and the reason is written beside them and in
``gripper/data/soft_gripper/README.md``.

Example:
    >>> from gripper.core.params import GripperParams
    >>> p = GripperParams()
    >>> p.finger.n_segments, p.layout.n_fingers
    (6, 4)
    >>> p2 = p.replace(finger=p.finger.replace(pitch=0.018)).validate()
"""

from __future__ import annotations

import dataclasses
import json
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from gripper.core.resources import MODEL_DIR
from gripper.core.servo import SERVO_PRESETS, ServoDatasheet, servo_datasheet

DEG = math.pi / 180.0

# paper 000, Table 2: torsion spring stiffness 1.9e-3 N·m/deg = 0.1089 N·m/rad, as printed. The
# unit is suspect (see docs/consistency.md): read per radian it is 1.9e-3 N·m/rad.
PAPER_HINGE_STIFFNESS = 1.9e-3 / DEG
PAPER_HINGE_STIFFNESS_PER_RAD_READING = 1.9e-3
# The committed calibration of the default design (``gripper calibrate --write-default``): the
# default hinge springs are its fitted values. A test fails when it is stale.
DEFAULT_CALIBRATION_FILE = MODEL_DIR / "calibration.json"
# How a closed cut resists further closing (HingeSprings.closure).
CLOSURE_MODELS = ("teeth", "stiffness", "rigid")
# Named spring sets of the command line's --springs (HingeSprings.paper's readings).
SPRING_SETS = ("calibrated", "paper", "paper_per_radian")
# Tip element's inertia about its proximal hinge [kg·m²] (default design: 16x16x18 mm of
# 1120 kg/m³ silicone, less its cuts, ~3.6 g at ~13 mm), for HingeSprings.paper's damping.
TIP_ELEMENT_INERTIA = 8.3e-7


def _finite(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ValueError(f"{name}: expected a number, got {value!r}")
    if not math.isfinite(value):
        raise ValueError(f"{name}: must be finite, got {value!r}")
    return float(value)


def _positive(name: str, value: Any) -> None:
    if _finite(name, value) <= 0.0:
        raise ValueError(f"{name}: must be > 0, got {value!r}")


def _nonneg(name: str, value: Any) -> None:
    if _finite(name, value) < 0.0:
        raise ValueError(f"{name}: must be >= 0, got {value!r}")


def check_between(name: str, value: Any, lo: float, hi: float, *, closed: bool = False) -> None:
    v = _finite(name, value)
    ok = lo <= v <= hi if closed else lo < v < hi
    if not ok:
        brackets = f"[{lo:g}, {hi:g}]" if closed else f"({lo:g}, {hi:g})"
        raise ValueError(f"{name}: must be in {brackets}, got {value!r}")


def _integer(name: str, value: Any, lo: int, hi: int) -> None:
    if isinstance(value, bool) or not isinstance(value, int):
        raise ValueError(f"{name}: expected an integer in [{lo}, {hi}], got {value!r}")
    if not lo <= value <= hi:
        raise ValueError(f"{name}: must be an integer in [{lo}, {hi}], got {value!r}")


def _committed_springs() -> tuple[tuple[float, ...], tuple[float, ...], tuple[float, ...]]:
    """(stiffness, damping, rest_angle_deg) fitted in :data:`DEFAULT_CALIBRATION_FILE`.

    Read once, at import, with no checks beyond shape (the schema and the design hash are
    checked by :mod:`gripper.calibration.calfile` and by the staleness test).
    """
    try:
        fitted = json.loads(DEFAULT_CALIBRATION_FILE.read_text())["fitted"]
        out = tuple(tuple(float(v) for v in fitted[key]) for key in
                    ("stiffness_Nm_per_rad", "damping_Nms_per_rad", "rest_angle_deg"))
    except (OSError, KeyError, TypeError, ValueError) as e:
        raise ImportError(f"gripper: the default design's committed calibration "
                          f"{DEFAULT_CALIBRATION_FILE} is missing or malformed ({e}); "
                          f"regenerate it with 'gripper calibrate --write-default'") from None
    return out  # type: ignore[return-value]


CALIBRATED_STIFFNESS, CALIBRATED_DAMPING, CALIBRATED_REST_ANGLE_DEG = _committed_springs()
_CALIBRATED = {"stiffness": CALIBRATED_STIFFNESS, "damping": CALIBRATED_DAMPING,
               "rest_angle_deg": CALIBRATED_REST_ANGLE_DEG}


class _Replace:
    def replace(self, **changes: Any):
        """A copy with ``changes`` applied (``dataclasses.replace``)."""
        return dataclasses.replace(self, **changes)


@dataclass(frozen=True)
class FingerGeometry(_Replace):
    """Geometry of one finger: a silicone bar cut by triangular notches into elements.

    Finger frame: x along the finger from the palm to the tip, z from the back (bridge side,
    z = 0) to the grasping face (z = ``height``), y across. Cuts open on the grasping face;
    the cable runs through holes above the bridge, so pulling it closes the cuts and curls the
    finger towards its grasping face.

    Attributes:
        n_segments: number of elements, the base element B1 fixed to the palm included
            [-] (paper 000 §III: six elements B1..B6, five spring hinges).
        pitch: element length along the finger, cut centre to cut centre [m]. Assumed 16 mm:
            96 mm fingers, about the size of the paper's photographed gripper fingers.
        width: element width across the finger (y) [m]. Assumed 16 mm.
        height: element height from back to grasping face (z) [m]. Assumed 18 mm: room for
            a bridge of a few mm (1.9 mm, below), a 6 mm hole and 3 mm of wall on the grasping
            face.
        cut_angle_deg: opening angle of each triangular cut [deg] (paper 000 §II: 45°). A hinge
            stops where its cut closes (:attr:`closure_angle_deg`).
        bridge_thickness: silicone left under each cut [m]. 1.9 mm: the bridge at which the
            mesh-converged continuum body of paper 000's silicone has the equivalent hinge
            spring of Table 2's "1.9e-3 N·m/deg" read per radian (root 1.892 mm, a root-find on
            the reference, ``docs/consistency.md``), the one reading a bridge of this finger can
            reach (read per degree it needs more than the 8.3 mm the channel leaves). The
            paper gives no dimension; 0.5.x assumed 3 mm.
        hole_height: height of the cable-hole axis above the back face [m]. Assumed 12 mm:
            10.1 mm above the bridge (the brief's 8-10 mm), an 11.05 mm lever arm about the
            hinge.
        hole_diameter: diameter of the cable holes [m] (paper 000 §II: 6 mm).
        extension_limit_deg: how far a hinge may bend backwards (opening the cut) [deg].
            Assumed 5°: the bridge and the closed back face resist extension stiffly.
    """

    n_segments: int = 6
    pitch: float = 0.016
    width: float = 0.016
    height: float = 0.018
    cut_angle_deg: float = 45.0
    bridge_thickness: float = 0.0019
    hole_height: float = 0.012
    hole_diameter: float = 0.006
    extension_limit_deg: float = 5.0

    @property
    def n_hinges(self) -> int:
        """Number of spring hinges, one per cut [-]."""
        return self.n_segments - 1

    @property
    def length(self) -> float:
        """Finger length from the palm face to the tip [m]."""
        return self.n_segments * self.pitch

    @property
    def cut_half_width(self) -> float:
        """Half the cut's opening at the grasping face [m]."""
        return (self.height - self.bridge_thickness) * math.tan(0.5 * self.cut_angle_deg * DEG)

    @property
    def closure_angle_deg(self) -> float:
        """Hinge angle at which the cut's faces touch, at the grasping face [deg].

        The hinge turns about the bridge's neutral axis (``hinge_z``), below the cut's apex, so
        the faces meet first at the grasping face: theta = 2·atan(w / (height - hinge_z)), w the
        cut's half-opening there. Slightly less than ``cut_angle_deg`` (42.7° for the default).
        """
        return 2.0 * math.degrees(math.atan(self.cut_half_width / (self.height - self.hinge_z)))

    @property
    def hinge_z(self) -> float:
        """Height of the hinge axes: the middle of the bridge, its neutral axis [m]."""
        return 0.5 * self.bridge_thickness

    def validate(self) -> FingerGeometry:
        _integer("finger.n_segments", self.n_segments, 2, 64)
        for name in ("pitch", "width", "height", "bridge_thickness", "hole_height",
                     "hole_diameter"):
            _positive(f"finger.{name}", getattr(self, name))
        check_between("finger.cut_angle_deg", self.cut_angle_deg, 0.0, 90.0)
        check_between("finger.extension_limit_deg", self.extension_limit_deg, 0.0, 90.0,
                 closed=True)
        if self.bridge_thickness >= self.height:
            raise ValueError(
                f"finger.bridge_thickness: must be < finger.height ({self.height:g} m), "
                f"got {self.bridge_thickness!r}")
        lo = self.bridge_thickness + 0.5 * self.hole_diameter
        hi = self.height - 0.5 * self.hole_diameter
        if not lo <= self.hole_height <= hi:
            raise ValueError(
                f"finger.hole_height: the hole must lie between the bridge and the grasping "
                f"face, in [{lo:g}, {hi:g}] m, got {self.hole_height!r}")
        if 2.0 * self.cut_half_width >= self.pitch:
            raise ValueError(
                f"finger.cut_angle_deg: cuts of {self.cut_angle_deg:g}° would meet at the "
                f"grasping face; need 2·(height-bridge)·tan(angle/2) < pitch "
                f"({self.pitch:g} m)")
        return self


@dataclass(frozen=True)
class Material(_Replace):
    """Silicone of the finger body.

    Attributes:
        density: [kg/m³] (paper 000, Table 1: 1.12 g/cm³).
        youngs_modulus: [Pa] (paper 000, Table 2: 0.44 MPa).
        poisson_ratio: [-] (paper 000, Table 2: 0.48).
        shore_a: hardness [Shore A] (paper 000, Table 1: 20 ± 2 A).
        tensile_strength: [Pa] (paper 000, Table 1: 4 MPa).
        elongation_at_break: strain at break [-] (paper 000, Table 1: >= 500 %).
        yeoh_c10, yeoh_c20, yeoh_c30: Yeoh coefficients of RTV 230 silicone [Pa]
            (paper 001, §2.3: 0.11596, 0.0168, -0.000319 MPa).
        friction: sliding friction coefficient of the silicone pads [-]. Assumed 1.0:
            soft silicone on dry plastic, paper and latex is typically 0.8-1.5.
    """

    density: float = 1120.0
    youngs_modulus: float = 0.44e6
    poisson_ratio: float = 0.48
    shore_a: float = 20.0
    tensile_strength: float = 4.0e6
    elongation_at_break: float = 5.0
    yeoh_c10: float = 0.11596e6
    yeoh_c20: float = 0.0168e6
    yeoh_c30: float = -0.000319e6
    friction: float = 1.0

    def validate(self) -> Material:
        for name in ("density", "youngs_modulus", "tensile_strength", "elongation_at_break",
                     "friction"):
            _positive(f"material.{name}", getattr(self, name))
        check_between("material.poisson_ratio", self.poisson_ratio, -1.0, 0.5)
        check_between("material.shore_a", self.shore_a, 0.0, 100.0, closed=True)
        for name in ("yeoh_c10", "yeoh_c20", "yeoh_c30"):
            _finite(f"material.{name}", getattr(self, name))
        return self


@dataclass(frozen=True)
class HingeSprings(_Replace):
    """Torsion springs at the bridges, one value per hinge or one value for all.

    The defaults are the committed calibration of the default design
    (:data:`DEFAULT_CALIBRATION_FILE`: the hinge finger fitted to the converged continuum
    reference, see ``docs/calibration.md``). :meth:`paper` gives paper 000's Table 2 spring
    instead, for comparison.

    Attributes:
        stiffness: per-hinge stiffness [N·m/rad]. Default: fitted (committed calibration).
        damping: per-hinge damping [N·m·s/rad]. Default: fitted to the reference's transient,
            which carries paper 000's modal damping 0.5 (Table 2). The paper's own "10
            N·m·s/deg" is implausible (K/c ≈ 5000 s) and is not used.
        rest_angle_deg: spring rest angle of each hinge [deg]; 0 = moulded straight.
        closure: how a hinge resists closing past its closure angle, where the faces of its
            cut meet (see :mod:`gripper.model.closure`):

            - ``"teeth"`` (default): the silicone teeth on either side of the cut are
              squeezed, a neo-Hookean solid of the finger's Young's modulus: 2.25 N·m/rad for
              the default design at small overrun, stiffening fivefold by 8.2° as the thin tips
              are squashed (:mod:`gripper.model.closure`). Independent of the time step, so grasp
              results are too.
            - ``"stiffness"``: a linear compliant stop of ``closure_stiffness``.
            - ``"rigid"``: a hard stop as stiff as the time step allows (limit time constant
              four steps): the idealisation of paper 000's hinge chain. Its overrun grows as
              the step squared (0.3° at stall tension at 5e-4 s, 6° at 2 ms), so grasp
              results then depend on the step.
        closure_stiffness: rotational stiffness of a closed cut [N·m/rad], used only when
            ``closure == "stiffness"``. The default 1.0 is a placeholder of the teeth
            estimate's order; set it from a measurement.
    """

    stiffness: tuple[float, ...] = CALIBRATED_STIFFNESS
    damping: tuple[float, ...] = CALIBRATED_DAMPING
    rest_angle_deg: tuple[float, ...] = CALIBRATED_REST_ANGLE_DEG
    closure: str = "teeth"
    closure_stiffness: float = 1.0

    @classmethod
    def paper(cls, reading: str = "per_degree", **changes: Any) -> HingeSprings:
        """Paper 000's Table 2 spring on every hinge, for comparison with the calibrated default.

        Args:
            reading: ``"per_degree"`` (as printed, 1.9e-3 N·m/deg = 0.109 N·m/rad) or
                ``"per_radian"`` (1.9e-3 N·m/rad).

        Damping: the paper's modal damping 0.5 (Table 2) applied to the tip element's own
        hinge mode, c = 2·0.5·sqrt(K·I_tip), I_tip ≈ 8.3e-7 kg·m² about its hinge (the
        paper's "10 N·m·s/deg" is implausible: K/c ≈ 5000 s).
        """
        k = {"per_degree": PAPER_HINGE_STIFFNESS,
             "per_radian": PAPER_HINGE_STIFFNESS_PER_RAD_READING}.get(reading)
        if k is None:
            raise ValueError(f"springs reading: must be per_degree or per_radian, got {reading!r}")
        c = 2.0 * 0.5 * math.sqrt(k * TIP_ELEMENT_INERTIA)
        return cls(stiffness=(k,), damping=(c,), rest_angle_deg=(0.0,), **changes)

    def per_hinge(self, n_hinges: int) -> tuple[tuple[float, ...], ...]:
        """(stiffness, damping, rest_angle_deg), each broadcast to ``n_hinges`` values.

        The committed calibration's per-hinge values (the defaults) on a finger with another
        number of hinges become their mean on every hinge: that calibration is of the default
        design, so recalibrate such a design (``gripper calibrate --params``).
        """
        out = []
        for name in ("stiffness", "damping", "rest_angle_deg"):
            v = tuple(getattr(self, name))
            if len(v) not in (1, n_hinges) and v == _CALIBRATED[name]:
                v = (sum(v) / len(v),)
            out.append(v * n_hinges if len(v) == 1 else v)
        return tuple(out)

    def validate(self, n_hinges: int | None = None) -> HingeSprings:
        for name, check in (("stiffness", _positive), ("damping", _nonneg),
                            ("rest_angle_deg", _finite)):
            values = getattr(self, name)
            if not isinstance(values, tuple | list) or len(values) == 0:
                raise ValueError(f"springs.{name}: expected a non-empty list of numbers, "
                                 f"got {values!r}")
            if (n_hinges is not None and len(values) not in (1, n_hinges)
                    and tuple(values) != _CALIBRATED[name]):
                raise ValueError(f"springs.{name}: expected 1 or {n_hinges} values (one per "
                                 f"hinge), got {len(values)}")
            for i, v in enumerate(values):
                check(f"springs.{name}[{i}]", v)
        for i, v in enumerate(self.rest_angle_deg):
            check_between(f"springs.rest_angle_deg[{i}]", v, -90.0, 90.0)
        if self.closure not in CLOSURE_MODELS:
            raise ValueError(f"springs.closure: must be one of {', '.join(CLOSURE_MODELS)}, "
                             f"got {self.closure!r}")
        _positive("springs.closure_stiffness", self.closure_stiffness)
        return self


@dataclass(frozen=True)
class Cable(_Replace):
    """The driving cable (paper 000 §II: polyethylene fibre, Ø 0.5 mm, fixed at the tip).

    Attributes:
        diameter: [m] (paper 000 §II: 0.5 mm).
        youngs_modulus: effective axial modulus of the braided fibre [Pa]. Assumed 50 GPa:
            UHMW-polyethylene fibre is 100-120 GPa, a braided line about half of that.
        friction_loss: dry friction of the cable in its holes [N]. Assumed 0: the 0.5 mm cable
            runs loose in 6 mm holes (paper 000 §II).
    """

    diameter: float = 0.5e-3
    youngs_modulus: float = 50e9
    friction_loss: float = 0.0

    @property
    def axial_stiffness(self) -> float:
        """EA [N]: force per unit strain of the cable."""
        return self.youngs_modulus * math.pi * (0.5 * self.diameter) ** 2

    def validate(self) -> Cable:
        _positive("cable.diameter", self.diameter)
        _positive("cable.youngs_modulus", self.youngs_modulus)
        _nonneg("cable.friction_loss", self.friction_loss)
        return self


@dataclass(frozen=True)
class ServoParams(_Replace):
    """The servo that reels each cable in: a datasheet preset, a spool and controller tuning.

    Attributes:
        preset: key of :data:`gripper.core.servo.SERVO_PRESETS` ("hobby_6v" or "smart_12v").
        spool_radius: radius the cable winds on [m]. Assumed 15 mm: 180° of hobby-servo
            travel then reels in 47 mm, enough to close all five default cuts (≈ 50 mm).
        saturation_error_deg: position error at which the PD asks for the stall torque [deg].
            Assumed 0.6°, about a hobby servo's dead band.
        damping_ratio: damping ratio of the position loop on the rotor inertia [-]. Assumed 1.
        contraction_speed: default cable contraction speed, the slew limit of the position
            set-point [m/s]; 0 means the servo's no-load speed times the spool radius.
    """

    preset: str = "hobby_6v"
    spool_radius: float = 0.020
    saturation_error_deg: float = 0.6
    damping_ratio: float = 1.0
    contraction_speed: float = 0.0

    @property
    def datasheet(self) -> ServoDatasheet:
        return servo_datasheet(self.preset)

    @property
    def max_cable_tension(self) -> float:
        """Stall torque / spool radius [N]."""
        return self.datasheet.stall_torque / self.spool_radius

    @property
    def slew_rate(self) -> float:
        """Slew limit of the servo-angle set-point [rad/s]."""
        v = self.contraction_speed or self.datasheet.no_load_speed * self.spool_radius
        return v / self.spool_radius

    def validate(self) -> ServoParams:
        if not isinstance(self.preset, str) or self.preset not in SERVO_PRESETS:
            servo_datasheet(str(self.preset))  # raises with the allowed names
        _positive("servo.spool_radius", self.spool_radius)
        check_between("servo.saturation_error_deg", self.saturation_error_deg, 0.0, 90.0)
        _positive("servo.damping_ratio", self.damping_ratio)
        _nonneg("servo.contraction_speed", self.contraction_speed)
        return self


@dataclass(frozen=True)
class GripperLayout(_Replace):
    """How the fingers sit on the palm.

    Attributes:
        n_fingers: number of fingers, evenly spaced around the palm axis [-] (paper 000 §V:
            four).
        palm_radius: distance from the palm axis to each finger's grasping face [m]. Assumed
            40 mm: an 80 mm opening takes the balloon, boxes and cylinders of the grasp set.
        palm_thickness: thickness of the palm plate [m]. Assumed 20 mm (3D-printed hub).
        mount_tilt_deg: finger splay at the mount, positive tilting the tips outwards [deg].
            Assumed 0 (fingers hang straight down, as in the paper's photograph).
        palm_mass: mass of palm, servos and cable routing, carried by the lift [kg]. Assumed
            0.35 kg: four 55 g servos plus a printed hub.
    """

    n_fingers: int = 4
    palm_radius: float = 0.040
    palm_thickness: float = 0.020
    mount_tilt_deg: float = 0.0
    palm_mass: float = 0.35

    def validate(self) -> GripperLayout:
        _integer("layout.n_fingers", self.n_fingers, 1, 12)
        _positive("layout.palm_radius", self.palm_radius)
        _positive("layout.palm_thickness", self.palm_thickness)
        check_between("layout.mount_tilt_deg", self.mount_tilt_deg, -45.0, 45.0, closed=True)
        _positive("layout.palm_mass", self.palm_mass)
        return self


@dataclass(frozen=True)
class LiftAxis(_Replace):
    """The stage that carries the palm: a vertical lift axis, optional x/y axes.

    Each axis is a position-controlled linear stage (MuJoCo ``position`` actuator).

    Attributes:
        z_travel: lift travel below and above the home height [m]. Assumed ±0.25 m.
        xy_enabled: add horizontal x and y axes (needed to shake the object) [-].
        xy_travel: horizontal travel either side [m]. Assumed ±0.05 m.
        stiffness: position gain of each axis [N/m]. Assumed 4000 N/m: 1 mm error per 4 N.
        damping_ratio: damping ratio of each axis with the palm mass [-]. Assumed 1.
        max_force: force limit of each axis [N]. Assumed 60 N, a small linear stage.
        home_height: palm-face height above the floor at zero lift [m]. Assumed 0.25 m:
            96 mm fingers clear a 100 mm object with room to approach.
    """

    z_travel: float = 0.25
    xy_enabled: bool = True
    xy_travel: float = 0.05
    stiffness: float = 4000.0
    damping_ratio: float = 1.0
    max_force: float = 60.0
    home_height: float = 0.25

    def validate(self) -> LiftAxis:
        for name in ("z_travel", "xy_travel", "stiffness", "damping_ratio", "max_force",
                     "home_height"):
            _positive(f"lift.{name}", getattr(self, name))
        if not isinstance(self.xy_enabled, bool):
            raise ValueError(f"lift.xy_enabled: expected true or false, got {self.xy_enabled!r}")
        return self


INTEGRATORS = ("euler", "implicit", "implicitfast", "rk4")


@dataclass(frozen=True)
class SimOptions(_Replace):
    """Simulation settings of the gripper model.

    Attributes:
        timestep: [s]. Default 1 ms (see the model README for the convergence check).
        integrator: MuJoCo integrator, one of euler, implicit, implicitfast, rk4.
        gravity: gravitational acceleration along -z [m/s²].
    """

    timestep: float = 1.0e-3
    integrator: str = "implicitfast"
    gravity: float = 9.81

    def validate(self) -> SimOptions:
        check_between("sim.timestep", self.timestep, 0.0, 0.01, closed=False)
        if self.integrator not in INTEGRATORS:
            raise ValueError(f"sim.integrator: must be one of {', '.join(INTEGRATORS)}, "
                             f"got {self.integrator!r}")
        _nonneg("sim.gravity", self.gravity)
        return self


_SECTIONS: dict[str, type] = {
    "finger": FingerGeometry,
    "material": Material,
    "springs": HingeSprings,
    "cable": Cable,
    "servo": ServoParams,
    "layout": GripperLayout,
    "lift": LiftAxis,
    "sim": SimOptions,
}


@dataclass(frozen=True)
class GripperParams(_Replace):
    """All parameters of a gripper: the single source of truth for every model built.

    Example:
        >>> p = GripperParams.load("my_design.json")          # doctest: +SKIP
        >>> p.replace(layout=p.layout.replace(n_fingers=3)).save("three.json")  # doctest: +SKIP
    """

    finger: FingerGeometry = field(default_factory=FingerGeometry)
    material: Material = field(default_factory=Material)
    springs: HingeSprings = field(default_factory=HingeSprings)
    cable: Cable = field(default_factory=Cable)
    servo: ServoParams = field(default_factory=ServoParams)
    layout: GripperLayout = field(default_factory=GripperLayout)
    lift: LiftAxis = field(default_factory=LiftAxis)
    sim: SimOptions = field(default_factory=SimOptions)

    def validate(self) -> GripperParams:
        """Check every field; return ``self``.

        Raises:
            ValueError: naming the first bad field and the allowed range.
        """
        self.finger.validate()
        self.material.validate()
        self.springs.validate(self.finger.n_hinges)
        self.cable.validate()
        self.servo.validate()
        self.layout.validate()
        self.lift.validate()
        self.sim.validate()
        if self.cable.diameter >= self.finger.hole_diameter:
            raise ValueError(f"cable.diameter: must be smaller than finger.hole_diameter "
                             f"({self.finger.hole_diameter:g} m), got {self.cable.diameter!r}")
        return self

    # -- files -------------------------------------------------------------------------------
    def to_dict(self) -> dict[str, dict[str, Any]]:
        """Plain nested dict (JSON/TOML-ready)."""
        out: dict[str, dict[str, Any]] = {}
        for name in _SECTIONS:
            sec = dataclasses.asdict(getattr(self, name))
            out[name] = {k: list(v) if isinstance(v, tuple) else v for k, v in sec.items()}
        return out

    @classmethod
    def from_dict(cls, data: Any) -> GripperParams:
        """Build and validate from a nested dict; unknown sections or fields are errors.

        Raises:
            ValueError: unknown key, wrong type or out-of-range value.
        """
        if not isinstance(data, dict):
            raise ValueError(f"parameter file: expected a table of sections, got {type(data).__name__}")
        sections = {}
        for name, values in data.items():
            if name not in _SECTIONS:
                raise ValueError(f"{name}: unknown section; allowed: {', '.join(_SECTIONS)}")
            if not isinstance(values, dict):
                raise ValueError(f"{name}: expected a table of fields, got {values!r}")
            klass = _SECTIONS[name]
            known = {f.name for f in dataclasses.fields(klass)}
            kwargs = {}
            for key, value in values.items():
                if key not in known:
                    raise ValueError(f"{name}.{key}: unknown field; allowed: "
                                     f"{', '.join(sorted(known))}")
                if isinstance(value, list):
                    value = tuple(value)
                kwargs[key] = value
            sections[name] = klass(**kwargs)
        return cls(**sections).validate()

    def save(self, path: str | Path) -> Path:
        """Write the parameters as JSON (``.json``) or TOML (``.toml``)."""
        path = Path(path)
        if path.suffix == ".json":
            text = json.dumps(self.to_dict(), indent=2) + "\n"
        elif path.suffix == ".toml":
            text = _to_toml(self.to_dict())
        else:
            raise ValueError(f"parameter file: suffix must be .json or .toml, got {path.name!r}")
        tmp = path.with_name(path.name + ".tmp")
        tmp.write_text(text)
        tmp.replace(path)
        return path

    @classmethod
    def load(cls, path: str | Path) -> GripperParams:
        """Read parameters from a ``.json`` or ``.toml`` file (missing fields take defaults).

        Raises:
            ValueError: unreadable or malformed file, or invalid values.
        """
        path = Path(path)
        try:
            text = path.read_text()
        except OSError as e:
            raise ValueError(f"parameter file: cannot read {str(path)!r}: {e.strerror}") from None
        try:
            if path.suffix == ".toml":
                data = tomllib.loads(text)
            elif path.suffix == ".json":
                data = json.loads(text)
            else:
                raise ValueError(f"parameter file: suffix must be .json or .toml, got {path.name!r}")
        except (json.JSONDecodeError, tomllib.TOMLDecodeError) as e:
            msg = str(e).splitlines()[0]
            raise ValueError(f"parameter file: {path.name} is malformed: {msg}") from None
        return cls.from_dict(data)


def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int | float):
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise TypeError(type(v))


def _to_toml(data: dict[str, dict[str, Any]]) -> str:
    lines = []
    for section, values in data.items():
        lines.append(f"[{section}]")
        lines += [f"{k} = {_toml_value(v)}" for k, v in values.items()]
        lines.append("")
    return "\n".join(lines)
