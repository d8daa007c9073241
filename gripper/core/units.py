"""Units, stated once for the whole package.

Every quantity is SI (m, kg, s, N, Pa, N·m, rad) unless its name says otherwise: a name ending
in ``_deg`` is in degrees, ``_mm`` in millimetres, and a unit suffix such as ``_N`` or ``_m``
in a record key names the unit of that value. Parameter fields carry their unit in their
metadata (:mod:`gripper.core.fields`).
"""

from __future__ import annotations

import math

DEG = math.pi / 180.0  # rad per degree
