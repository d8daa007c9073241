"""The proportional pressure regulator that feeds each pneumatic finger: its datasheet figures
and the first-order model built on them.

An electro-pneumatic regulator (SMC ITV series) holds its output at a pressure proportional to
its input signal, with an internal pressure sensor closing the loop, and reports that pressure
on a monitor output. The model: the output pressure follows the set-point, clamped to the set
range, through a first-order lag whose time constant gives the datasheet's response time
(``RESPONSE_FRACTION`` of a step); a set-point below the range's low end vents the output to 0.
In the MJCF it is the chamber actuator's own dynamics (``dyntype="filterexact"``, the
actuator's activation is the chamber pressure [Pa]; :mod:`gripper.drives.pneumatic.chamber`).

Not modelled, with the reason: the flow limit (the regulator's rated flow fills a finger's
8 mL chamber many times faster than its response time; SMC's ITV0000 flow figure was not in
the sources at hand, so this is unchecked); hysteresis and repeatability (1 % F.S. class:
below the monitor's accuracy).

Example:
    >>> from gripper.datasheets.regulator import regulator_datasheet
    >>> ds = regulator_datasheet("smc_itv0030")
    >>> ds.pressure_max, round(ds.time_constant, 4)
    (500000.0, 0.0434)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

# A first-order lag reaches this fraction of a step in the datasheet's response time: the 90 %
# rise time is the usual definition of a regulator's response time (SMC does not define its own
# in the sources at hand; 90 % is assumed).
RESPONSE_FRACTION = 0.9


@dataclass(frozen=True)
class RegulatorDatasheet:
    """One regulator model's figures (SI units) and their sources.

    Attributes:
        name: preset key.
        description: the product.
        pressure_min: low end of the set pressure range [Pa]; a lower set-point vents to 0.
        pressure_max: high end of the set pressure range [Pa] (full scale, F.S.).
        supply_max: highest supply pressure [Pa].
        response_time: time to ``RESPONSE_FRACTION`` of a set-point step, no load [s].
        linearity: output error over the range, fraction of F.S. [-].
        monitor_accuracy: the monitor output's error, fraction of F.S. [-].
        source: where each figure comes from.
    """

    name: str
    description: str
    pressure_min: float
    pressure_max: float
    supply_max: float
    response_time: float
    linearity: float
    monitor_accuracy: float
    source: str

    @property
    def time_constant(self) -> float:
        """The first-order lag's time constant [s]: response_time / ln(1 / (1 - fraction))."""
        return self.response_time / -math.log(1.0 - RESPONSE_FRACTION)

    def output(self, set_point: float) -> float:
        """The steady output pressure [Pa] for a set-point [Pa]: clamped to the range, vented below it."""
        if set_point < self.pressure_min:
            return 0.0
        return min(set_point, self.pressure_max)


# SMC ITV0030 (compact ITV0000 series, 0.001-0.5 MPa), the regulator soft-robotics labs commonly
# drive pneumatic fingers with. Set range and supply: SMC catalogue CAT.ES60-23A, "Variation Map",
# Series ITV0000: ITV003 0.001-0.5 MPa, max supply 1.0 MPa (stored copy:
# https://studylib.net/doc/18330324/high-pressure-electro). Linearity ±1 % F.S. and monitor output
# accuracy ±6 % F.S.: as quoted from SMC's catalogue by lab documentation (GitHub READMEs of two
# ITV0030 pressure boards); SMC's own ITV0000 table was not among the stored sources. Response time:
# assumed 0.1 s, the figure the same lab documentation gives for the ITV series, unconfirmed
# against SMC's table.
_ITV0030 = RegulatorDatasheet(
    name="smc_itv0030",
    description="SMC ITV0030 electro-pneumatic regulator (0.001-0.5 MPa)",
    pressure_min=1.0e3,
    pressure_max=0.5e6,
    supply_max=1.0e6,
    response_time=0.1,
    linearity=0.01,
    monitor_accuracy=0.06,
    source="SMC CAT.ES60-23A variation map (range, supply); linearity, monitor accuracy and the "
           "0.1 s response time as lab documentation quotes SMC (unconfirmed)",
)

REGULATOR_PRESETS: dict[str, RegulatorDatasheet] = {_ITV0030.name: _ITV0030}


def regulator_datasheet(name: str) -> RegulatorDatasheet:
    """The preset ``name`` (a key of :data:`REGULATOR_PRESETS`).

    Raises:
        ValueError: an unknown preset, naming the allowed ones.
    """
    try:
        return REGULATOR_PRESETS[name]
    except KeyError:
        raise ValueError(f"pneumatic.regulator: must be one of {', '.join(REGULATOR_PRESETS)}, got {name!r}") from None


__all__ = ["REGULATOR_PRESETS", "RESPONSE_FRACTION", "RegulatorDatasheet", "regulator_datasheet"]
