"""mkdocs hook: pages generated from the code at build time, so they cannot go stale.

- ``<!-- cli-reference -->``: every ``gripper`` subcommand's ``--help``, from the parser itself;
- ``<!-- trial-record-schema -->``: the trial record's JSON schema;
- ``<!-- protocol-table -->``: the grasp protocol's fields (unit, allowed, source) from their
  metadata;
- ``<!-- sensing-table -->``: the servo sensing model's fields, likewise;
- ``<!-- depth-camera-table -->``: the palm depth camera's fields, likewise;
- ``<!-- rl-hyperparams -->``: the RL baselines' hyper-parameters (``gripper.rl.hyperparams``);
- ``<!-- version -->``: the package's version;
- ``<!-- pneumatic-finger-table -->``, ``<!-- regulator-table -->``, ``<!-- pressure-sensing-table -->``,
  ``<!-- pneumatic-calibration -->``: the pneumatic gripper's fields, regulator datasheets, pressure
  sensing and committed calibration;
- ``<!-- env-arguments -->``: the environment's arguments (``EnvConfig``'s fields and the rest);
- ``<!-- actuator-table -->``: paper 001's actuator's parameters (``PneumaticActuator``);
- ``<!-- actuator-convergence -->``, ``<!-- actuator-check -->``, ``<!-- actuator-studies -->``: its
  finite-element model's measurements, from ``gripper/data/actuator/reference_results.json``
  (``scripts/actuator_reference.py`` regenerates it).

The API pages' examples drop their ``# doctest: +SKIP`` markers (they keep the examples that
run simulations out of a doctest run; a reader needs only the example).
"""

from __future__ import annotations

import json
import os
import re

CLI_COLUMNS = 80  # the widest code block the site's content column shows without a scroll bar


def _cli_reference() -> str:
    os.environ["COLUMNS"] = str(CLI_COLUMNS)  # argparse wraps to the terminal width: fix it
    from gripper.cli.main import build_parser

    parser = build_parser()
    out = ["```text", parser.format_help().rstrip(), "```"]
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    for name, p in sub.choices.items():  # type: ignore[attr-defined]
        out += [f"## gripper {name}", "", "```text", p.format_help().rstrip(), "```", ""]
    return "\n".join(out)


def _schema() -> str:
    from gripper.experiments.record import TrialRecord

    return "```json\n" + json.dumps(TrialRecord.json_schema(), indent=2) + "\n```"


def _fields_table(classes, number_format: str = "") -> str:
    """One Markdown row per declared field of each (dataclass, prefix): default, unit, allowed
    values and source."""
    from gripper.core.fields import field_specs

    lines = ["| field | default | unit | allowed | source |", "|---|---|---|---|---|"]
    for cls, prefix in classes:
        for name, spec in field_specs(cls).items():
            value = getattr(cls(), name)
            numeric = isinstance(value, int | float) and not isinstance(value, bool)
            shown = format(value, number_format) if numeric else value
            lines.append(f"| {prefix}.{name} | {shown} | {spec.unit} "
                         f"| {spec.allowed()} | {spec.source} |")
    return "\n".join(lines)


def _protocol_table() -> str:
    from gripper.experiments.protocol import GraspProtocol, TrialNoise

    return _fields_table(((GraspProtocol, "protocol"), (TrialNoise, "noise")))


def _sensing_table() -> str:
    from gripper.drives.cable.sensing import ServoSensing

    return _fields_table(((ServoSensing, "sensing"),), ".4g")


def _depth_camera_table() -> str:
    from gripper.sim.depth import DepthCamera

    return _fields_table(((DepthCamera, "depth"),), ".4g")


def _rl_hyperparams() -> str:
    from gripper.rl.hyperparams import (
        HER_SAMPLED_GOALS,
        PPO_HYPERPARAMS,
        RECOMMENDED,
        SAC_HYPERPARAMS,
        TQC_HYPERPARAMS,
    )

    recipe = {**PPO_HYPERPARAMS, **RECOMMENDED["hyperparams"]}
    lines = ["| hyper-parameter | PPO | PPO, recommended recipe (`--recommended`) | SAC | TQC (+ HER with `--goal`) |",
             "|---|---|---|---|---|"]
    for k in dict.fromkeys([*PPO_HYPERPARAMS, *SAC_HYPERPARAMS, *TQC_HYPERPARAMS]):
        lines.append(f"| {k} | {PPO_HYPERPARAMS.get(k, '')} | {recipe.get(k, '')} | {SAC_HYPERPARAMS.get(k, '')} "
                     f"| {TQC_HYPERPARAMS.get(k, '')} |")
    lines.append(f"| demonstrations (`--demos`, `--demo-noise`) | 0 | {RECOMMENDED['demo_episodes']} episodes, "
                 f"DART noise {RECOMMENDED['demo_noise']} | 0 | none |")
    lines.append(f"| hindsight goals (with `--goal`) | | | {HER_SAMPLED_GOALS} per transition, \"future\" "
                 f"| {HER_SAMPLED_GOALS} per transition, \"future\" |")
    return "\n".join(lines)


def _env_arguments() -> str:
    """The environment's arguments: EnvConfig's declared fields, then the others."""
    from gripper.envs.config import DEFAULT_REWARD_WEIGHTS, EnvConfig
    from gripper.envs.grasp_env import RENDER_ARGUMENTS

    rows = [_fields_table(((EnvConfig, "env"),)).replace("| env.", "| ")]
    rows += ['| objects | ("block", "cylinder") | - | library names, object files or "a,b" | sampled per episode '
             "with the environment's generator; rigid objects are fastest |",
             f"| reward_weights | {DEFAULT_REWARD_WEIGHTS} | - | any of these keys, finite | overrides some dense "
             "reward weights |",
             "| params | GripperParams() | - | a GripperParams or a .toml/.json parameter file | the design |",
             "| actuation | None | - | cable or pneumatic | the fingers, overriding params' (the pneumatic "
             "gripper's observation and action: below) |",
             "| calibration | None | - | a calibration JSON from gripper calibrate | its fitted hinge springs "
             "replace those of params |"]
    meaning = {"render_mode": "rgb_array, depth_array or human (needs a display)", "width": "image width [px]",
               "height": "image height [px]", "camera": "front, side, top, track (follows the palm) or palm"}
    rows += [f"| {k} | {v!r} | - | {meaning[k]} | the renderer's |" for k, v in RENDER_ARGUMENTS.items()]
    return "\n".join(rows)


def _actuator_table() -> str:
    from gripper.references.pneumatic_params import PneumaticActuator

    return _fields_table(((PneumaticActuator, "actuator"),))


def _pneumatic_finger_table() -> str:
    from gripper.core.params import Actuation, PneumaticFinger

    return _fields_table(((Actuation, "actuation"), (PneumaticFinger, "pneumatic")), ".4g")


def _regulator_table() -> str:
    from gripper.datasheets.regulator import REGULATOR_PRESETS

    lines = ["| preset | range [kPa] | supply max [kPa] | response time [s] | linearity [% F.S.] | "
             "monitor accuracy [% F.S.] | source |", "|---|---|---|---|---|---|---|"]
    for ds in REGULATOR_PRESETS.values():
        lines.append(f"| {ds.name} | {ds.pressure_min / 1e3:g}-{ds.pressure_max / 1e3:g} | {ds.supply_max / 1e3:g} | "
                     f"{ds.response_time:g} | {100 * ds.linearity:g} | {100 * ds.monitor_accuracy:g} | {ds.source} |")
    return "\n".join(lines)


def _pressure_sensing_table() -> str:
    from gripper.drives.pneumatic.sensing import PressureSensing

    return _fields_table(((PressureSensing, "pressure_sensing"),), ".4g")


def _pneumatic_calibration() -> str:
    """The committed pneumatic calibration: fitted values and the tip error per pressure."""
    from gripper.core.params import PNEUMATIC_CALIBRATION_FILE

    cal = json.loads(PNEUMATIC_CALIBRATION_FILE.read_text())
    m = cal["metrics"]
    held = {h["pressure_kPa"] for h in m["held_out"]}
    lines = ["| pressure [kPa] | tip error [% of length] |", "|---|---|"]
    for row in m["per_pressure"]:
        tag = " (held out)" if row["pressure_kPa"] in held else ""
        lines.append(f"| {row['pressure_kPa']:g}{tag} | {100 * row['tip_error_frac']:.2f} |")
    lines.append(f"| sag (lying, 0 kPa) | {100 * m['sag_tip_error_frac']:.2f} |")
    fitted = ", ".join(f"{k} = {v:.4g}" for k, v in cal["fitted"].items())
    return (f"Fitted ({m['n_segments']} segments, {m['fit_wall_time_s']:.1f} s): {fitted} (SI units). "
            f"Tip RMS over the fitted pressures {100 * m['tip_rms_frac']:.2f} % of the length.\n\n" + "\n".join(lines))


def _actuator_results() -> dict:
    from gripper.core.resources import DATA_DIR

    path = DATA_DIR / "actuator" / "reference_results.json"
    return json.loads(path.read_text()) if path.is_file() else {}


def _actuator_convergence() -> str:
    data = _actuator_results()
    if "richardson" not in data:
        return "*Not measured yet: run `scripts/actuator_reference.py convergence`.*"
    rows = ["| level | cells | unknowns | bending at 250 kPa [deg] | sweep time [s] |", "|---|---|---|---|---|"]
    for ratio, sw in sorted(data["sweeps"].items(), key=lambda kv: int(kv[0])):
        rows.append(f"| {ratio} | {sw['cells']} | {sw['unknowns']} | {sw['angle_deg'][-1]:.2f} | "
                    f"{sw['wall_time_s']:.0f} |")
    r = data["richardson"]
    gravity = data["sweeps"][str(r["studies_refinement"])]["angle_deg"][0]
    ratios = ", ".join(f"{x:.2f}" for x in r.get("cell_size_ratios", []))
    rows += ["", f"The bending (less gravity's {gravity:.1f}° at 0 kPa) extrapolated at each pressure "
                 f"(cell sizes relative to level 1: 1/({ratios})):", "",
             "| pressure [kPa] | " + " | ".join(f"level {k} [deg]" for k in r["refinements"])
             + " | order p | extrapolated [deg] | GCI finest | GCI studies' mesh |",
             "|---" * (len(r["refinements"]) + 5) + "|"]
    for row in r["by_pressure"]:
        angles = f"| {row['pressure_kPa']:g} | " + " | ".join(f"{a:.2f}" for a in row["angles_deg"])
        if row["order"] is None:
            rows.append(angles + " | oscillatory | - | - | "
                        f"**±{100 * row['uncertainty_studies_mesh']:.2f} %** (half the range) |")
            continue
        rows.append(angles + f" | {row['order']:.2f} | {row['extrapolated_deg']:.2f} | {100 * row['gci_fine']:.2f} % | "
                    f"**{100 * row['gci_studies_mesh']:.2f} %** |")
    return "\n".join(rows)


def _actuator_check() -> str:
    data = _actuator_results()
    if "semi_analytical" not in data:
        return "*Not measured yet: run `scripts/actuator_reference.py convergence`.*"
    sa = data["semi_analytical"]
    fe = data["sweeps"][str(data["richardson"]["studies_refinement"])]
    head = "| pressure [kPa] | " + " | ".join(f"{p:g}" for p in sa["pressure_kPa"]) + " |"
    rows = [head, "|---" * (len(sa["pressure_kPa"]) + 1) + "|",
            "| finite elements [deg] | " + " | ".join(f"{a:.1f}" for a in fe["angle_deg"]) + " |",
            "| semi-analytical [deg] | " + " | ".join(f"{a:.1f}" for a in sa["angle_deg"]) + " |",
            "| FE / semi-analytical | - | "
            + " | ".join(f"{f / a:.2f}" for f, a in zip(fe["angle_deg"][1:], sa["angle_deg"][1:], strict=True)) + " |"]
    return "\n".join(rows)


def _actuator_section() -> str:
    data = _actuator_results()
    if "section" not in data:
        return "*Not measured yet: run `scripts/actuator_reference.py section`.*"
    sec = data["section"]
    rows = ["| pressure [kPa] | duct area | duct height | pressure's lever (first moment) | "
            "finite elements [deg] | moment balance with that lever [deg] |", "|---|---|---|---|---|---|"]
    for i, p in enumerate(sec["pressure_kPa"]):
        if i == 0:
            continue
        rows.append(f"| {p:g} | ×{sec['area_ratio'][i]:.2f} | ×{sec['height_ratio'][i]:.2f} | "
                    f"×{sec['first_moment_ratio'][i]:.2f} | {sec['finite_element_deg'][i]:.1f} | "
                    f"{sec['semi_analytical_deformed_deg'][i]:.1f} |")
    return "\n".join(rows)


def _actuator_studies() -> str:
    data = _actuator_results()
    if "studies" not in data:
        return "*Not measured yet: run the five studies, then `scripts/actuator_reference.py studies runs/paper001_*`.*"
    rows = ["| case study | value | bending at 125 kPa [deg] | bending at 250 kPa [deg] | sweep time [s] |",
            "|---|---|---|---|---|"]
    times = []
    for case in data["studies"].values():
        for pt in sorted(case["points"], key=lambda p: next(iter(p["changes"].values()), case["base_value"])):
            value = next(iter(pt["changes"].values()), case["base_value"])
            shown = f"{value:g}°" if case["key"].endswith("_deg") else f"{value * 1e3:g} mm"
            base = "" if pt["changes"] else " (base)"
            if pt["status"] != "ok":
                rows.append(f"| {case['name']} | {shown}{base} | failed: {pt['error']} | | {pt['wall_time_s']:.0f} |")
                continue
            angles = pt["curve"]["bending_angle_deg"]
            rows.append(f"| {case['name']} | {shown}{base} | {angles[len(angles) // 2]:.1f} | {angles[-1]:.1f} | "
                        f"{pt['wall_time_s']:.0f} |")
            times.append(pt["wall_time_s"])
    if times:
        import statistics

        rows += ["", f"Per-design time (one full 0-250 kPa sweep, two worker processes on 2 cores): median "
                     f"**{statistics.median(times):.0f} s** over {len(times)} designs, "
                     f"range {min(times):.0f}-{max(times):.0f} s."]
    return "\n".join(rows)


def _version() -> str:
    from importlib.metadata import version

    return version("gripper")


MARKERS = {"<!-- rl-hyperparams -->": _rl_hyperparams, "<!-- version -->": _version,
           "<!-- env-arguments -->": _env_arguments, "<!-- actuator-table -->": _actuator_table,
           "<!-- cli-reference -->": _cli_reference, "<!-- trial-record-schema -->": _schema,
           "<!-- protocol-table -->": _protocol_table, "<!-- sensing-table -->": _sensing_table,
           "<!-- depth-camera-table -->": _depth_camera_table,
           "<!-- actuator-convergence -->": _actuator_convergence, "<!-- actuator-check -->": _actuator_check,
           "<!-- actuator-studies -->": _actuator_studies, "<!-- actuator-section -->": _actuator_section,
           "<!-- pneumatic-finger-table -->": _pneumatic_finger_table,
           "<!-- regulator-table -->": _regulator_table, "<!-- pressure-sensing-table -->": _pressure_sensing_table,
           "<!-- pneumatic-calibration -->": _pneumatic_calibration}


def on_page_markdown(markdown: str, **kwargs) -> str:
    for marker, make in MARKERS.items():
        if marker in markdown:
            markdown = markdown.replace(marker, make())
    return markdown


SKIP_MARKER = re.compile(r"\s*(?:<span[^>]*>)?#\s*doctest:\s*\+SKIP(?:</span>)?")


def on_page_content(html: str, **kwargs) -> str:
    return SKIP_MARKER.sub("", html)
