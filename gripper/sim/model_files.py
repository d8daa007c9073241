"""The committed MJCF, in MuJoCo Menagerie's layout: ``models/soft_gripper/``.

The files are the model the trials and the environment run, not an export of it:

- ``soft_gripper.xml``: the gripper on its lift stage as a trial steps it: the ``discrete``
  integrator at the trials' 2 ms step, each hinge's closed-cut limit matched to the design under
  that integrator (:mod:`gripper.model.closure`), default classes (``soft_gripper`` with
  ``visual``, ``collision``, ``hinge``, ``pad``, ``servo``) and named materials;
- ``scene.xml``: ``<include file="soft_gripper.xml"/>`` plus the floor, light and cameras. Trials
  add their object to this scene (``gripper.sim.scene``); a test compiles both and compares them;
- ``README.md``: its parameter table between ``<!-- params:start -->`` and ``<!-- params:end -->``
  is generated here too.

``gripper write-models`` writes them into the checkout's ``models/soft_gripper/`` or a folder the
user names, never into an installed package.

Example:
    >>> from gripper.sim.model_files import generate_model_files
    >>> sorted(generate_model_files())
    ['scene.xml', 'soft_gripper.xml']
"""

from __future__ import annotations

from pathlib import Path

import mujoco

from gripper.core.atomic import write_text_atomic
from gripper.core.params import GripperParams, parameter_rows
from gripper.core.resources import MODEL_DIR, checkout_models_dir
from gripper.model.builders import MODEL_NAME, add_scene_dressing
from gripper.model.closure import teeth_closure_stiffness
from gripper.sim.scene import trial_gripper_spec, trial_params

START, END = "<!-- params:start -->", "<!-- params:end -->"
GRIPPER_FILE, SCENE_FILE = f"{MODEL_NAME}.xml", "scene.xml"


def default_model_dir() -> Path | None:
    """Where ``write-models`` writes without ``--out``: the checkout's ``models/soft_gripper``, or
    None in an installed package (its copy is read-only by intent)."""
    top = checkout_models_dir()
    return top / MODEL_NAME if top is not None else None


def scene_xml() -> str:
    """``scene.xml``: the gripper file included, then the floor, light and cameras."""
    dressing = mujoco.MjSpec()
    dressing.modelname = f"{MODEL_NAME} scene"
    add_scene_dressing(dressing)
    head, sep, rest = dressing.to_xml().partition(">\n")
    return f'{head}{sep}  <include file="{GRIPPER_FILE}"/>\n\n{rest}'


def generate_model_files(params: GripperParams | None = None) -> dict[str, str]:
    """The XML texts, by file name, for ``params`` (defaults if None) at the trials' step."""
    p = trial_params(params or GripperParams())
    return {GRIPPER_FILE: trial_gripper_spec(p).to_xml(), SCENE_FILE: scene_xml()}


def parameter_table(params: GripperParams | None = None) -> str:
    """Markdown table of every parameter: value, unit, allowed range and source, all from the
    fields' metadata (:func:`gripper.core.params.parameter_rows`)."""
    p = params or GripperParams()
    lines = ["| section | field | value | unit | allowed | source |", "|---|---|---|---|---|---|"]
    for section, key, value, spec in parameter_rows(p):
        shown = list(value) if isinstance(value, tuple) else value
        lines.append(f"| {section} | {key} | {shown} | {spec.unit} | {spec.allowed()} | {spec.source} |")
    derived = [
        ("finger", "closure_angle_deg", f"{p.finger.closure_angle_deg:.2f}", "deg"),
        ("springs", "closed-cut stiffness (teeth estimate)",
         f"{teeth_closure_stiffness(p.finger, p.material):.3g}", "N·m/rad"),
        ("finger", "length", f"{p.finger.length:g}", "m"),
        ("cable", "axial_stiffness (EA)", f"{p.cable.axial_stiffness:.4g}", "N"),
        ("servo", "max_cable_tension", f"{p.servo.max_cable_tension:.4g}", "N"),
    ]
    lines += [f"| {s} (derived) | {k} | {v} | {u} | | |" for s, k, v, u in derived]
    return "\n".join(lines)


def readme_with_table(text: str, params: GripperParams | None = None) -> str:
    """``text`` with the parameter table between the markers replaced."""
    if START not in text or END not in text:
        raise ValueError(f"model README: markers {START} / {END} missing")
    head, rest = text.split(START, 1)
    _, tail = rest.split(END, 1)
    return f"{head}{START}\n{parameter_table(params)}\n{END}{tail}"


def write_model_files(out_dir: str | Path | None = None, params: GripperParams | None = None) -> list[Path]:
    """Write the XML files (and refresh the README table if a README is there) into ``out_dir``
    (default: :func:`default_model_dir`), each atomically.

    Raises:
        ValueError: no ``out_dir`` outside a source checkout.
    """
    target = out_dir if out_dir is not None else default_model_dir()
    if target is None:
        raise ValueError(f"--out: give a folder; the installed package's models ({MODEL_DIR}) are "
                         "not written to")
    out = Path(target)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name, text in generate_model_files(params).items():
        written.append(write_text_atomic(out / name, text))
    readme = out / "README.md"
    if readme.exists():
        written.append(write_text_atomic(readme, readme_with_table(readme.read_text(), params)))
    return written


__all__ = ["default_model_dir", "generate_model_files", "parameter_table", "readme_with_table", "scene_xml",
           "write_model_files"]
