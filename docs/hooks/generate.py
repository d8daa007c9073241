"""mkdocs hook: pages generated from the code at build time, so they cannot go stale.

- ``<!-- cli-reference -->``: every ``gripper`` subcommand's ``--help``, from the parser itself;
- ``<!-- trial-record-schema -->``: the trial record's JSON schema;
- ``<!-- protocol-table -->``: the grasp protocol's fields (unit, allowed, source) from their
  metadata;
- ``<!-- sensing-table -->``: the servo sensing model's fields, likewise;
- ``<!-- depth-camera-table -->``: the palm depth camera's fields, likewise;
- ``<!-- rl-hyperparams -->``: the RL baselines' hyper-parameters (``gripper.rl.hyperparams``);
- ``<!-- version -->``: the package's version;
- ``<!-- env-arguments -->``: the environment's arguments (``EnvConfig``'s fields and the rest);
- ``<!-- actuator-table -->``: paper 001's actuator's parameters (``PneumaticActuator``).

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
            lines.append(f"| {prefix}.{name} | {getattr(cls(), name):{number_format}} | {spec.unit} "
                         f"| {spec.allowed()} | {spec.source} |")
    return "\n".join(lines)


def _protocol_table() -> str:
    from gripper.experiments.protocol import GraspProtocol, TrialNoise

    return _fields_table(((GraspProtocol, "protocol"), (TrialNoise, "noise")))


def _sensing_table() -> str:
    from gripper.servo.sensing import ServoSensing

    return _fields_table(((ServoSensing, "sensing"),), ".4g")


def _depth_camera_table() -> str:
    from gripper.sim.depth import DepthCamera

    return _fields_table(((DepthCamera, "depth"),), ".4g")


def _rl_hyperparams() -> str:
    from gripper.rl.hyperparams import PPO_HYPERPARAMS, SAC_HYPERPARAMS

    lines = ["| hyper-parameter | PPO | SAC |", "|---|---|---|"]
    for k in dict.fromkeys([*PPO_HYPERPARAMS, *SAC_HYPERPARAMS]):
        lines.append(f"| {k} | {PPO_HYPERPARAMS.get(k, '')} | {SAC_HYPERPARAMS.get(k, '')} |")
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
             "| calibration | None | - | a calibration JSON from gripper calibrate | its fitted hinge springs "
             "replace those of params |"]
    meaning = {"render_mode": "rgb_array, depth_array or human (needs a display)", "width": "image width [px]",
               "height": "image height [px]", "camera": "front, side, top, track (follows the palm) or palm"}
    rows += [f"| {k} | {v!r} | - | {meaning[k]} | the renderer's |" for k, v in RENDER_ARGUMENTS.items()]
    return "\n".join(rows)


def _actuator_table() -> str:
    from gripper.references.pneumatic_params import PneumaticActuator

    return _fields_table(((PneumaticActuator, "actuator"),))


def _version() -> str:
    from importlib.metadata import version

    return version("gripper")


MARKERS = {"<!-- rl-hyperparams -->": _rl_hyperparams, "<!-- version -->": _version,
           "<!-- env-arguments -->": _env_arguments, "<!-- actuator-table -->": _actuator_table,
           "<!-- cli-reference -->": _cli_reference, "<!-- trial-record-schema -->": _schema,
           "<!-- protocol-table -->": _protocol_table, "<!-- sensing-table -->": _sensing_table,
           "<!-- depth-camera-table -->": _depth_camera_table}


def on_page_markdown(markdown: str, **kwargs) -> str:
    for marker, make in MARKERS.items():
        if marker in markdown:
            markdown = markdown.replace(marker, make())
    return markdown


SKIP_MARKER = re.compile(r"\s*(?:<span[^>]*>)?#\s*doctest:\s*\+SKIP(?:</span>)?")


def on_page_content(html: str, **kwargs) -> str:
    return SKIP_MARKER.sub("", html)
