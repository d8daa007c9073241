"""The committed MJCF of every shipped gripper, in MuJoCo Menagerie's layout: ``models/<name>/``
(``soft_gripper``: the cable gripper; ``pneumatic_gripper``: paper 001's actuators), the name
being the drive's ``model_name``.

The files are the model the trials and the environment run, not an export of it:

- ``<name>.xml``: the gripper on its lift stage as a trial steps it: the ``discrete`` integrator
  at the trials' 2 ms step, what the drive matches to that integrator (the cable finger's
  closed-cut limits: :mod:`gripper.drives.cable.closure`), default classes (``<name>`` with
  ``visual``, ``collision``, ``hinge``, ``pad`` and the drive's own) and named materials;
- ``scene.xml``: ``<include file="<name>.xml"/>`` plus the floor, light and cameras. Trials
  add their object to this scene (``gripper.sim.scene``); a test compiles both and compares them;
- ``README.md``: its parameter table between ``<!-- params:start -->`` and ``<!-- params:end -->``
  is generated here too (the drive's sections and derived figures); its picture,
  ``<name>.png``, by ``gripper write-models --picture`` (``gripper.render.model_picture``).

``gripper write-models`` writes them into the checkout's ``models/<name>/`` or a folder the
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
from gripper.core.resources import MODELS_DIR, checkout_models_dir
from gripper.drives import drive_for
from gripper.drives.drive import SHIPPED_DRIVES
from gripper.model.builders import add_scene_dressing
from gripper.sim.scene import trial_gripper_spec, trial_params

START, END = "<!-- params:start -->", "<!-- params:end -->"
SCENE_FILE = "scene.xml"


def shipped_grippers() -> dict[str, GripperParams]:
    """The grippers ``models/`` holds, by model name: each drive's default design."""
    out = {}
    for kind in SHIPPED_DRIVES:
        p = GripperParams()
        p = p.replace(actuation=p.actuation.replace(kind=kind)).validate()
        out[drive_for(p).model_name] = p
    return out


def gripper_file(params: GripperParams | None = None) -> str:
    """The gripper's own MJCF file name, ``<model name>.xml``."""
    return f"{drive_for(params or GripperParams()).model_name}.xml"


def model_dir(params: GripperParams | None = None, top: Path | None = MODELS_DIR) -> Path | None:
    """The gripper's folder under ``top`` (default: the package's ``models/``)."""
    return top / drive_for(params or GripperParams()).model_name if top is not None else None


def default_model_dir(params: GripperParams | None = None) -> Path | None:
    """Where ``write-models`` writes without ``--out``: the checkout's ``models/<name>``, or
    None in an installed package (its copy is read-only by intent)."""
    return model_dir(params, checkout_models_dir())


def scene_xml(params: GripperParams | None = None) -> str:
    """``scene.xml``: the gripper file included, then the floor, light and cameras."""
    dressing = mujoco.MjSpec()
    dressing.modelname = f"{drive_for(params or GripperParams()).model_name} scene"
    add_scene_dressing(dressing)
    head, sep, rest = dressing.to_xml().partition(">\n")
    return f'{head}{sep}  <include file="{gripper_file(params)}"/>\n\n{rest}'


def generate_model_files(params: GripperParams | None = None) -> dict[str, str]:
    """The XML texts, by file name, for ``params`` (defaults if None) at the trials' step."""
    p = trial_params(params or GripperParams())
    return {gripper_file(p): trial_gripper_spec(p).to_xml(), SCENE_FILE: scene_xml(p)}


def parameter_table(params: GripperParams | None = None) -> str:
    """Markdown table of the drive's parameter sections: value, unit, allowed range and source,
    all from the fields' metadata (:func:`gripper.core.params.parameter_rows`), then the
    drive's derived figures."""
    p = params or GripperParams()
    drive = drive_for(p)
    lines = ["| section | field | value | unit | allowed | source |", "|---|---|---|---|---|---|"]
    for section, key, value, spec in parameter_rows(p):
        if section not in drive.sections:
            continue
        shown = list(value) if isinstance(value, tuple) else value
        lines.append(f"| {section} | {key} | {shown} | {spec.unit} | {spec.allowed()} | {spec.source} |")
    lines += [f"| {s} (derived) | {k} | {v} | {u} | | |" for s, k, v, u in drive.derived_parameters()]
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
    target = out_dir if out_dir is not None else default_model_dir(params)
    if target is None:
        raise ValueError(f"--out: give a folder; the installed package's models ({MODELS_DIR}) are "
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


__all__ = ["SCENE_FILE", "default_model_dir", "generate_model_files", "gripper_file", "model_dir", "parameter_table",
           "readme_with_table", "scene_xml", "shipped_grippers", "write_model_files"]
