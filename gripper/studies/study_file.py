"""A design study's file: what to vary around which base design, with which design and
responses (format in ``docs/studies.md``), read and checked once, and each design point's
parameters, with hinge springs that follow the design (:func:`apply_point`).

Besides the design's parameters (``finger.cut_angle_deg``, ``actuation.kind``, ...), a gripper
study may fix or vary how its trials are run: ``protocol.<field>`` (a
:class:`gripper.experiments.protocol.GraspProtocol` field: the grip set-point, the time step, the
approach, ...), ``placement.mass_scale`` / ``placement.friction_scale`` (the object's mass and
friction coefficient scaled in every trial, in place of the sampled scatter:
:class:`gripper.objects.scene_objects.Placement`) and ``object.mesh_points`` (the deformable
objects' mesh resolution, three whole numbers, for a mesh-convergence study; the objects keep
their names, so their trials keep their placements). A point that changes ``protocol.timestep``
keeps the control period (``chunk_steps`` follows) unless it sets ``protocol.chunk_steps`` too.

Example:
    >>> from gripper.studies.study_file import load_study
    >>> load_study("one_at_a_time").design
    'one_at_a_time'
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from gripper.core.hashing import stable_hash
from gripper.core.params import GripperParams
from gripper.core.ranges import SEED_MAX, TRIALS_MAX
from gripper.core.resources import STUDIES_DIR
from gripper.core.user_files import parse_user_data, read_user_text
from gripper.drives import drive_class, drive_for
from gripper.experiments.protocol import GraspProtocol
from gripper.objects.envelope_objects import SHAPES
from gripper.objects.kinds import registered_kinds
from gripper.references.pneumatic_params import PneumaticActuator

DESIGNS = ("one_at_a_time", "factorial", "latin_hypercube")
MODELS = ("gripper", "actuator")  # the cable gripper (GripperParams) or paper 001's actuator
RESPONSES: dict[str, dict[str, type]] = {
    "bending": {"r_max": float, "duration": float},
    "tension_for_angle": {"angle_deg": float},
    "blocked_force": {"r": float},
    "grasp": {"objects": list, "trials": int},
    "holding_force": {"objects": list, "trials": int},
    # the capability envelope on one grid (gripper.objects.envelope_objects): per shape, the
    # smallest and largest width held (at HELD_FRACTION of its trials)
    "envelope": {"shapes": list, "sizes": list, "mass": float, "friction": float, "trials": int},
    # the heaviest mass held of one shape and width (the envelope's payload, at one point)
    "payload": {"shape": str, "size": float, "masses": list, "friction": float, "trials": int},
    # success on the everyday parts built as meshes (gripper.objects.everyday_parts)
    "parts": {"parts": list, "trials": int},
    "inflation": {"pressure_max": float, "steps": int, "refinement": int},
}
# upper bounds of response options: the actuator model's pressure range (PneumaticActuator.pressure_max's
# bound), load steps, and the finest mesh that fits this machine's memory (refinement 8: ~600k unknowns)
RESPONSE_LIMITS: dict[str, dict[str, float]] = {"inflation": {"pressure_max": 1e6, "steps": 100, "refinement": 8},
                   # trials per object (per width, for the envelope) and a bending run's length [s]
                   # (ten minutes of simulated time, the command line's MAX_SIMULATED_S)
                   "grasp": {"trials": 1000}, "holding_force": {"trials": 1000}, "envelope": {"trials": 100},
                   "payload": {"trials": 100}, "parts": {"trials": 1000},
                   "bending": {"duration": 600.0}}
# Design points in one study: a factorial of 13 parameters at two levels; a study's trials in all
# (points × each point's trials) at most TRIALS_MAX, a day of trials on one core.
POINTS_MAX = 10_000
MODEL_RESPONSES = {"gripper": ("bending", "tension_for_angle", "blocked_force", "grasp", "holding_force", "envelope",
                               "payload", "parts"),
                   "actuator": ("inflation",)}


@dataclass(frozen=True)
class ActuatorDesign:
    """Paper 001's actuator as a study's base design: one section, ``actuator``, so a study
    varies ``actuator.<field>`` of :class:`gripper.references.pneumatic_params.PneumaticActuator`."""

    actuator: PneumaticActuator = field(default_factory=PneumaticActuator)

    def to_dict(self) -> dict:
        return {"actuator": dataclasses.asdict(self.actuator)}

    def replace(self, **changes) -> ActuatorDesign:
        return dataclasses.replace(self, **changes)

    def validate(self) -> ActuatorDesign:
        self.actuator.validate()
        return self
# Parameters whose change alters the finger's bending and so would void a calibration.
CALIBRATION_SECTIONS = ("finger.", "material.", "springs.")
# Finger fields that move no spring (the calibration's design hash leaves them out too,
# gripper.calibration.calfile.design_hash): the tip element lies past the last hinge.
SPRING_NEUTRAL = ("finger.tip_taper",)
BRIDGE_RULE = "hinge stiffness scaled by the bridge-beam rule k ∝ E·w·t³ (not fitted)"


def gent_modulus(shore_a: float) -> float:
    """Young's modulus [Pa] from Shore A hardness by Gent's empirical relation (1958)."""
    return 0.0981e6 * (56.0 + 7.62336 * shore_a) / (0.137505 * (254.0 - 2.54 * shore_a))


@dataclass(frozen=True)
class Study:
    """A parsed, validated study (see the module docstring for the file format)."""

    name: str
    base: GripperParams | ActuatorDesign
    design: str
    vary: dict
    responses: dict
    objective: tuple[str, str] | None = None
    limits: tuple = ()  # ("at_least" | "at_most", metric, value): points a recommendation may use
    points: int = 0
    seed: int = 0
    source: str = ""
    lines: dict = field(default_factory=dict, compare=False)
    protocol: GraspProtocol = field(default_factory=GraspProtocol)  # the trials' fixed protocol
    placement: dict = field(default_factory=dict)  # fixed placement scales, e.g. {"friction_scale": 0.5}

    def value(self, key: str):
        """The base value of a varied key: a design parameter, or a trial setting."""
        section, _, name = key.partition(".")
        if section == "protocol":
            return getattr(self.protocol, name)
        if key == "object.mesh_points":
            return self.placement.get("mesh_points")
        if section == "placement":
            return self.placement.get(name, 1.0)
        return get_dotted(self.base, key)

    def trial_setup(self, changes: dict) -> tuple[GraspProtocol, dict]:
        """The protocol and the placement scales of a point with ``changes`` (see the module)."""
        proto = self.protocol
        edits = {k.partition(".")[2]: v for k, v in changes.items() if k.startswith("protocol.")}
        if "timestep" in edits and "chunk_steps" not in edits:
            edits["chunk_steps"] = max(1, round(proto.chunk_steps * proto.timestep / edits["timestep"]))
        proto = dataclasses.replace(proto, **edits).validate() if edits else proto
        placement = {**self.placement,
                     **{k.partition(".")[2]: v for k, v in changes.items() if k in PLACEMENT_KEYS}}
        return proto, placement

    def design_points(self) -> list[dict]:
        """The parameter changes of every point, in a fixed order (point 0 is the base)."""
        pts: list[dict] = [{}]
        if self.design == "one_at_a_time":
            for key, values in self.vary.items():
                pts += [{key: v} for v in values]
        elif self.design == "factorial":
            keys = list(self.vary)
            pts += [dict(zip(keys, combo, strict=True)) for combo in itertools.product(*self.vary.values())]
        else:
            from scipy.stats import qmc

            keys = list(self.vary)
            u = qmc.LatinHypercube(d=len(keys), seed=self.seed).random(self.points)
            for row in u:
                pt = {}
                for k, x in zip(keys, row, strict=True):
                    lo, hi = self.vary[k]["min"], self.vary[k]["max"]
                    v = lo + x * (hi - lo)
                    pt[k] = int(round(v)) if isinstance(self.value(k), int) else float(v)
                pts.append(pt)
        return pts

    def identity(self) -> dict:
        from gripper.core.provenance import versions

        return {"versions": {k: v for k, v in versions().items() if k in ("gripper", "mujoco")},
                "name": self.name, "base": self.base.to_dict(), "design": self.design, "vary": self.vary,
                "responses": self.responses, "objective": self.objective, "limits": self.limits,
                "points": self.points, "seed": self.seed,
                # the trials' settings, where a study sets them (absent: the defaults, as before 0.18.0)
                **({"protocol": self.protocol.to_dict()} if self.protocol != GraspProtocol() else {}),
                **({"placement": self.placement} if self.placement else {})}

    def hash(self) -> str:
                return stable_hash([self.identity()])


def get_dotted(p: GripperParams | ActuatorDesign, dotted: str):
    section, _, name = dotted.partition(".")
    return getattr(getattr(p, section), name)


def _key_line(text: str, key: str) -> int:
    """Line number of ``key`` in the TOML text (for error messages): the line that sets it (the
    last part of a dotted key), else its section's header; 0 if neither is found."""
    lines = text.splitlines()
    for k in dict.fromkeys((key, key.split(".")[-1])):
        pat = re.compile(r'^\s*"?' + re.escape(k) + r'"?\s*=')
        for i, line in enumerate(lines, 1):
            if pat.match(line):
                return i
    header = re.compile(r"^\s*\[\s*" + re.escape(key.split(".")[0]) + r"\s*\]")
    return next((i for i, line in enumerate(lines, 1) if header.match(line)), 0)


PLACEMENT_KEYS = ("placement.mass_scale", "placement.friction_scale", "object.mesh_points")


def is_trial_key(key: str) -> bool:
    """Whether ``key`` names a trial setting (``protocol.<field>``, ``placement.<scale>``)."""
    section, _, name = key.partition(".")
    if section == "protocol":
        return name in {f.name for f in dataclasses.fields(GraspProtocol)}
    return key in PLACEMENT_KEYS


def _has_param(p, key: str) -> bool:
    """Whether ``key`` (``section.field``) names a parameter of the design ``p``."""
    section, _, name = key.partition(".")
    sub = getattr(p, section, None)
    return sub is not None and dataclasses.is_dataclass(sub) and name in {f.name for f in dataclasses.fields(sub)}


def _replace_dotted(p, key: str, value):
    section, _, name = key.partition(".")
    sub = getattr(p, section)
    if isinstance(getattr(sub, name), tuple) and not isinstance(value, tuple | list):
        value = (value,)
    value = tuple(value) if isinstance(value, list) else value
    return p.replace(**{section: dataclasses.replace(sub, **{name: value})})


def apply_point(base, changes: dict) -> tuple:
    """The design of one point, and the reasons it is not calibrated (empty: calibrated).

    An actuator's point (:class:`ActuatorDesign`) is its base with the changes: nothing to
    calibrate. A gripper's:

    A point that changes the finger's geometry within the committed stiffness surrogate's
    ranges (:mod:`gripper.calibration.surrogate`) gets the base springs times the surrogate's
    stiffness ratio (and the exact E ratio): calibrated on the continuum reference. Otherwise
    the bridge-beam rule sets them and the point is marked not calibrated, with the reason.
    """
    changes = {k: v for k, v in changes.items() if not is_trial_key(k)}
    p = base
    for key, value in changes.items():
        p = _replace_dotted(p, key, value)
    if isinstance(base, ActuatorDesign):
        return p.validate(), []
    changes = {k: v for k, v in changes.items() if k not in SPRING_NEUTRAL}
    if "finger.n_segments" in changes and "finger.pitch" not in changes:
        length = base.finger.pitch * base.finger.n_segments
        p = p.replace(finger=dataclasses.replace(p.finger, pitch=length / p.finger.n_segments))
    if "material.shore_a" in changes and "material.youngs_modulus" not in changes:
        e = base.material.youngs_modulus * gent_modulus(p.material.shore_a) / gent_modulus(base.material.shore_a)
        p = p.replace(material=dataclasses.replace(p.material, youngs_modulus=e))
    e_ratio = p.material.youngs_modulus / base.material.youngs_modulus
    geometry = {k: get_dotted(p, k) for k in SURROGATE_DIMENSIONS if get_dotted(p, k) != get_dotted(base, k)}
    surrogate, why_not = _surrogate_for(base, p, changes)
    reasons = []
    if "springs.stiffness" in changes:
        if any(k.startswith(("finger.", "material.")) for k in changes):
            reasons.append("springs set by hand while the finger or silicone changed")
    elif surrogate is not None:
        scale = e_ratio * surrogate.ratio(geometry, base)
        if scale != 1.0:
            k = tuple(v * scale for v in base.springs.stiffness)
            if p.finger.n_hinges != base.finger.n_hinges:
                k = (float(np.mean(k)),)
            p = p.replace(springs=dataclasses.replace(p.springs, stiffness=k))
    else:
        scale = (e_ratio * (p.finger.width / base.finger.width)
                 * (p.finger.bridge_thickness / base.finger.bridge_thickness) ** 3)
        if scale != 1.0:
            k = tuple(v * scale for v in base.springs.stiffness)
            if p.finger.n_hinges != base.finger.n_hinges:
                k = (float(np.mean(k)),)
            p = p.replace(springs=dataclasses.replace(p.springs, stiffness=k))
        if any(k.startswith(CALIBRATION_SECTIONS) for k in changes):
            reasons.append(f"{why_not}; " + BRIDGE_RULE)
    return p.validate(), reasons


SURROGATE_DIMENSIONS = ("finger.cut_angle_deg", "finger.bridge_thickness", "finger.hole_height",
                        "finger.pitch")
_SURROGATE_CACHE: dict = {}


def _surrogate_for(base: GripperParams, p: GripperParams, changes: dict):
    """The committed stiffness surrogate if it covers this point, else (None, the reason)."""
    from gripper.calibration.surrogate import StiffnessSurrogate

    other = [k for k in changes if k.startswith(("finger.", "material."))
             and k not in SURROGATE_DIMENSIONS
             and k not in ("finger.n_segments", "material.shore_a", "material.youngs_modulus")]
    if other:
        return None, f"{', '.join(other)} changed, outside the stiffness surrogate's dimensions"
    default = GripperParams()
    if base.finger != default.finger or base.material != default.material:
        return None, "the base design is not the default one the surrogate was built around"
    if "s" not in _SURROGATE_CACHE:
        _SURROGATE_CACHE["s"] = StiffnessSurrogate.load_default()
    s = _SURROGATE_CACHE["s"]
    for k in SURROGATE_DIMENSIONS:
        lo, hi = s.ranges[k]
        if not lo - 1e-12 <= get_dotted(p, k) <= hi + 1e-12:
            return None, f"{k} = {get_dotted(p, k):g} is outside the stiffness surrogate's range"
    return s, ""


# A study file's error: err(key, message), a ValueError naming the file, the key's line and the key.
_Error = Callable[[str, str], ValueError]


def load_study(path: str | Path) -> Study:
    """Parse and validate a study file; every error names the key and its line.

    ``path`` is a file, or the name of a study shipped with the package (``one_at_a_time``,
    ``latin_hypercube``: ``gripper/data/studies``), so the examples work from an installed wheel.

    Raises:
        ValueError: unreadable file, bad TOML, unknown key or parameter, wrong type, value out of
            range (checked by building every design point before any work starts).
    """
    path = _study_path(Path(path))
    text = read_user_text(path, "study")
    data = parse_user_data(text, "toml", f"study: {path}")

    def err(key, msg):
        line = _key_line(text, key.split(".")[-1] if key.startswith("responses.") else key)
        return ValueError(f"study: {path}:{line}: {key}: {msg}")

    st = _study_table(data, path, err)
    design, model, base, points, seed = _study_header(st, path, err)
    base, protocol, placement = _read_fixed(data.get("fixed", {}), model, base, err)
    vary = _read_vary(data.get("vary", {}), model, design, base, protocol, placement, err)
    responses = _read_responses(data.get("responses", {}), model, base, vary, err)
    objective, limits = _read_objective(dict(data.get("objective", {})), responses, err)
    study = Study(name=str(st.get("name", path.stem)), base=base, design=design, vary=vary, responses=responses,
                  objective=objective, points=points, seed=seed, source=str(path),
                  limits=tuple((b, k, v) for (b, k), v in limits.items()), protocol=protocol, placement=placement)
    _check_size(design, vary, points, responses, err)
    _check_points_build(study, responses, err)
    if objective is not None and objective[1] not in metric_names(responses):
        raise err(f"objective.{objective[0]}",
                  f"unknown metric {objective[1]!r}; available: {', '.join(metric_names(responses))}")
    return study


def _study_path(path: Path) -> Path:
    """``path``, or the shipped study of that name where ``path`` is a bare name and no file."""
    shipped = STUDIES_DIR / f"{path.name}.toml"
    if not path.exists() and path.suffix == "" and path.parent == Path(".") and shipped.is_file():
        return shipped
    return path


def _study_table(data: dict, path: Path, err: _Error) -> dict:
    """The file's [study] table, once its sections and the table's keys and texts are checked."""
    for section in data:
        if section not in ("study", "fixed", "vary", "responses", "objective"):
            raise err(section, "unknown section; allowed: study, fixed, vary, responses, objective")
        if not isinstance(data[section], dict):
            raise err(section, f"must be a table ([{section}]), got {data[section]!r}")
    if "study" not in data:
        raise ValueError(f"study: {path}: no [study] section; a study file starts with [study] "
                         "(see the shipped one_at_a_time.toml)")
    st = data["study"]
    for k in st:
        if k not in ("name", "model", "base", "design", "points", "seed"):
            raise err(k, "unknown key in [study]; allowed: name, model, base, design, points, seed")
    for k in ("name", "model", "base", "design"):
        if k in st and not isinstance(st[k], str):
            raise err(k, f"must be text, got {st[k]!r}")
    if "name" in st and (len(st["name"]) > 100 or not st["name"].isprintable()):
        raise err("name", f"a title of at most 100 printable characters on one line, got {len(st['name'])} "
                  "characters")
    return st


def _study_header(st: dict, path: Path, err: _Error) -> tuple[str, str, GripperParams | ActuatorDesign, Any, int]:
    """(design, model, base design, points, seed) of the [study] table ``st``."""
    design = st.get("design", "one_at_a_time")
    if design not in DESIGNS:
        raise err("design", f"must be one of {', '.join(DESIGNS)}, got {design!r}")
    model = st.get("model", "gripper")
    if model not in MODELS:
        raise err("model", f"must be one of {', '.join(MODELS)}, got {model!r}")
    base: GripperParams | ActuatorDesign = ActuatorDesign() if model == "actuator" else GripperParams()
    if st.get("base") and model == "actuator":
        raise err("base", "an actuator study sets its base design in [fixed], not a parameter file")
    if st.get("base"):
        bpath = Path(st["base"])
        if not bpath.is_absolute():
            bpath = path.parent / bpath
        try:
            base = GripperParams.load(bpath)
        except ValueError as e:
            raise err("base", str(e)) from None
    points = st.get("points", 0)
    seed = st.get("seed", 0)
    if not isinstance(seed, int) or isinstance(seed, bool) or not 0 <= seed <= SEED_MAX:
        raise err("seed", f"must be an integer in [0, {SEED_MAX:,}], got {seed!r}")
    if design == "latin_hypercube" and (not isinstance(points, int) or isinstance(points, bool)
                                        or not 1 <= points <= POINTS_MAX):
        raise err("points", f"must be an integer in [1, {POINTS_MAX:,}] for a latin_hypercube, got {points!r}")
    return design, model, base, points, seed


def _read_fixed(fixed: dict, model: str, base: GripperParams | ActuatorDesign,
                err: _Error) -> tuple[GripperParams | ActuatorDesign, GraspProtocol, dict]:
    """The [fixed] table applied: (base design, the trials' protocol, the placement scales)."""
    protocol, placement = GraspProtocol(), {}
    for key, value in fixed.items():
        if model == "gripper" and is_trial_key(key):
            try:
                if key.startswith("protocol."):
                    protocol = dataclasses.replace(protocol, **{key.partition(".")[2]: value}).validate()
                else:
                    placement[key.partition(".")[2]] = _scale(value)
            except (ValueError, TypeError) as e:
                raise err(key, str(e)) from None
            continue
        if not _has_param(base, key):
            raise err(key, f"unknown parameter in [fixed]; use a dotted path of the {model}'s parameters")
        try:
            base = _replace_dotted(base, key, value).validate()
        except (ValueError, TypeError) as e:
            raise err(key, str(e)) from None
    return base, protocol, placement


def _read_vary(vary: dict, model: str, design: str, base: GripperParams | ActuatorDesign, protocol: GraspProtocol,
               placement: dict, err: _Error) -> dict:
    """The [vary] table, each key's values checked and converted in place (:func:`_vary_values`)."""
    if not vary:
        raise err("vary", "give at least one parameter to vary")
    for key, spec in vary.items():
        vary[key] = _vary_values(key, spec, model, design, base, protocol, placement, err)
    return vary


def _vary_values(key: str, spec, model: str, design: str, base: GripperParams | ActuatorDesign,
                 protocol: GraspProtocol, placement: dict, err: _Error) -> list | dict:
    """The values of varied ``key`` (a list; a latin_hypercube's {min, max}), of its base value's type."""
    trial = model == "gripper" and is_trial_key(key)
    if not trial and not _has_param(base, key):
        example = "actuator.cladding_thickness" if model == "actuator" else "finger.cut_angle_deg"
        raise err(key, f"unknown parameter; use a dotted {model} parameter path such as {example}, "
                  + ("or a trial setting (protocol.<field>, placement.mass_scale, placement.friction_scale)"
                     if model == "gripper" else ""))
    current = (getattr(protocol, key.partition(".")[2]) if key.startswith("protocol.")
               else (0, 0, 0) if key == "object.mesh_points"
               else placement.get(key.partition(".")[2], 1.0) if trial else get_dotted(base, key))
    want = int if isinstance(current, int) and not isinstance(current, bool) else (
        float if isinstance(current, float | tuple) else type(current))
    if key == "object.mesh_points":  # three whole numbers per value
        want = list
        if design == "latin_hypercube":
            raise err(key, "takes a list of [nx, ny, nz] values, not a latin_hypercube range")
    if design == "latin_hypercube":
        if not isinstance(spec, dict) or set(spec) != {"min", "max"}:
            raise err(key, "needs a range { min = ..., max = ... } for a latin_hypercube")
        values = [spec["min"], spec["max"]]
    else:
        if not isinstance(spec, list) or not spec:
            raise err(key, f"needs a non-empty list of values for a {design} study")
        values = spec
    for v in values:
        ok = isinstance(v, int | float) and not isinstance(v, bool) if want is float else isinstance(v, want)
        if not ok or (isinstance(v, float) and not math.isfinite(v)):
            raise err(key, f"expected {want.__name__} values, got {v!r}")
    if design == "latin_hypercube" and not values[0] < values[1]:
        raise err(key, f"min must be < max, got {values}")
    return [want(v) for v in values] if design != "latin_hypercube" else {"min": values[0], "max": values[1]}


def _read_responses(responses: dict, model: str, base: GripperParams | ActuatorDesign, vary: dict,
                    err: _Error) -> dict:
    """The [responses] table, each response and option checked against the model and its drives."""
    if not responses:
        raise err("responses", f"give at least one response; allowed: {', '.join(MODEL_RESPONSES[model])}")
    kinds = ({base.actuation.kind, *vary.get("actuation.kind", ())} if isinstance(base, GripperParams)
             else set())
    for name, opts in responses.items():
        lacking = sorted(k for k in kinds if name not in drive_class(k).responses)
        if lacking and name in MODEL_RESPONSES[model]:
            raise err("responses." + name, f"the {', '.join(lacking)} gripper's drive has no such response; "
                      f"it measures {', '.join(drive_class(lacking[0]).responses)}")
        if name not in MODEL_RESPONSES[model]:
            raise err("responses." + name, f"unknown response for a {model} study; allowed: "
                                           f"{', '.join(MODEL_RESPONSES[model])}")
        if not isinstance(opts, dict):
            raise err("responses." + name, "must be a table, e.g. { r_max = 0.45 }")
        for k, v in opts.items():
            _check_response_option(name, k, v, err)
    _check_response_grids(responses, err)
    return responses


def _check_response_option(name: str, k: str, v, err: _Error) -> None:
    """Option ``k = v`` of response ``name``: known, of its type and within its limit."""
    typ = RESPONSES[name].get(k)
    if typ is None:
        raise err("responses." + name, f"unknown option {k!r}; allowed: {', '.join(RESPONSES[name])}")
    if typ is float and not (isinstance(v, int | float) and not isinstance(v, bool) and v > 0):
        raise err("responses." + name, f"{k} must be a number > 0, got {v!r}")
    if typ is int and not (isinstance(v, int) and not isinstance(v, bool) and v >= 1):
        raise err("responses." + name, f"{k} must be an integer >= 1, got {v!r}")
    if name in RESPONSE_LIMITS and k in RESPONSE_LIMITS[name] and v > RESPONSE_LIMITS[name][k]:
        raise err("responses." + name, f"{k} must be at most {RESPONSE_LIMITS[name][k]:g}, got {v!r}")
    if typ is str and v not in SHAPES:
        raise err("responses." + name, f"{k} must be one of {', '.join(SHAPES)}, got {v!r}")
    if typ is list and name == "parts":
        from gripper.objects.everyday_parts import PARTS
        if not (isinstance(v, list) and v and all(isinstance(x, str) and x in PARTS for x in v)):
            raise err("responses." + name, f"{k} must be a non-empty list of {', '.join(PARTS)}, got {v!r}")
    elif typ is list and name == "payload":
        if not (isinstance(v, list) and v and all(isinstance(x, int | float) and not isinstance(x, bool)
                                                  and x > 0 for x in v)):
            raise err("responses." + name, f"{k} must be a non-empty list of masses > 0 kg, got {v!r}")
    elif typ is list and name == "envelope":
        ok = isinstance(v, list) and bool(v) and (
            all(s in SHAPES for s in v) if k == "shapes" else
            all(isinstance(x, int | float) and not isinstance(x, bool) and 0 < x <= 0.3 for x in v))
        if not ok:
            allowed = f"shapes of {', '.join(SHAPES)}" if k == "shapes" else "widths in (0, 0.3] m"
            raise err("responses." + name, f"{k} must be a non-empty list of {allowed}, got {v!r}")
    elif typ is list:
        from gripper.objects.library import get_object
        if not isinstance(v, list) or not v:
            raise err("responses." + name, f"{k} must be a non-empty list of object names")
        for o in v:
            try:
                get_object(o)
            except ValueError as e:
                raise err("responses." + name, str(e)) from None


def _check_response_grids(responses: dict, err: _Error) -> None:
    """The envelope's and the payload's objects, built once each way, so a point cannot fail on one."""
    from gripper.objects.envelope_objects import check_envelope_points

    grids = {}
    if "envelope" in responses:
        opts = responses["envelope"]
        grids["envelope"] = (opts.get("shapes", list(SHAPES)), opts.get("sizes", [0.03]),
                             [opts.get("mass", 0.05)], [opts.get("friction", 0.6)])
    if "payload" in responses:
        opts = responses["payload"]
        grids["payload"] = ([opts.get("shape", "box")], [opts.get("size", 0.06)],
                            opts.get("masses", [0.2, 0.5, 1.0]), [opts.get("friction", 0.6)])
    for name, grid in grids.items():
        try:
            check_envelope_points(*grid)
        except ValueError as e:
            raise err(f"responses.{name}", str(e)) from None


def _read_objective(obj: dict, responses: dict, err: _Error) -> tuple[tuple[str, str] | None, dict]:
    """(objective, limits) of the [objective] table ``obj`` (a copy, emptied as it is read)."""
    objective = None
    limits: dict = {}
    for bound in ("at_least", "at_most"):
        table = obj.pop(bound, {})
        if not isinstance(table, dict):
            raise err(bound, "must be a table of metric = number, e.g. { grasp_block_success_rate = 1.0 }")
        for k, v in table.items():
            if k not in metric_names(responses) or not (isinstance(v, int | float) and not isinstance(v, bool)):
                raise err(bound, f"{k} = {v!r}: need a metric of the responses ({', '.join(metric_names(responses))}) "
                                 "and a number")
            limits[(bound, k)] = float(v)
    if obj:
        if len(obj) != 1 or next(iter(obj)) not in ("maximize", "minimize"):
            raise err("objective", "give exactly one of maximize = \"...\" or minimize = \"...\"")
        sense, metric = next(iter(obj.items()))
        objective = (sense, str(metric))
    return objective, limits


def _check_size(design: str, vary: dict, points: int, responses: dict, err: _Error) -> None:
    """Refuse a study of more than POINTS_MAX design points or TRIALS_MAX trials."""
    n_points = _count_points(design, vary, points)
    if n_points > POINTS_MAX:
        raise err("vary", f"{n_points:,} design points; at most {POINTS_MAX:,} (vary fewer parameters or values)")
    trials = n_points * _trials_per_point(responses)
    if trials > TRIALS_MAX:
        raise err("responses", f"{n_points:,} design points × {trials // n_points:,} trials = {trials:,} trials; at "
                  f"most {TRIALS_MAX:,} (a day of trials on one core)")


def _check_points_build(study: Study, responses: dict, err: _Error) -> None:
    """Build every design point before any work starts; the first that fails is refused, naming its key."""
    for pt in study.design_points():
        try:
            p, _ = apply_point(study.base, pt)
            proto, scales = study.trial_setup(pt)
            for k, v in scales.items():
                if k == "mesh_points":
                    _mesh_points(v, responses)
                else:
                    _scale(v, f"placement.{k}")
            if isinstance(p, GripperParams) and ("grasp" in responses or "holding_force" in responses):
                drive_for(p).check_set_point(proto)
        except ValueError as e:
            key = next(iter(pt)) if pt else "base"
            raise err(key, f"value {pt.get(key)!r} gives an invalid design ({e})") from None


def _count_points(design: str, vary: dict, points: int) -> int:
    """The design points a study has (point 0, the base, included), counted without listing them."""
    if design == "one_at_a_time":
        return 1 + sum(len(v) for v in vary.values())
    if design == "factorial":
        return 1 + math.prod(len(v) for v in vary.values())
    return 1 + points


def _trials_per_point(responses: dict) -> int:
    """Grasp trials one design point runs (the default trial count where a response leaves it out)."""
    from gripper.bench.defaults import DEFAULT_TRIALS

    n = 0
    for name in ("grasp", "holding_force"):
        if name in responses:
            opts = responses[name]
            n += len(opts.get("objects", ["block"])) * opts.get("trials", DEFAULT_TRIALS)
    if "envelope" in responses:
        opts = responses["envelope"]
        n += len(opts.get("shapes", SHAPES)) * len(opts.get("sizes", [0] * 8)) * opts.get("trials", 3)
    if "payload" in responses:
        opts = responses["payload"]
        n += len(opts.get("masses", [0] * 3)) * opts.get("trials", 3)
    if "parts" in responses:
        from gripper.objects.everyday_parts import PARTS

        opts = responses["parts"]
        n += len(opts.get("parts", PARTS)) * opts.get("trials", 5)
    return max(n, 1)


def _mesh_points(value, responses: dict) -> tuple[int, int, int]:
    """``object.mesh_points`` on every deformable object of the responses (raises naming it)."""
    from gripper.objects.library import get_object

    pts = tuple(value) if isinstance(value, list | tuple) else value
    meshed = 0
    for name in ("grasp", "holding_force"):
        for spec in responses.get(name, {}).get("objects", ["block"]):
            obj = get_object(spec)
            if obj.is_flex:
                dataclasses.replace(obj, mesh_points=pts).validate()
                meshed += 1
    if not meshed:
        deformable = ", ".join(k.name for k in registered_kinds().values() if k.deformable)
        raise ValueError(f"object.mesh_points: the responses grasp no deformable object (a {deformable}) "
                         "whose mesh it could set")
    return pts


def _scale(value, key: str = "placement") -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not (math.isfinite(value) and value > 0):
        raise ValueError(f"{key}: a scale must be a number > 0, got {value!r}")
    return float(value)


def metric_names(responses: dict) -> list[str]:
    names = []
    if "bending" in responses:
        names += ["bending_angle_max_deg", "bending_angle_at_half_r_deg", "tension_at_r_max_N"]
    if "tension_for_angle" in responses:
        names += ["tension_for_angle_N"]
    if "blocked_force" in responses:
        names += ["blocked_tip_force_N"]
    if "inflation" in responses:
        names += ["bending_angle_at_max_deg", "bending_angle_at_half_deg"]
    if "grasp" in responses:
        from gripper.objects.library import get_object

        for o in responses["grasp"].get("objects", ["block"]):
            name = get_object(o).name  # an object file's own name, not its path
            names += [f"grasp_{name}_success_rate", f"grasp_{name}_median_peak_force_N"]
    if "envelope" in responses:
        for shape in responses["envelope"].get("shapes", list(SHAPES)):
            names += [f"envelope_{shape}_smallest_m", f"envelope_{shape}_largest_m"]
        names += ["envelope_range_m"]
    if "payload" in responses:
        from gripper.experiments.design_responses import payload_metric

        names += [payload_metric(responses["payload"])]
    if "parts" in responses:
        from gripper.objects.everyday_parts import PARTS

        names += [f"part_{name}_success_rate" for name in responses["parts"].get("parts", list(PARTS))]
    if "holding_force" in responses:
        from gripper.objects.library import get_object

        for o in responses["holding_force"].get("objects", ["block"]):
            names += [f"holding_{get_object(o).name}_median_force_N"]
    return names
