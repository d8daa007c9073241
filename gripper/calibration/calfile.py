"""Calibration files: fitted hinge values for one finger design, as versioned JSON.

Schema ``gripper.calibration/1``::

    {
      "schema": "gripper.calibration/1",
      "design_hash": "<16 hex>",          # finger geometry + material + cable (design_hash())
      "source": "reference" | "measured",
      "fitted": {"stiffness_Nm_per_rad": [...], "damping_Nms_per_rad": [...],
                 "rest_angle_deg": [...]},
      "paper_stiffness_Nm_per_deg": 0.0019,  # paper 000 Table 2, for comparison
      "metrics": {...},                    # gripper.calibration.fit.fit_metrics
      "settings": {...},                   # reference and fit settings
      "versions": {"gripper": ..., "mujoco": ...}
    }

Every consumer (``gripper bend``, ``bench``, ``video``, ``write-models``, the environment)
applies a file with :func:`apply_calibration`, which refuses a file made for another design
unless ``force=True``.

Example:
    >>> from gripper.core.params import GripperParams
    >>> p = GripperParams()
    >>> cal = Calibration(design_hash=design_hash(p), source="measured",
    ...                   stiffness=(0.01,) * 5, damping=(1e-4,) * 5, rest_angle_deg=(0.0,) * 5)
    >>> apply_calibration(p, cal).springs.stiffness[0]
    0.01
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import mujoco

from gripper.core.atomic import write_atomic
from gripper.core.hashing import stable_hash
from gripper.core.params import GripperParams
from gripper.core.user_files import parse_user_data, read_user_text

SCHEMA = "gripper.calibration/1"
PAPER_STIFFNESS_NM_PER_DEG = 1.9e-3  # paper 000, Table 2


class CalibrationMismatch(ValueError):
    """The calibration file was made for another finger design."""


def design_hash(p: GripperParams) -> str:
    """Hash of what the body's bending depends on: finger geometry, material, cable [hex].

    The tip's taper (``finger.tip_taper``) is left out: the tip element lies distal of the last
    hinge, so its shape moves no spring, and the bending test is horizontal (its weight loads the
    bearings). A tapered design keeps its square tip's calibration."""
    d = p.to_dict()
    finger = {k: v for k, v in d["finger"].items() if k != "tip_taper"}
    return stable_hash({"finger": finger, "material": d["material"], "cable": d["cable"]})


@dataclass(frozen=True)
class Calibration:
    """Fitted hinge values of one design (SI units: N·m/rad, N·m·s/rad, deg)."""

    design_hash: str
    source: str
    stiffness: tuple[float, ...]
    damping: tuple[float, ...]
    rest_angle_deg: tuple[float, ...]
    metrics: dict = field(default_factory=dict)
    settings: dict = field(default_factory=dict)

    def to_json_dict(self) -> dict:
        from gripper.core.provenance import package_version
        return {
            "schema": SCHEMA,
            "design_hash": self.design_hash,
            "source": self.source,
            "fitted": {"stiffness_Nm_per_rad": list(self.stiffness),
                       "damping_Nms_per_rad": list(self.damping),
                       "rest_angle_deg": list(self.rest_angle_deg)},
            "paper_stiffness_Nm_per_deg": PAPER_STIFFNESS_NM_PER_DEG,
            "metrics": self.metrics,
            "settings": self.settings,
            "versions": {"gripper": package_version(), "mujoco": mujoco.__version__},
        }

    def save(self, path: str | Path) -> Path:
        path = Path(path)
        text = json.dumps(self.to_json_dict(), indent=2) + "\n"
        write_atomic(path, lambda tmp: Path(tmp).write_text(text))
        return path

    @classmethod
    def load(cls, path: str | Path) -> Calibration:
        """Read and check a calibration file.

        Raises:
            ValueError: unreadable file, wrong schema, missing or non-numeric fields.
        """
        path = Path(path)
        data = parse_user_data(read_user_text(path, "calibration file"), "json", f"calibration file {path.name}")
        if not isinstance(data, dict) or data.get("schema") != SCHEMA:
            got = data.get("schema") if isinstance(data, dict) else type(data).__name__
            raise ValueError(f"calibration file: schema must be {SCHEMA!r}, got {got!r}")
        fitted = data.get("fitted")
        if not isinstance(fitted, dict):
            raise ValueError("calibration file: missing the 'fitted' table")
        values = {}
        for key in ("stiffness_Nm_per_rad", "damping_Nms_per_rad", "rest_angle_deg"):
            v = fitted.get(key)
            if (not isinstance(v, list) or not v
                    or not all(isinstance(x, int | float) and not isinstance(x, bool) for x in v)):
                raise ValueError(f"calibration file: fitted.{key} must be a non-empty list of "
                                 f"numbers, got {v!r}")
            values[key] = tuple(float(x) for x in v)
        if not isinstance(data.get("design_hash"), str):
            raise ValueError("calibration file: missing design_hash")
        return cls(design_hash=data["design_hash"], source=str(data.get("source", "")),
                   stiffness=values["stiffness_Nm_per_rad"],
                   damping=values["damping_Nms_per_rad"],
                   rest_angle_deg=values["rest_angle_deg"],
                   metrics=data.get("metrics", {}), settings=data.get("settings", {}))


def apply_calibration(p: GripperParams, cal: Calibration | str | Path | None, *,
                      force: bool = False) -> GripperParams:
    """``p`` with its hinge springs replaced by the calibration's fitted values.

    Raises:
        CalibrationMismatch: the file's design hash differs from ``p``'s (unless ``force``).
        ValueError: a malformed file or values that do not fit the design.
    """
    if cal is None:
        return p
    if not isinstance(cal, Calibration):
        cal = Calibration.load(cal)
    mine = design_hash(p)
    if cal.design_hash != mine and not force:
        raise CalibrationMismatch(
            f"calibration file: made for design {cal.design_hash}, these parameters are "
            f"design {mine}; recalibrate (gripper calibrate) or pass --force-calibration")
    springs = p.springs.replace(stiffness=cal.stiffness, damping=cal.damping,
                                rest_angle_deg=cal.rest_angle_deg)
    return p.replace(springs=springs).validate()
