"""The README, the docs site and the shipped example files against the code: the docs build as
the README writes it, and every version, default and command they state is the code's."""

from __future__ import annotations

import importlib.util
import re
import shlex
import subprocess
import tomllib
from importlib.metadata import version
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[1]
README = (ROOT / "README.md").read_text()
VERSION = version("gripper")


def test_docs_build_as_the_readme_writes_it():
    """The README's docs command, run exactly as written from the repository's root; mkdocs.yml
    sets ``strict``, so a broken link or a warning fails it."""
    found = re.findall(r"builds with `([^`]*mkdocs build[^`]*)`", README)
    assert len(found) == 1, found
    done = subprocess.run(shlex.split(found[0]), cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "strict: true" in (ROOT / "mkdocs.yml").read_text()


def test_versions_are_the_packages():
    assert tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"] == VERSION
    readme = re.findall(r"^Version (\d+\.\d+\.\d+)", README, flags=re.M)
    assert readme == [VERSION], readme
    changelog = re.findall(r"^## (\d+\.\d+\.\d+)", (ROOT / "CHANGELOG.md").read_text(), flags=re.M)
    assert changelog[0] == VERSION, changelog[:2]
    assert "This site describes gripper <!-- version -->." in (ROOT / "docs" / "index.md").read_text()
    site = ROOT / "site" / "index.html"
    if site.exists():  # built by the test above (same session) or by hand
        assert f"This site describes gripper {VERSION}." in site.read_text()


def test_readme_defaults_are_the_codes():
    from gripper.bench.defaults import DEFAULT_TRIALS
    from gripper.envs.registration import ENV_ID
    from gripper.experiments.protocol import GraspProtocol

    assert f"at {GraspProtocol().grip_tension:g} N per cable" in README
    assert f"at {GraspProtocol().grip_pressure / 1e3:g} kPa per chamber" in README
    assert f"{DEFAULT_TRIALS} trials on each default object" in README
    assert set(re.findall(r"SoftGripperGrasp-v\d+", README)) == {ENV_ID.split(":")[-1]}


def test_readme_commands_run_from_the_venv():
    """After the README's commands, ``gripper`` and ``pip`` are not on the PATH (nothing
    activates the venv): every command line the README shows names ``.venv/bin/`` or says to
    activate it first."""
    blocks = re.findall(r"```bash\n(.*?)```", README, flags=re.S)
    lines = [ln.split("#")[0].strip() for b in blocks for ln in b.splitlines()]
    bare = [ln for ln in lines if re.match(r"(gripper|pip|mkdocs|pytest)\b", ln)]
    assert not bare, bare


def _hook():
    spec = importlib.util.spec_from_file_location("generate", ROOT / "docs" / "hooks" / "generate.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_cli_reference_fits_the_page():
    hook = _hook()
    wide = [ln for ln in hook._cli_reference().splitlines() if len(ln) > hook.CLI_COLUMNS]
    assert not wide, wide


def test_api_examples_show_no_doctest_markers():
    hook = _hook()
    html = '<span class="n">x</span>  <span class="c1"># doctest: +SKIP</span>\n'
    assert hook.on_page_content(html) == '<span class="n">x</span>\n'


@pytest.mark.parametrize("name", ["one_at_a_time", "latin_hypercube"])
def test_shipped_studies_state_the_defaults(name):
    """A shipped study's ``# default X unit`` comments are the code's defaults, and each sweep
    reaches to within 20 % of the default (one-sided where the default is at the stiffness
    surrogate's edge)."""
    from gripper.core.params import GripperParams

    text = (ROOT / "gripper" / "data" / "studies" / f"{name}.toml").read_text()
    p = GripperParams()
    scale = {"mm": 1e-3, "deg": 1.0, "A": 1.0, "": 1.0}
    for key, value, unit in re.findall(r'^"([\w.]+)" = .*# default ([\d.]+) ?(mm|deg|A|)\b', text, flags=re.M):
        section, field = key.split(".")
        default = getattr(getattr(p, section), field)
        assert float(value) * scale[unit] == pytest.approx(default), (key, value, unit, default)
    vary = tomllib.loads(text)["vary"]
    for key, spec in vary.items():
        section, field = key.split(".")
        default = getattr(getattr(p, section), field)
        values = [spec["min"], spec["max"]] if isinstance(spec, dict) else spec
        assert min(values) <= 1.2 * default and max(values) >= 0.8 * default, (key, values, default)
