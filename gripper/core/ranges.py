"""Physical ranges: the bounds every design and object field is checked against, each with its
reason, in one place (SI units).

They are not the design's limits (a default sits well inside); they keep out what no gripper
of this kind meets and what would reach MuJoCo's compiler as nonsense: a 1000 t block, a 1 µg
part, a friction of 10⁶, a balloon of 1 mPa, parts a few micrometres in size. A field's own
range (:func:`gripper.core.fields.param`'s ``within``) is checked before any run folder is made.

Example:
    >>> from gripper.core.ranges import OBJECT_MASS
    >>> OBJECT_MASS.text()
    '[0.0001, 10] kg'
    >>> OBJECT_MASS.contains(2000.0)
    False
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

# Seeds: integers in [0, 2³² − 1], the range NumPy's and Python's seeding share; trial and point
# indices below 2³¹ (an int32 in a MuJoCo or NumPy array).
SEED_MAX = 2**32 - 1
INDEX_MAX = 2**31 - 1
# Trials in one run (a bench, an envelope, a study): a day of block trials on one core.
TRIALS_MAX = 100_000


@dataclass(frozen=True)
class Range:
    """Bounds ``lo`` < (or <= with ``lo_closed``) value <= ``hi`` [``unit``], and why."""

    lo: float
    hi: float
    unit: str
    reason: str
    lo_closed: bool = False

    def text(self) -> str:
        return f"{'[' if self.lo_closed else '('}{self.lo:g}, {self.hi:g}] {self.unit}".rstrip()

    def contains(self, v: float) -> bool:
        return (v >= self.lo if self.lo_closed else v > self.lo) and v <= self.hi

    def check(self, name: str, value: Any) -> float:
        """``value`` as a float, or ValueError naming ``name``, the range and its reason."""
        if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value) \
                or not self.contains(value):
            raise ValueError(f"{name}: must be in {self.text()} ({self.reason}), got {value!r}")
        return float(value)


# --- objects (gripper.objects.grasp_object) ---
OBJECT_MASS = Range(1e-4, 10.0, "kg", "from a paper clip's fraction to beyond any soft gripper's payload: the lift "
                    "axis's 60 N holds 6 kg", lo_closed=True)
OBJECT_HALF_EXTENT = Range(5e-4, 0.5, "m", "a part of 1 mm, below which its contact is thinner than the pads' "
                           "margins, to a metre across")
OBJECT_DENSITY = Range(10.0, 25_000.0, "kg/m³", "expanded polystyrene (about 15) to osmium (22 590), the densest "
                       "solid")
FRICTION = Range(0.01, 5.0, "-", "PTFE on steel (0.04) to the stickiest elastomer pairs (about 3); "
                 "above 5 a coefficient describes glue, not friction")
CLOSE_COMMAND = Range(0.0, 10.0, "rad", "the servo's spool angle: full closing is 3 rad")
OBJECT_MODULUS = Range(1e3, 3e11, "Pa", "a 1 kPa gel to steel (210 GPa)")
FILM_THICKNESS = Range(5e-6, 5e-3, "m", "5 µm cling film to 5 mm board")
YIELD_STRAIN = Range(0.0, 0.1, "-", "paper and board yield at 0.2-2 % strain; 10 % bounds any card")
DAMAGE_LIMIT = {"contact_force": Range(0.0, 1e4, "N", "up to 10 kN, a thousand times the grip"),
                "strain": Range(0.0, 10.0, "-", "up to stretch 11, past latex's break (7-8)"),
                "dent": Range(0.0, 0.1, "m", "up to 10 cm, the size of the largest box")}

# --- the finger, the gripper and its stage (gripper.core.params) ---
FINGER_ELEMENT = Range(1e-3, 0.1, "m", "a finger element from 1 mm, the finest a cast mould holds, to 10 cm, a "
                       "hand-sized finger's whole length")
FINGER_FEATURE = Range(1e-4, 0.05, "m", "a bridge or cable hole from 0.1 mm to 5 cm")
ELASTOMER_DENSITY = Range(100.0, 5000.0, "kg/m³", "foamed silicone (about 300) to a metal-filled compound")
ELASTOMER_MODULUS = Range(1e3, 1e10, "Pa", "a 1 kPa gel to a 10 GPa rigid polymer")
ELASTOMER_STRENGTH = Range(1e3, 1e9, "Pa", "1 kPa to 1 GPa, past any elastomer's tensile strength")
ELONGATION = Range(0.0, 20.0, "-", "elastomers break below 2000 % elongation")
YEOH_COEFFICIENT = Range(-1e9, 1e9, "Pa", "elastomers' Yeoh coefficients are kPa to MPa; ±1 GPa bounds them",
                         lo_closed=True)
HINGE_STIFFNESS = Range(0.0, 10.0, "N·m/rad", "5000 times the calibrated hinge (1.8e-3)")
HINGE_DAMPING = Range(0.0, 1.0, "N·m·s/rad", "1000 times the calibrated hinge's", lo_closed=True)
CABLE_DIAMETER = Range(0.0, 5e-3, "m", "the cable runs through 6 mm holes")
CABLE_MODULUS = Range(1e6, 1.2e12, "Pa", "a rubber cord to diamond")
CABLE_FRICTION = Range(0.0, 100.0, "N", "below the servo's pull (53.9 N)", lo_closed=True)
SPOOL_RADIUS = Range(0.0, 0.1, "m", "a servo's spool or horn")
DAMPING_RATIO = Range(0.0, 10.0, "-", "ten times critical damping")
SPEED = Range(0.0, 10.0, "m/s", "a cable or stage faster than 10 m/s is a different machine", lo_closed=True)
PALM_SIZE = Range(1e-3, 0.5, "m", "a palm from 1 mm to 0.5 m")
PALM_MASS = Range(1e-3, 20.0, "kg", "a printed hub to an industrial gripper's 20 kg")
STAGE_TRAVEL = Range(0.0, 2.0, "m", "a table-top stage to an arm's reach")
STAGE_STIFFNESS = Range(0.0, 1e6, "N/m", "1 mm of error per kN")
STAGE_FORCE = Range(0.0, 1e4, "N", "an industrial arm's 10 kN")
PNEUMATIC_LENGTH = Range(0.0, 1.0, "m", "a finger under a metre")
PNEUMATIC_SECTION = Range(0.0, 0.2, "m", "a finger's section under 20 cm")
PNEUMATIC_MASS = Range(0.0, 1.0, "kg", "a finger under 1 kg")
BENDING_STIFFNESS = Range(0.0, 10.0, "N·m²", "EI of a 20 mm silicone finger is about 1e-3 N·m²; 10 is a steel rod's")
ROOT_STIFFNESS = Range(0.0, 100.0, "N·m/rad", "a finger's root, softer than 100 N·m/rad")
KNEE_CURVATURE = Range(0.0, 1000.0, "1/m", "a 1 mm bend radius", lo_closed=True)
MOMENT_PER_PASCAL = Range(0.0, 1e-3, "N·m/Pa", "a 20 mm chamber gives about 1e-6 N·m/Pa")
