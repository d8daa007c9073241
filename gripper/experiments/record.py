"""The trial record: what one grasp trial reports, typed, with its JSON schema.

A :class:`TrialRecord` is what :func:`gripper.experiments.trial.run_trial` returns and what
each line of a benchmark's ``trials.jsonl`` holds (:meth:`TrialRecord.to_dict`). It is also a
read-only mapping of those JSON keys, so ``rec["success"]`` and ``rec.success`` are the same.

Each drive reports under one nested ``drive`` entry, with keys of its own (schema 3, gripper
0.23.0); records of schema 2 (0.9.0-0.22.0), whose cable and pneumatic keys stood at the top
level, are upgraded when read (:func:`upgrade_record`).

Statuses: ``"ok"`` (the protocol ran to its end: the outcome fields are set), ``"error"``
(the simulation went unstable: ``error`` says how, ``success`` is None and the trial counts
neither as a success nor as a failure) or ``"no_object"`` (the palm camera saw nothing on the
table: ``error`` says what it saw; neither a success nor a failure).

Example:
    >>> from gripper.experiments.record import TrialRecord
    >>> sorted(TrialRecord.json_schema()["required"])[:3]
    ['config_hash', 'drive', 'failed_phase']
"""

from __future__ import annotations

import dataclasses
import types
import typing
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from typing import Any

SCHEMA_ID = "gripper.trial_record/3"
STATUSES = ("ok", "error", "no_object")
FAILED_PHASES = ("lift", "hold", "shake", "damage")
# Fields set only when the protocol ran to its end (status "ok").
REQUIRED_OUTCOME_FIELDS = ("lift_height_m", "slip_m", "max_slip_m", "damaged", "damage_measure",
                           "damage_limit")
# Optional outcome fields, set when the protocol ran to its end.
OUTCOME_FIELDS = (*REQUIRED_OUTCOME_FIELDS, "policy")
# Added in gripper 0.12.0 (optional): the grasp made, where the palm went, the camera's estimate.
APPROACH_FIELDS = ("grasp", "palm_xy_m", "depth_estimate")
# Added in gripper 0.21.0 (optional): the wrist's turn and how the fingers met the footprint.
WRIST_FIELDS = ("wrist_yaw_rad", "pose")
# Set only by the grasp controller (policy "controller").
CONTROLLER_FIELDS = ("contact_time_s", "grasp_time_s")
# Schema 2's drive keys at the top level, and where schema 3 keeps them in the drive entry
# (upgrade_record): the cable gripper's, and the pneumatic gripper's from 0.15.0 (with its kind).
SCHEMA_2_DRIVE_KEYS = {"peak_cable_tension_N": "peak_cable_tension_N", "close_command_rad": "close_command_rad",
                       "servo_at_grasp": "at_grasp", "servo_at_hold_end": "at_hold_end",
                       "grip_tension_N": "grip_tension_N", "grip_pressure_Pa": "grip_pressure_Pa",
                       "peak_pressure_Pa": "peak_pressure_Pa"}
# The drive of a schema 2 record without ``actuation``, and the keys of schema 2 that the
# pneumatic gripper wrote with nothing to say (it has no cable).
SCHEMA_2_DEFAULT_DRIVE = "cable"
SCHEMA_2_PNEUMATIC_EMPTY = ("peak_cable_tension_N",)


def upgrade_record(data: dict[str, Any]) -> dict[str, Any]:
    """A record of schema 2 (gripper 0.9.0-0.22.0) in schema 3's form: the drive's keys, which
    stood at the top level, move into the ``drive`` entry with the drive's kind (``actuation``,
    absent for the cable gripper); the servos' readings are the entry's ``at_grasp`` and
    ``at_hold_end``. A record that has a ``drive`` entry is returned as it is."""
    if "drive" in data or not isinstance(data, dict) or "peak_cable_tension_N" not in data:
        return data
    out = {k: v for k, v in data.items() if k not in SCHEMA_2_DRIVE_KEYS and k != "actuation"}
    named = data.get("actuation")  # schema 2 named the pneumatic drive only; the others were the cable's
    drive = {"kind": named or SCHEMA_2_DEFAULT_DRIVE}
    for old, new in SCHEMA_2_DRIVE_KEYS.items():
        if old in data and data[old] is not None and not (named and old in SCHEMA_2_PNEUMATIC_EMPTY):
            drive[new] = data[old]
    out["drive"] = drive
    return out


@dataclass(frozen=True)
class Perturbation:
    """The sampled placement of the object: offset [m], yaw [rad], mass and friction scales [-]."""

    x_m: float
    y_m: float
    yaw_rad: float
    mass_scale: float
    friction_scale: float


@dataclass(frozen=True, eq=True)
class TrialRecord(Mapping[str, Any]):
    """One grasp trial's record (SI units; keys name their unit).

    Attributes:
        trial_id: ``{object}-{seed}-{index:04d}``.
        object, seed, index: what was grasped, the run's base seed and the trial's index.
        perturbation: the sampled placement (:class:`Perturbation` fields).
        config_hash: stable hash of the parameters, protocol, noise and object.
        versions: MuJoCo, gripper and NumPy versions.
        status: ``ok``, ``error`` or ``no_object``.
        success: held through lift, hold and shake without damage (None on error).
        failed_phase: the first phase that failed (lift, hold, shake, damage), or None.
        lift_height_m, slip_m, max_slip_m: object rise at the end, slip relative to the palm at
            the end and its largest value since the end of the lift [m].
        damaged, damage_measure, damage_limit: the object's damage measure (its unit is the
            object's) against its limit.
        policy: ``controller`` or ``per_object``.
        drive: the drive's entry: its ``kind`` and what it reports under keys of its own
            (``Drive.trial_outcome``, ``Drive.command_outcome``): its peak effort, its closing
            command or set-point, its sensed state at the end of the close phase and of the hold
            (``at_grasp``, ``at_hold_end``, one entry per finger).
        grasp: ``envelope`` or ``fingertip`` (gripper.experiments.approach).
        palm_xy_m: where the approach put the palm over the table [m].
        wrist_yaw_rad: the wrist's turn [rad]; pose: ``none``, ``across`` or ``straddle``
            (gripper.experiments.approach).
        depth_estimate: the palm camera's estimate (``ObjectEstimate`` as a dict; None under
            the catalogue approach).
        contact_time_s: from the start of closing to the first finger's detected contact [s]
            (controller only; None if none was detected).
        grasp_time_s: from the start of closing until every finger held its set-point or the
            end of its travel [s] (controller only; None if that never happened).
        error: what went unstable (status ``error``), or what the camera saw (``no_object``).
        peak_total_force_N, peak_finger_force_N: peaks over the trial.
        warnings: MuJoCo warnings raised.
        sim_time_s, wall_time_s: simulated and wall-clock time.
        run_config_hash: the benchmark run's configuration hash (set by the benchmark).
    """

    trial_id: str
    object: str
    seed: int
    index: int
    perturbation: dict[str, float]
    config_hash: str
    versions: dict[str, str]
    status: str
    success: bool | None
    failed_phase: str | None
    peak_total_force_N: float
    peak_finger_force_N: list[float]
    drive: dict[str, Any]
    warnings: int
    sim_time_s: float
    wall_time_s: float
    lift_height_m: float | None = None
    slip_m: float | None = None
    max_slip_m: float | None = None
    damaged: bool | None = None
    damage_measure: float | None = None
    damage_limit: float | None = None
    policy: str | None = None
    grasp: str | None = None
    palm_xy_m: list[float] | None = None
    depth_estimate: dict[str, float] | None = None
    wrist_yaw_rad: float | None = None
    pose: str | None = None
    contact_time_s: float | None = None
    grasp_time_s: float | None = None
    error: str | None = None
    run_config_hash: str | None = None

    # -- the JSON form ---------------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """The JSON-ready dict: outcome fields only when ``ok``, ``error`` only on error,
        ``run_config_hash`` only when set."""
        out = {}
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            if f.name in (*OUTCOME_FIELDS, *APPROACH_FIELDS, *WRIST_FIELDS) and self.status != "ok":
                continue
            if f.name in ("error", "run_config_hash", *CONTROLLER_FIELDS, *APPROACH_FIELDS, *WRIST_FIELDS) \
                    and v is None:
                continue
            out[f.name] = v
        return out

    @classmethod
    def from_dict(cls, data: Any, *, where: str = "trial record") -> TrialRecord:
        """Parse and check a record read back (e.g. a line of ``trials.jsonl``); a record of
        schema 2 is upgraded first (:func:`upgrade_record`).

        Raises:
            ValueError: naming ``where`` and the key that is missing, unknown or of the wrong type.
        """
        if not isinstance(data, dict):
            raise ValueError(f"{where}: expected a JSON object, got {type(data).__name__}")
        data = upgrade_record(data)
        schema = cls.json_schema()
        props, required = schema["properties"], set(schema["required"])
        unknown = sorted(set(data) - set(props))
        if unknown:
            raise ValueError(f"{where}: unknown key {unknown[0]!r}; allowed: {', '.join(props)}")
        for key in sorted(required - set(data)):
            raise ValueError(f"{where}: missing key {key!r}")
        for key, value in data.items():
            if not _matches(value, props[key]):
                raise ValueError(f"{where}: {key}: expected {_describe(props[key])}, got {value!r}")
        if data["status"] == "ok":
            for key in REQUIRED_OUTCOME_FIELDS:
                if key not in data:
                    raise ValueError(f"{where}: missing key {key!r} (status ok)")
        return cls(**data)

    @classmethod
    def json_schema(cls) -> dict[str, Any]:
        """JSON Schema (draft 2020-12) of :meth:`to_dict`'s output."""
        hints = typing.get_type_hints(cls)
        props: dict[str, Any] = {}
        required = []
        for f in dataclasses.fields(cls):
            props[f.name] = _schema_of(hints[f.name]) if f.name != "drive" else {}
            if f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING:
                required.append(f.name)
        props["status"] = {"enum": list(STATUSES)}
        props["failed_phase"] = {"enum": [*FAILED_PHASES, None]}
        props["drive"] = {"type": "object", "required": ["kind"], "properties": {"kind": {"type": "string"}},
                          "additionalProperties": True}
        props["perturbation"] = {"type": "object", "additionalProperties": False,
                                 "required": [f.name for f in dataclasses.fields(Perturbation)],
                                 "properties": {f.name: {"type": "number"}
                                                for f in dataclasses.fields(Perturbation)}}
        return {"$schema": "https://json-schema.org/draft/2020-12/schema", "$id": SCHEMA_ID,
                "title": "TrialRecord", "type": "object", "additionalProperties": False,
                "required": required, "properties": props}

    # -- a read-only mapping of the JSON keys -----------------------------------------------------
    def __getitem__(self, key: str) -> Any:
        return self.to_dict()[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self.to_dict())

    def __len__(self) -> int:
        return len(self.to_dict())


_JSON_TYPES = {str: "string", int: "integer", float: "number", bool: "boolean", type(None): "null"}


def _schema_of(tp: Any) -> dict[str, Any]:
    origin = typing.get_origin(tp)
    if origin in (types.UnionType, typing.Union):
        parts = [_schema_of(a) for a in typing.get_args(tp)]
        out: dict[str, Any] = {"type": [p["type"] for p in parts]}
        for p in parts:  # the container's item schema (a union of one container and null)
            out.update({k: v for k, v in p.items() if k != "type"})
        return out
    if origin is list:
        return {"type": "array", "items": _schema_of(typing.get_args(tp)[0])}
    if origin is dict:
        return {"type": "object", "additionalProperties": _schema_of(typing.get_args(tp)[1])}
    return {"type": _JSON_TYPES[tp]}


def _matches(value: Any, schema: dict[str, Any]) -> bool:
    """Whether ``value`` fits ``schema`` (the subset of JSON Schema that :meth:`json_schema` uses)."""
    if "enum" in schema:
        return value in schema["enum"]
    kinds = schema["type"] if isinstance(schema["type"], list) else [schema["type"]]
    for kind in kinds:
        if kind == "null" and value is None:
            return True
        if kind == "boolean" and isinstance(value, bool):
            return True
        if kind == "integer" and isinstance(value, int) and not isinstance(value, bool):
            return True
        if kind == "number" and isinstance(value, int | float) and not isinstance(value, bool):
            return True
        if kind == "string" and isinstance(value, str):
            return True
        if kind == "array" and isinstance(value, list):
            return all(_matches(v, schema["items"]) for v in value)
        if kind == "object" and isinstance(value, dict):
            if schema.get("additionalProperties") is True:  # named keys checked, the rest free
                return (set(schema["required"]) <= set(value)
                        and all(_matches(value[k], sub) for k, sub in schema["properties"].items() if k in value))
            if "properties" in schema:
                return (set(value) == set(schema["required"])
                        and all(_matches(v, schema["properties"][k]) for k, v in value.items()))
            return all(_matches(v, schema["additionalProperties"]) for v in value.values())
    return False


def _describe(schema: dict[str, Any]) -> str:
    if "enum" in schema:
        return "one of " + ", ".join(str(v) for v in schema["enum"])
    kinds = schema["type"] if isinstance(schema["type"], list) else [schema["type"]]
    return " or ".join(kinds)
