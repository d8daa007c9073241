"""Parameters of the soft gripper: frozen dataclasses, SI units, ``validate()``, JSON/TOML files.

Every field states its unit. Numbers from paper 000 ("Dynamic Modeling and Grasping Application
of a Cable-Driven Soft Actuator") and paper 001 cite their table; dimensions the papers do not
give (their figures are lost) are chosen here and the reason is written beside them and in
``models/soft_gripper/README.md``.

Example:
    >>> from gripper.core.params import GripperParams
    >>> p = GripperParams()
    >>> p.finger.n_segments, p.layout.n_fingers
    (6, 4)
    >>> p2 = p.replace(finger=p.finger.replace(pitch=0.018)).validate()
"""

from __future__ import annotations

import dataclasses
import functools
import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Self

from gripper.core.arguments import check_instance
from gripper.core.atomic import write_text_atomic
from gripper.core.fields import FieldSpec, Validated, check_fields, field_specs, param
from gripper.core.ranges import (
    BENDING_STIFFNESS,
    CABLE_DIAMETER,
    CABLE_FRICTION,
    CABLE_MODULUS,
    DAMPING_RATIO,
    ELASTOMER_DENSITY,
    ELASTOMER_MODULUS,
    ELASTOMER_STRENGTH,
    ELONGATION,
    FINGER_ELEMENT,
    FINGER_FEATURE,
    FRICTION,
    HINGE_DAMPING,
    HINGE_STIFFNESS,
    KNEE_CURVATURE,
    MOMENT_PER_PASCAL,
    PALM_MASS,
    PALM_SIZE,
    PNEUMATIC_LENGTH,
    PNEUMATIC_MASS,
    PNEUMATIC_SECTION,
    ROOT_STIFFNESS,
    SPEED,
    SPOOL_RADIUS,
    STAGE_FORCE,
    STAGE_STIFFNESS,
    STAGE_TRAVEL,
    YEOH_COEFFICIENT,
)
from gripper.core.resources import DEFAULT_CALIBRATION_DIR, PNEUMATIC_CALIBRATION_DIR
from gripper.core.units import DEG
from gripper.core.user_files import read_user_data
from gripper.datasheets.regulator import REGULATOR_PRESETS, RegulatorDatasheet, regulator_datasheet
from gripper.datasheets.servo import SERVO_PRESETS, ServoDatasheet, servo_datasheet

# paper 000, Table 2: torsion spring stiffness 1.9e-3 N·m/deg = 0.1089 N·m/rad, as printed. The
# unit is suspect (see docs/consistency.md): read per radian it is 1.9e-3 N·m/rad.
PAPER_HINGE_STIFFNESS = 1.9e-3 / DEG
PAPER_HINGE_STIFFNESS_PER_RAD_READING = 1.9e-3
# The committed calibration of the default design (``gripper calibrate --write-default``): the
# default hinge springs are its fitted values. A test fails when it is stale.
DEFAULT_CALIBRATION_FILE = DEFAULT_CALIBRATION_DIR / "calibration.json"
# How a closed cut resists further closing (HingeSprings.closure).
CLOSURE_MODELS = ("teeth", "stiffness", "rigid")
# Named spring sets of the command line's --springs (HingeSprings.paper's readings).
SPRING_SETS = ("calibrated", "paper", "paper_per_radian")
# Tip element's inertia about its proximal hinge [kg·m²] (default design: 16x16x18 mm of
# 1120 kg/m³ silicone, less its cuts, ~3.6 g at ~13 mm), for HingeSprings.paper's damping.
TIP_ELEMENT_INERTIA = 8.3e-7


def _spring(name: str):
    return lambda: committed_springs()[name]


@functools.cache
def committed_springs() -> dict[str, tuple[float, ...]]:
    """``stiffness``, ``damping`` and ``rest_angle_deg`` fitted in :data:`DEFAULT_CALIBRATION_FILE`:
    the defaults of :class:`HingeSprings`.

    Read once, when first needed (not at import), with no checks beyond shape (the schema and the design hash are
    checked by :mod:`gripper.calibration.calfile` and by the staleness test).
    """
    try:
        fitted = json.loads(DEFAULT_CALIBRATION_FILE.read_text())["fitted"]
        out = tuple(tuple(float(v) for v in fitted[key]) for key in
                    ("stiffness_Nm_per_rad", "damping_Nms_per_rad", "rest_angle_deg"))
    except (OSError, KeyError, TypeError, ValueError) as e:
        raise RuntimeError(f"gripper: the default design's committed calibration "
                          f"{DEFAULT_CALIBRATION_FILE} is missing or malformed ({e}); "
                          f"regenerate it with 'gripper calibrate --write-default'") from None
    return dict(zip(("stiffness", "damping", "rest_angle_deg"), out, strict=True))

# The committed calibration of the default pneumatic finger (``gripper calibrate --reference
# actuator --write-default``): paper 001's actuator in finite elements, fitted. Its ``design``
# block is the actuator's shape as the finger's collision body takes it, and ``fitted`` the
# springs and the pressure's moment (per unit length: the finger's segment count is free).
PNEUMATIC_CALIBRATION_FILE = PNEUMATIC_CALIBRATION_DIR / "calibration.json"
# The drives' names (``actuation.kind``): the two shipped, and any a user registers with
# gripper.drives.register_drive (a live list: validation and help read it as it is).
ACTUATIONS = ["cable", "pneumatic"]


@functools.cache
def committed_pneumatic() -> dict[str, float]:
    """The committed pneumatic calibration's design and fitted values: the defaults of
    :class:`PneumaticFinger` (read once, when first needed)."""
    try:
        data = json.loads(PNEUMATIC_CALIBRATION_FILE.read_text())
        return {k: float(v) for k, v in {**data["design"], **data["fitted"]}.items()}
    except (OSError, KeyError, TypeError, ValueError, AttributeError) as e:
        raise RuntimeError(f"gripper: the pneumatic finger's committed calibration {PNEUMATIC_CALIBRATION_FILE} is "
                          f"missing or malformed ({e}); regenerate it with "
                          f"'gripper calibrate --reference actuator --write-default'") from None




# The silicone wall left each side of the cable hole at a tapered tip [m] (assumed: 1 mm, a
# wall a cast mould fills reliably; the anchor's pull-out is not modelled).
TIP_WALL = 0.001


@dataclass(frozen=True)
class FingerGeometry(Validated):
    """Geometry of one finger: a silicone bar cut by triangular notches into elements.

    Finger frame: x along the finger from the palm to the tip, z from the back (bridge side,
    z = 0) to the grasping face (z = ``height``), y across. Cuts open on the grasping face;
    the cable runs through holes above the bridge, so pulling it closes the cuts and curls the
    finger towards its grasping face. Each field's unit, range and source are in its metadata
    (the model README's parameter table lists them).

    Attributes:
        n_segments: number of elements, the base element B1 fixed to the palm included.
        pitch: element length along the finger, cut centre to cut centre.
        width: element width across the finger (y).
        height: element height from back to grasping face (z).
        cut_angle_deg: opening angle of each triangular cut. A hinge stops where its cut closes
            (:attr:`closure_angle_deg`).
        bridge_thickness: silicone left under each cut (the hinge's bridge).
        hole_height: height of the cable-hole axis above the back face.
        hole_diameter: diameter of the cable holes.
        extension_limit_deg: how far a hinge may bend backwards (opening the cut).
        tip_taper: the tip element's width at its distal end over ``width``: 1 is the square tip
            of paper 000's photograph; below 1 the tip element narrows linearly along its length
            (a tapered fingertip, as soft grippers give their tips to reach between neighbours
            and pick small parts). It stops at ``hole_diameter`` plus a 1 mm wall on each side,
            round the cable's anchor.
    """

    SECTION = "finger"

    n_segments: int = param(6, "-", ge=2, le=64, integer=True,
                            source="paper 000 §III: six elements B1..B6, five spring hinges")
    pitch: float = param(0.016, "m", within=FINGER_ELEMENT,
                         source="assumed: 96 mm fingers, about the paper's photographed fingers")
    width: float = param(0.016, "m", within=FINGER_ELEMENT, source="assumed")
    height: float = param(0.018, "m", within=FINGER_ELEMENT,
                          source="assumed: room for the bridge, a 6 mm hole and 3 mm of wall")
    cut_angle_deg: float = param(45.0, "deg", gt=0, lt=90, source="paper 000 §II: 45°")
    bridge_thickness: float = param(
        0.0019, "m", within=FINGER_FEATURE, source="root-find: the bridge at which the converged continuum body has "
        "Table 2's spring read per radian (docs/consistency.md)")
    hole_height: float = param(0.012, "m", within=FINGER_FEATURE,
                               source="assumed: 10.1 mm above the bridge (brief: 8-10 mm), 11.05 mm lever arm")
    hole_diameter: float = param(0.006, "m", within=FINGER_FEATURE, source="paper 000 §II: 6 mm")
    extension_limit_deg: float = param(5.0, "deg", ge=0, le=90,
                                       source="assumed: the bridge and closed back face resist extension")
    tip_taper: float = param(1.0, "-", gt=0, le=1,
                             source="chosen by the gripping-range study (docs/envelope.md); 1 is the square tip of "
                             "paper 000's photograph")

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

    def check(self) -> None:
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
        least = (self.hole_diameter + 2.0 * TIP_WALL) / self.width
        if self.tip_taper < least:
            raise ValueError(
                f"finger.tip_taper: the tip must keep the cable hole and a {TIP_WALL * 1e3:g} mm wall on each side, "
                f"so at least (hole_diameter + {2e3 * TIP_WALL:g} mm) / width = {least:.3g}, got {self.tip_taper!r}")

    @property
    def tip_width(self) -> float:
        """The tip element's width at its distal end [m]."""
        return self.tip_taper * self.width


# RTV 230 silicone's Yeoh coefficients C10, C20, C30 [Pa]: paper 001 §2.3 Step 2 ("C1 = 0.11596,
# C2 = 0.0168, C3 = -0.000319", no unit given; MPa, the unit of the paper's other moduli, as Abaqus
# in mm, N and MPa takes them). The one home of these numbers: the finger's material, paper 001's
# actuator (gripper.references.pneumatic_params) and the tube check read them from here.
RTV230_YEOH = (0.11596e6, 0.0168e6, -0.000319e6)
RTV230_YEOH_SOURCE = "paper 001 §2.3 Step 2 (RTV 230): C1 = 0.11596, C2 = 0.0168, C3 = -0.000319 MPa"


@dataclass(frozen=True)
class Material(Validated):
    """Silicone of the finger body (paper 000 Tables 1-2, paper 001 §2.3).

    Attributes:
        density: mass density.
        youngs_modulus: small-strain Young's modulus.
        poisson_ratio: Poisson's ratio.
        shore_a: hardness.
        tensile_strength: stress at break.
        elongation_at_break: strain at break.
        yeoh_c10, yeoh_c20, yeoh_c30: Yeoh coefficients of RTV 230 silicone.
        friction: sliding friction coefficient of the silicone pads.
    """

    SECTION = "material"

    density: float = param(1120.0, "kg/m³", within=ELASTOMER_DENSITY, source="paper 000 Table 1: 1.12 g/cm³")
    youngs_modulus: float = param(0.44e6, "Pa", within=ELASTOMER_MODULUS, source="paper 000 Table 2: 0.44 MPa")
    poisson_ratio: float = param(0.48, "-", gt=-1, lt=0.5, source="paper 000 Table 2: 0.48")
    shore_a: float = param(20.0, "Shore A", ge=0, le=100, source="paper 000 Table 1: 20 ± 2 A")
    tensile_strength: float = param(4.0e6, "Pa", within=ELASTOMER_STRENGTH, source="paper 000 Table 1: 4 MPa")
    elongation_at_break: float = param(5.0, "-", within=ELONGATION, source="paper 000 Table 1: >= 500 %")
    yeoh_c10: float = param(RTV230_YEOH[0], "Pa", within=YEOH_COEFFICIENT, source=RTV230_YEOH_SOURCE)
    yeoh_c20: float = param(RTV230_YEOH[1], "Pa", within=YEOH_COEFFICIENT, source=RTV230_YEOH_SOURCE)
    yeoh_c30: float = param(RTV230_YEOH[2], "Pa", within=YEOH_COEFFICIENT, source=RTV230_YEOH_SOURCE)
    friction: float = param(1.0, "-", within=FRICTION,
                            source="assumed: soft silicone on dry plastic, paper, latex is 0.8-1.5")


@dataclass(frozen=True)
class HingeSprings(Validated):
    """Torsion springs at the bridges, one value per hinge or one value for all.

    The defaults are the committed calibration of the default design
    (:data:`DEFAULT_CALIBRATION_FILE`: the hinge finger fitted to the converged continuum
    reference, see ``docs/calibration.md``). :meth:`paper` gives paper 000's Table 2 spring
    instead, for comparison. Paper 000's own damping ("10 N·m·s/deg") is implausible and is not
    used (``docs/calibration.md``).

    Attributes:
        stiffness: per-hinge stiffness.
        damping: per-hinge damping, fitted to the reference's transient.
        rest_angle_deg: spring rest angle of each hinge; 0 = moulded straight.
        closure: how a hinge resists closing past its closure angle, where the faces of its
            cut meet (:mod:`gripper.drives.cable.closure`; the model README gives the figures):

            - ``"teeth"`` (default): the silicone teeth on either side of the cut are
              squeezed, a neo-Hookean solid of the finger's Young's modulus, stiffening as
              their thin tips are squashed. Independent of the time step, so grasp results
              are too.
            - ``"stiffness"``: a linear compliant stop of ``closure_stiffness``.
            - ``"rigid"``: a hard stop as stiff as the time step allows: the idealisation of
              paper 000's hinge chain, whose overrun grows as the step squared.
        closure_stiffness: rotational stiffness of a closed cut, used only when
            ``closure == "stiffness"``; set it from a measurement.
    """

    SECTION = "springs"

    stiffness: tuple[float, ...] = param(None, "N·m/rad", factory=_spring("stiffness"), within=HINGE_STIFFNESS,
                                         numbers=True,
                                         source="fitted: the committed calibration")
    damping: tuple[float, ...] = param(None, "N·m·s/rad", factory=_spring("damping"), within=HINGE_DAMPING,
                                       numbers=True,
                                       source="fitted: the committed calibration")
    rest_angle_deg: tuple[float, ...] = param(None, "deg", factory=_spring("rest_angle_deg"), gt=-90, lt=90,
                                              numbers=True, source="fitted: the committed calibration")
    closure: str = param("teeth", "-", choices=CLOSURE_MODELS, source="gripper.drives.cable.closure")
    closure_stiffness: float = param(1.0, "N·m/rad", within=HINGE_STIFFNESS,
                                     source="assumed: a placeholder of the teeth estimate's order")

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
            if len(v) not in (1, n_hinges) and v == committed_springs()[name]:
                v = (sum(v) / len(v),)
            out.append(v * n_hinges if len(v) == 1 else v)
        return tuple(out)

    def validate(self, n_hinges: int | None = None) -> HingeSprings:
        """Check every field; with ``n_hinges``, also that each list has 1 or ``n_hinges``
        values (the committed calibration's lists are broadcast, see :meth:`per_hinge`)."""
        check_fields(self, self.SECTION)
        for name in ("stiffness", "damping", "rest_angle_deg"):
            values = getattr(self, name)
            if (n_hinges is not None and len(values) not in (1, n_hinges)
                    and tuple(values) != committed_springs()[name]):
                raise ValueError(f"springs.{name}: expected 1 or {n_hinges} values (one per "
                                 f"hinge), got {len(values)}")
        return self


@dataclass(frozen=True)
class Cable(Validated):
    """The driving cable (paper 000 §II: polyethylene fibre, fixed at the tip).

    Attributes:
        diameter: cable diameter.
        youngs_modulus: effective axial modulus of the braided fibre.
        friction_loss: dry friction of the cable in its holes.
    """

    SECTION = "cable"

    diameter: float = param(0.5e-3, "m", within=CABLE_DIAMETER, source="paper 000 §II: Ø 0.5 mm")
    youngs_modulus: float = param(50e9, "Pa", within=CABLE_MODULUS,
                                  source="assumed: UHMW-PE fibre is 100-120 GPa, a braid about half")
    friction_loss: float = param(0.0, "N", within=CABLE_FRICTION, source="assumed: a 0.5 mm cable loose in 6 mm holes")

    @property
    def axial_stiffness(self) -> float:
        """EA [N]: force per unit strain of the cable."""
        return self.youngs_modulus * math.pi * (0.5 * self.diameter) ** 2


@dataclass(frozen=True)
class ServoParams(Validated):
    """The servo that reels each cable in: a datasheet preset, a spool and controller tuning.

    Attributes:
        preset: key of :data:`gripper.datasheets.servo.SERVO_PRESETS`.
        spool_radius: radius the cable winds on.
        saturation_error_deg: position error at which the PD asks for the stall torque.
        damping_ratio: damping ratio of the position loop on the rotor inertia.
        contraction_speed: default cable contraction speed, the slew limit of the position
            set-point; 0 means the servo's no-load speed times the spool radius.
    """

    SECTION = "servo"

    preset: str = param("hobby_6v", "-", choices=tuple(SERVO_PRESETS),
                        source="the datasheets in gripper.datasheets.servo")
    spool_radius: float = param(0.020, "m", within=SPOOL_RADIUS,
                                source="assumed: 180° of travel reels in 63 mm, enough to close every cut")
    saturation_error_deg: float = param(0.6, "deg", gt=0, lt=90,
                                        source="assumed: about a hobby servo's dead band")
    damping_ratio: float = param(1.0, "-", within=DAMPING_RATIO, source="assumed: a critically damped position loop")
    contraction_speed: float = param(0.0, "m/s", within=SPEED,
                                     source="0: the servo's no-load speed times the spool radius")

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


@dataclass(frozen=True)
class GripperLayout(Validated):
    """How the fingers sit on the palm.

    Attributes:
        n_fingers: number of fingers, evenly spaced around the palm axis.
        palm_radius: distance from the palm axis to each finger's grasping face.
        palm_thickness: thickness of the palm plate.
        mount_tilt_deg: finger splay at the mount, positive tilting the tips outwards.
        palm_mass: mass of palm, servos and cable routing, carried by the lift.
    """

    SECTION = "layout"

    n_fingers: int = param(4, "-", ge=1, le=12, integer=True, source="paper 000 §V: four fingers")
    palm_radius: float = param(0.025, "m", within=PALM_SIZE,
                               source="chosen by the gripping-range study (gripper/data/studies/gripping_range.toml, "
                               "docs/envelope.md): the widest range that keeps the five default objects; 40 mm "
                               "until 0.20.0 (assumed)")
    palm_thickness: float = param(0.020, "m", within=PALM_SIZE, source="assumed: a 3D-printed hub")
    mount_tilt_deg: float = param(15.0, "deg", ge=-45, le=45,
                                  source="chosen by the gripping-range study (docs/envelope.md): splayed tips open "
                                  "wide over a small palm; 0 until 0.20.0 (assumed: straight, as in the paper's "
                                  "photograph)")
    palm_mass: float = param(0.35, "kg", within=PALM_MASS, source="assumed: four 55 g servos and a printed hub")


@dataclass(frozen=True)
class LiftAxis(Validated):
    """The stage that carries the palm: a vertical lift axis, optional x/y axes.

    Each axis is a position-controlled linear stage (MuJoCo ``position`` actuator).

    Attributes:
        z_travel: lift travel below and above the home height.
        xy_enabled: add horizontal x and y axes (needed to shake the object).
        xy_travel: horizontal travel either side.
        stiffness: position gain of each axis.
        damping_ratio: damping ratio of each axis with the palm mass.
        max_force: force limit of each axis.
        home_height: palm-face height above the floor at zero lift.
        yaw_enabled: add the wrist: a rotary axis turning the palm about its own (vertical) axis,
            so that the grasp can meet a long part across its width.
        yaw_stiffness: position gain of the wrist.
        yaw_max_torque: torque limit of the wrist.
    """

    SECTION = "lift"

    z_travel: float = param(0.25, "m", within=STAGE_TRAVEL, source="assumed: ±0.25 m")
    xy_enabled: bool = param(True, "-", source="needed to shake the object")
    xy_travel: float = param(0.05, "m", within=STAGE_TRAVEL, source="assumed: ±0.05 m")
    stiffness: float = param(4000.0, "N/m", within=STAGE_STIFFNESS, source="assumed: 1 mm of error per 4 N")
    damping_ratio: float = param(1.0, "-", within=DAMPING_RATIO, source="assumed: critically damped with the palm mass")
    max_force: float = param(60.0, "N", within=STAGE_FORCE, source="assumed: a small linear stage")
    home_height: float = param(0.25, "m", within=STAGE_TRAVEL,
                               source="assumed: 96 mm fingers clear a 100 mm object with room to approach")
    yaw_enabled: bool = param(True, "-", source="the grasp turns the palm to the part's footprint (0.21.0)")
    yaw_stiffness: float = param(10.0, "N·m/rad", gt=0, le=1e4,
                                 source="assumed: the linear axes' bandwidth (about 100 rad/s) on the palm's "
                                 "1e-3 kg·m² about its axis")
    yaw_max_torque: float = param(2.0, "N·m", gt=0, le=1e3, source="assumed: a small rotary stage")


@dataclass(frozen=True)
class Actuation(Validated):
    """Which finger the gripper has.

    Attributes:
        kind: ``"cable"``: paper 000's cut silicone finger bent by a cable a servo reels in (the
            ``finger``, ``springs``, ``cable`` and ``servo`` sections); ``"pneumatic"``: paper
            001's fibre-reinforced actuator bent by its chamber pressure, fed by a proportional
            regulator (the ``pneumatic`` section).
    """

    SECTION = "actuation"

    kind: str = param("cable", "-", choices=ACTUATIONS, source="the two seed papers' fingers")


_PN_CAL = "fitted: the committed pneumatic calibration"


def _pneumatic(name: str):
    return lambda: committed_pneumatic()[name]
# Paper 001's actuator pressure range, 0-250 kPa (§2.3 Step 3): the calibration's range, the
# regulator's default set-point limit, the finite-element model's load and the grip set-point.
PAPER_001_PRESSURE_MAX = 250e3  # Pa
_PN_SHAPE = "paper 001's actuator (gripper.references.pneumatic_params), as the committed calibration records it"


@dataclass(frozen=True)
class PneumaticFinger(Validated):
    """The pneumatic finger: paper 001's actuator as a chain of rigid segments on hinges at its
    neutral layer, bent by its chamber pressure (``gripper.drives.pneumatic.chamber``).

    Finger frame as the cable finger's: x from the palm to the tip, z from the back (the
    actuator's round top, z = 0) to the grasping face (the fabric side, z = ``height``). The hinges
    lie on the neutral layer's mid-plane, so the fabric's length never changes (the layer does
    not stretch). Springs and the pressure's moment are stored per unit length, as a continuum's
    (bending stiffness, curvature), so a finger of any segment count has the calibrated bend:
    hinge stiffness = EI / pitch, knee angle = knee curvature x pitch (``pitch``: the hinge
    spacing).

    Attributes:
        n_segments: rigid segments, the first on the root hinge at the clamp (n - 1 inner hinges).
        length, width, height: the actuator's size.
        neutral_height: the neutral layer's mid-plane above the grasping face.
        mass: the actuator's mass.
        bending_stiffness: EI of the soft range.
        stiffening: EI added past the knee (the silicone and fibres stiffening as it bends).
        root_stiffness: the root hinge's spring at the clamp (the clamped end's compliance,
            lumped; not per length).
        knee_curvature: the curvature at which the stiffening starts.
        moment_per_pascal: the chamber pressure's bending moment per pascal, the same at every
            hinge (a uniform section).
        damping_ratio: each hinge's damping, as a ratio of critical for its spring on the tip
            segment's inertia.
        regulator: key of :data:`gripper.datasheets.regulator.REGULATOR_PRESETS`.
        pressure_max: highest chamber pressure the regulator is set to.
    """

    SECTION = "pneumatic"

    n_segments: int = param(8, "-", ge=3, le=64, integer=True,
                            source="assumed: seven hinges 20 mm apart, about the cable finger's 16 mm elements")
    length: float = param(None, "m", factory=_pneumatic("length"), within=PNEUMATIC_LENGTH, source=_PN_SHAPE)
    width: float = param(None, "m", factory=_pneumatic("width"), within=PNEUMATIC_SECTION, source=_PN_SHAPE)
    height: float = param(None, "m", factory=_pneumatic("height"), within=PNEUMATIC_SECTION, source=_PN_SHAPE)
    neutral_height: float = param(None, "m", factory=_pneumatic("neutral_height"), within=PNEUMATIC_SECTION,
                                  source=_PN_SHAPE)
    mass: float = param(None, "kg", factory=_pneumatic("mass"), within=PNEUMATIC_MASS, source=_PN_SHAPE)
    bending_stiffness: float = param(None, "N·m²", factory=_pneumatic("bending_stiffness"), within=BENDING_STIFFNESS,
                                     source=_PN_CAL)
    stiffening: float = param(None, "N·m²", factory=_pneumatic("stiffening"), ge=0, within=BENDING_STIFFNESS,
                              source=_PN_CAL)
    root_stiffness: float = param(None, "N·m/rad", factory=_pneumatic("root_stiffness"), within=ROOT_STIFFNESS,
                                  source=_PN_CAL)
    knee_curvature: float = param(None, "1/m", factory=_pneumatic("knee_curvature"), within=KNEE_CURVATURE,
                                  source=_PN_CAL)
    moment_per_pascal: float = param(None, "N·m/Pa", factory=_pneumatic("moment_per_pascal"),
                                     within=MOMENT_PER_PASCAL, source=_PN_CAL)
    damping_ratio: float = param(0.5, "-", gt=0, le=10,
                                 source="assumed: paper 000 Table 2's modal damping ratio of its silicone finger")
    regulator: str = param("smc_itv0030", "-", choices=tuple(REGULATOR_PRESETS),
                           source="the datasheets in gripper.datasheets.regulator")
    pressure_max: float = param(PAPER_001_PRESSURE_MAX, "Pa", gt=0, le=1e6,
                                source="paper 001 §2.3 Step 3: 0-250 kPa, the calibration's range")

    @property
    def datasheet(self) -> RegulatorDatasheet:
        return regulator_datasheet(self.regulator)

    @property
    def pitch(self) -> float:
        """Hinge spacing [m]: the length over the hinge count (the base and tip segments are half
        a pitch long, :mod:`gripper.drives.pneumatic.chamber`)."""
        return self.length / self.n_hinges

    @property
    def n_hinges(self) -> int:
        """Inner hinges, between segments (the root hinge at the clamp besides) [-]."""
        return self.n_segments - 1

    @property
    def hinge_z(self) -> float:
        """Height of the hinge axes in the finger frame: the neutral layer's mid-plane [m]."""
        return self.height - self.neutral_height

    @property
    def hinge_stiffness(self) -> float:
        """Each hinge's spring, EI over the segment length [N·m/rad]."""
        return self.bending_stiffness / self.pitch

    @property
    def command_max(self) -> float:
        """Highest set-point [Pa]: ``pressure_max`` within the regulator's range."""
        return min(self.pressure_max, self.datasheet.pressure_max)

    def check(self) -> None:
        if self.neutral_height >= self.height:
            raise ValueError(f"pneumatic.neutral_height: must be < pneumatic.height ({self.height:g} m), "
                             f"got {self.neutral_height!r}")
        if self.pressure_max > self.datasheet.pressure_max:
            raise ValueError(f"pneumatic.pressure_max: must be at most the regulator's "
                             f"{self.datasheet.pressure_max:g} Pa, got {self.pressure_max!r}")


CONTACT_MODELS = ("pads", "solver")


@dataclass(frozen=True)
class PadContact(Validated):
    """How the fingers meet a part: the silicone's contact law and the fingers' surface shape
    (``gripper.parts.pads``; the derivation and its checks: ``docs/contact.md``).

    ``model = "pads"`` (the default): each finger element (cable) or segment (pneumatic) carries
    its collision surface on a pad body that slides into it along the grasping face's normal,
    against springs in N/m that follow Hertz's law for the silicone (E* = E / (1 - nu^2): paper
    000 Table 2 for the cable finger, 6 C10 of paper 001's Yeoh fit with nu = 0.5 for the
    pneumatic one), and the part's contact is made near-rigid, so the force-indentation is the
    material's whatever the part weighs. ``"solver"``: the earlier contact, MuJoCo's default
    softness on the element itself (its stiffness scales with the contact's effective mass),
    kept for comparison.

    Attributes:
        model: ``"pads"`` or ``"solver"``.
        pad_radius: the pad's curvature radius in Hertz's law.
        edge_radius: rounding of the cable finger elements' edges.
        pneumatic_edge_radius: rounding of the pneumatic segments' grasping-face edges.
        damping_ratio: the pad's damping, a ratio of critical for its 1 N tangent stiffness on
            the element's mass.
        fit_force_max: the highest pad force the piecewise-linear spring follows Hertz to.
    """

    SECTION = "contact"

    model: str = param("pads", "-", choices=CONTACT_MODELS,
                       source="issue 44: the contact law from the finger's material")
    pad_radius: float = param(0.008, "m", gt=0, le=0.1,
                              source="assumed: half the 16 mm finger width, a pad face rounded across the finger")
    edge_radius: float = param(0.0015, "m", ge=0, le=0.004,
                               source="assumed: a molded silicone edge; at most what the middle element's "
                                      "2.7 mm grasping face between two cuts can hold")
    pneumatic_edge_radius: float = param(0.002, "m", ge=0, le=0.005,
                                         source="assumed: a molded edge, about the 2 mm wall of paper 001 §2.1")
    damping_ratio: float = param(0.5, "-", gt=0, le=10,
                                 source="paper 000 Table 2's modal damping ratio of the silicone finger")
    fit_force_max: float = param(15.0, "N", gt=0.1, le=1000,
                                 source="assumed: three times the 5 N set-point's blocked-tip force")


INTEGRATORS = ("euler", "implicit", "implicitfast", "rk4")


@dataclass(frozen=True)
class SimOptions(Validated):
    """Simulation settings of the gripper model (grasp trials replace the step with
    :data:`gripper.core.timesteps.TRIAL_TIMESTEP`).

    Attributes:
        timestep: physics step.
        integrator: MuJoCo integrator (the pneumatic gripper always takes MuJoCo's discrete
            integrator, implicit in its stiff hinge springs:
            ``gripper.drives.pneumatic.drive.PneumaticDrive.configure``).
        gravity: gravitational acceleration along -z.
    """

    SECTION = "sim"

    # 10 µs at the least: a finer step is never needed (paper 000's bending test runs at 5e-4 s),
    # and 1e-12 s would turn a 2 s check into 2e12 steps
    timestep: float = param(1.0e-3, "s", ge=1e-5, lt=0.01, source="the model README's convergence check")
    integrator: str = param("implicitfast", "-", choices=INTEGRATORS, source="MuJoCo's integrators")
    gravity: float = param(9.81, "m/s²", ge=0, le=100, source="standard gravity; at most ten g")


_SECTIONS: dict[str, type] = {
    "finger": FingerGeometry,
    "material": Material,
    "springs": HingeSprings,
    "cable": Cable,
    "servo": ServoParams,
    "layout": GripperLayout,
    "lift": LiftAxis,
    "sim": SimOptions,
    "actuation": Actuation,
    "pneumatic": PneumaticFinger,
    "contact": PadContact,
}


@dataclass(frozen=True)
class GripperParams(Validated):
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
    actuation: Actuation = field(default_factory=Actuation)
    pneumatic: PneumaticFinger = field(default_factory=PneumaticFinger)
    contact: PadContact = field(default_factory=PadContact)

    def validate(self) -> Self:
        """Check every section (each registered in :data:`_SECTIONS`, so none can be skipped),
        then the rules across sections; return ``self``.

        Raises:
            ValueError: naming the first bad field and the allowed range.
            TypeError: a section field that is not registered (a new section must be added to
                :data:`_SECTIONS`, whose entries all validate themselves).
        """
        unregistered = [f.name for f in dataclasses.fields(self) if f.name not in _SECTIONS]
        if unregistered:
            raise TypeError(f"{type(self).__name__}: section(s) {', '.join(unregistered)} not in "
                            "gripper.core.params._SECTIONS, so validate() would skip them")
        for name in _SECTIONS:
            section = getattr(self, name)
            if isinstance(section, HingeSprings):
                section.validate(self.finger.n_hinges)
            else:
                section.validate()
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
        return write_text_atomic(path, text)

    @classmethod
    def load(cls, path: str | Path) -> GripperParams:
        """Read parameters from a ``.json`` or ``.toml`` file (missing fields take defaults).

        Raises:
            ValueError: unreadable or malformed file, or invalid values.
            TypeError: ``path`` is not a path.
        """
        path = Path(check_instance("path", path, (str, Path), optional=False))
        data = read_user_data(path, "parameter file")
        if not data:
            raise ValueError(f"parameter file: {path} sets no parameter; give the fields to change "
                             "('gripper params --out FILE' writes them all)")
        try:
            return cls.from_dict(data)
        except ValueError as e:
            raise ValueError(f"parameter file {path.name}: {e}") from None


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


def parameter_rows(params: GripperParams | None = None) -> list[tuple[str, str, Any, FieldSpec]]:
    """(section, field, value, spec) of every parameter, in file order: what the model README's
    table and ``gripper params --help`` list."""
    p = params or GripperParams()
    return [(section, name, getattr(getattr(p, section), name), spec)
            for section, klass in _SECTIONS.items() for name, spec in field_specs(klass).items()]


def parameter_help(width: int = 80) -> str:
    """The parameter fields as command-line help text: name, default, unit, allowed, source,
    each wrapped to ``width`` columns."""
    import textwrap

    lines = []
    for section, name, value, spec in parameter_rows():
        shown = list(value) if isinstance(value, tuple) else value
        if isinstance(shown, list) and len(shown) > 1:
            shown = "[" + ", ".join(f"{v:.3g}" for v in shown) + "]"
        text = f"{section}.{name} = {shown} [{spec.unit}], {spec.allowed()}; {spec.source}"
        lines += textwrap.wrap(text, width, initial_indent="  ", subsequent_indent="      ",
                               break_on_hyphens=False)
    return "\n".join(lines)
