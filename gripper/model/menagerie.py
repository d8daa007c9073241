"""Write the committed MJCF in MuJoCo Menagerie layout: ``gripper/data/soft_gripper/``.

Files: ``soft_gripper.xml`` (the gripper on its lift stage), ``scene.xml`` (the same with
floor, lights, cameras and a test block, self-contained) and the parameter table inside
``README.md`` between ``<!-- params:start -->`` and ``<!-- params:end -->``.

Example:
    >>> from gripper.model.menagerie import generate_model_files
    >>> sorted(generate_model_files())
    ['scene.xml', 'soft_gripper.xml']
"""

from __future__ import annotations

from pathlib import Path

from gripper.core.params import GripperParams, parameter_rows
from gripper.core.resources import MODEL_DIR
from gripper.model.builders import build_gripper_spec, build_scene_spec
from gripper.model.closure import teeth_closure_stiffness

REPO_MODELS = MODEL_DIR
START, END = "<!-- params:start -->", "<!-- params:end -->"

def generate_model_files(params: GripperParams | None = None) -> dict[str, str]:
    """The XML texts, by file name, generated from ``params`` (defaults if None)."""
    p = params or GripperParams()
    return {
        "soft_gripper.xml": build_gripper_spec(p).to_xml(),
        "scene.xml": build_scene_spec(p).to_xml(),
    }


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


def write_model_files(out_dir: str | Path = REPO_MODELS,
                      params: GripperParams | None = None) -> list[Path]:
    """Write the XML files (and refresh the README table if a README is there)."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name, text in generate_model_files(params).items():
        path = out / name
        path.write_text(text)
        written.append(path)
    readme = out / "README.md"
    if readme.exists():
        readme.write_text(readme_with_table(readme.read_text(), params))
        written.append(readme)
    return written


__all__ = ["generate_model_files", "write_model_files", "parameter_table", "readme_with_table"]
