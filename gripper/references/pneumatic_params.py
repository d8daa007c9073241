"""Paper 001's fibre-reinforced pneumatic composite actuator: its design parameters, each with its
source, validated once (SI units).

The actuator (paper 001 §2.1, Fig. 1): a main body of RTV 230 silicone with a half-round air duct
along its length, sealed at both ends; a fabric neutral layer under its flat face, which does not
stretch, so inflation bends the actuator towards it; a reinforcing fibre wound helically around
body and cladding at a small twist angle, which stops the duct from ballooning; and a silicone
cladding over it all. Clamped at one end, the other free; a follower pressure of 0-250 kPa on the
duct's surfaces (§2.3, Step 3).

The paper gives the materials (§2.3, Step 2), the five design parameters with their studied ranges
and recommended values (§2.4, Table 1), the length and the neutral layer's segments (§3, Fig. 17).
Its figures with the cross-section's dimensions are lost; the duct's radius and the body's width
are assumed here, once, with their reasons (``assumed:`` in each field's source).

Example:
    >>> from gripper.references.pneumatic_params import PneumaticActuator
    >>> a = PneumaticActuator().validate()
    >>> round(a.fibre_pitch * 1e3, 2)   # mm between turns of the 4° helix
    3.29
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from gripper.core.fields import Validated, param
from gripper.core.params import PAPER_001_PRESSURE_MAX, RTV230_YEOH, RTV230_YEOH_SOURCE

KPA = 1e3  # Pa
# The built actuator's neutral layer (paper 001 §3, Fig. 17): a1 = a2 = a3 = 40 mm, b1 = 5 mm, b2 = 15 mm
FIG17_SEGMENTS = {"segment_lengths": (0.040, 0.040, 0.040), "segment_gaps": (0.005, 0.015)}


@dataclass(frozen=True)
class PneumaticActuator(Validated):
    """One design of paper 001's actuator. Defaults: the design the paper recommends (Table 1),
    with one neutral layer along the length as in its case studies (``FIG17_SEGMENTS``: the
    segmented layer of the actuator it built, §3)."""

    SECTION = "actuator"

    # geometry [m]
    length: float = param(0.140, "m", gt=0, le=0.5, source="paper 001 §2.4.1 and §3: l = 140 mm")
    duct_radius: float = param(
        0.006, "m", gt=0, le=0.03,
        source="assumed: a 12 mm wide half-round duct, the size of the fibre-reinforced bending actuators "
               "the paper builds on (its refs. 20, 21, Polygerinos et al.); its Fig. 4 dimensions are lost")
    main_body_thickness: float = param(0.002, "m", gt=0, le=0.01,
                                       source="paper 001 §2.4.2, Table 1: 2 mm (studied 0.5-3 mm)")
    cladding_thickness: float = param(0.001, "m", ge=0, le=0.01,
                                      source="paper 001 §2.4.2, Table 1: 1 mm (studied 0-2.5 mm)")
    neutral_thickness: float = param(0.0002, "m", gt=0, le=0.005,
                                     source="paper 001 §2.4.2, Table 1: 0.2 mm (studied 0.1-0.5 mm)")
    fibre_diameter: float = param(0.0005, "m", gt=0, le=0.002,
                                  source="paper 001 §2.4.2, Table 1: 0.5 mm (studied 0.2-0.7 mm)")
    twist_angle_deg: float = param(4.0, "deg", gt=0, lt=45,
                                   source="paper 001 §2.4.2, Table 1: 4° (studied 3-15°), from the hoop direction")
    # the neutral layer's segments along the length, from the clamped end [m]: one over the whole
    # length, as in the case studies; FIG17_SEGMENTS holds the built actuator's three
    segment_lengths: tuple[float, ...] = param((0.140,), "m", gt=0, numbers=True,
                                               source="paper 001 §2.4.2: the case studies' 140 mm actuator, "
                                                      "one neutral layer along it")
    segment_gaps: tuple[float, ...] = param((), "m", ge=0, numbers=True, allow_empty=True,
                                            source="paper 001 §2.4.2: none in the case studies")
    # materials
    yeoh_c10: float = param(RTV230_YEOH[0], "Pa", gt=0, source=RTV230_YEOH_SOURCE)
    yeoh_c20: float = param(RTV230_YEOH[1], "Pa", source=RTV230_YEOH_SOURCE)
    yeoh_c30: float = param(RTV230_YEOH[2], "Pa", source=RTV230_YEOH_SOURCE)
    silicone_density: float = param(1140.0, "kg/m³", gt=0, source="paper 001 §2.3 Step 2: 1140 kg/m³")
    fabric_modulus: float = param(6500e6, "Pa", gt=0, source="paper 001 §2.3 Step 2: 6500 MPa")
    fabric_poisson: float = param(0.2, "-", gt=-1, lt=0.5, source="paper 001 §2.3 Step 2: 0.2")
    fabric_density: float = param(750.0, "kg/m³", gt=0, source="paper 001 §2.3 Step 2: 750 kg/m³")
    fibre_modulus: float = param(31076e6, "Pa", gt=0, source="paper 001 §2.3 Step 2: 31076 MPa")
    fibre_poisson: float = param(0.36, "-", gt=-1, lt=0.5, source="paper 001 §2.3 Step 2: 0.36")
    fibre_density: float = param(1201.0, "kg/m³", gt=0, source="paper 001 §2.3 Step 2: 1201 kg/m³")
    # load
    pressure_max: float = param(PAPER_001_PRESSURE_MAX, "Pa", gt=0, le=1e6, source="paper 001 §2.3 Step 3: 0-250 kPa")

    def check(self) -> None:
        if len(self.segment_gaps) != len(self.segment_lengths) - 1:
            raise ValueError(f"actuator.segment_gaps: one gap between each two of the "
                             f"{len(self.segment_lengths)} segments, got {len(self.segment_gaps)}")
        if self.neutral_span > self.length:
            raise ValueError(f"actuator.segment_lengths: the segments and gaps span {self.neutral_span:.4g} m, "
                             f"more than the length {self.length:g} m")
        if self.fibre_pitch <= self.fibre_diameter:
            raise ValueError(f"actuator.twist_angle_deg: at {self.twist_angle_deg:g}° the helix's turns "
                             f"({self.fibre_pitch * 1e3:.2f} mm apart) overlap the {self.fibre_diameter * 1e3:g} mm "
                             "fibre")

    @property
    def outer_radius(self) -> float:
        """Radius of the body's round face, duct plus wall [m]."""
        return self.duct_radius + self.main_body_thickness

    @property
    def winding_radius(self) -> float:
        """Radius at which the fibre is wound, on the body's round face [m]."""
        return self.outer_radius + 0.5 * self.fibre_diameter

    @property
    def winding_perimeter(self) -> float:
        """Length of one turn of the fibre around body and neutral layer [m], along the thread's
        centre line: the half-round (radius r + d/2), the two flat sides down past the neutral
        layer, the rounded corners (radius d/2) and the flat bottom."""
        d = self.fibre_diameter
        return (math.pi * self.winding_radius + 2 * (self.main_body_thickness + self.neutral_thickness)
                + math.pi * d / 2 + 2 * self.outer_radius)

    @property
    def fibre_pitch(self) -> float:
        """Axial distance between turns of the helix [m]: the winding's perimeter times tan(twist angle)."""
        return self.winding_perimeter * math.tan(math.radians(self.twist_angle_deg))

    @property
    def neutral_span(self) -> float:
        """Length the neutral layer's segments and gaps cover [m]."""
        return sum(self.segment_lengths) + sum(self.segment_gaps)

    @property
    def yeoh_shear_modulus(self) -> float:
        """The silicone's small-strain shear modulus [Pa]: 2 C10."""
        return 2.0 * self.yeoh_c10
