"""The package's architecture: layers (import-linter), no imports of the package root or of
another module's private names, and a lazy package root."""

from __future__ import annotations

import ast
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "gripper"
LINT_IMPORTS = Path(sys.executable).with_name("lint-imports")


def _modules():
    return [p for p in PACKAGE.rglob("*.py") if p != PACKAGE / "__init__.py"]


def _imports(path: Path):
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            yield node.module, [a.name for a in node.names]
        elif isinstance(node, ast.Import):
            for a in node.names:
                yield a.name, []


def test_no_module_imports_the_package_root():
    bad = [f"{p.relative_to(ROOT)}: {mod}" for p in _modules() for mod, names in _imports(p)
           if mod == "gripper"]
    assert not bad, bad


def test_no_private_name_crosses_modules():
    bad = [f"{p.relative_to(ROOT)}: {mod}.{n}" for p in _modules() for mod, names in _imports(p)
           if mod.startswith("gripper.") for n in names if n.startswith("_")]
    assert not bad, bad


def test_import_gripper_is_lazy():
    code = ("import sys, gripper; heavy = [m for m in ('mujoco', 'scipy', 'dask', 'matplotlib') "
            "if m in sys.modules]; print(heavy); assert not heavy; gripper.GripperParams; "
            "print(gripper.__version__)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr


@pytest.mark.skipif(not LINT_IMPORTS.exists(), reason="import-linter not installed")
def test_an_upward_import_breaks_the_layers_contract(tmp_path):
    """The contract can fail: the package copied with core importing the command line."""
    shutil.copytree(PACKAGE, tmp_path / "gripper", ignore=shutil.ignore_patterns("data", "__pycache__"))
    shutil.copy(ROOT / ".importlinter", tmp_path / ".importlinter")
    units = tmp_path / "gripper" / "core" / "units.py"
    units.write_text(units.read_text() + "\nimport gripper.cli.main  # noqa\n")
    env = {"PYTHONPATH": str(tmp_path), "PATH": str(LINT_IMPORTS.parent)}
    out = subprocess.run([str(LINT_IMPORTS), "--no-cache"], cwd=tmp_path, env=env,
                         capture_output=True, text=True)
    assert out.returncode != 0, out.stdout
    assert "gripper.core.units -> gripper.cli.main" in out.stdout, out.stdout


def test_environment_id_follows_its_version_history():
    """Gymnasium's rule: a new -vN whenever the dynamics change; the docstring's history ends
    with the registered version."""
    import re

    from gripper.envs.grasp_env import SoftGripperGraspEnv
    from gripper.envs.registration import ENV_ID

    history = (SoftGripperGraspEnv.__doc__ or "").split("## Version history", 1)[1].split("Example:")[0]
    versions = re.findall(r"^\s*- (v\d+)", history, flags=re.M)
    assert versions, "no version history in the environment's docstring"
    assert ENV_ID.endswith("-" + versions[-1]), (ENV_ID, versions[-1])


def test_the_committed_models_are_package_data():
    from gripper.core.resources import DATA_DIR, DEFAULT_CALIBRATION_DIR, MODELS_DIR, STUDIES_DIR

    assert DATA_DIR.is_relative_to(PACKAGE)
    for path in (MODELS_DIR / "soft_gripper" / "soft_gripper.xml", MODELS_DIR / "pneumatic_gripper" / "scene.xml",
                 DEFAULT_CALIBRATION_DIR / "calibration.json",
                 STUDIES_DIR / "one_at_a_time.toml", ROOT / "models" / "soft_gripper" / "scene.xml"):
        assert path.is_file(), path
    assert (PACKAGE / "models").resolve() == (ROOT / "models").resolve()  # one copy: the top-level one
    assert not list((ROOT / "models" / "soft_gripper").glob("calibration*"))  # lives with the calibration
    pyproject = (ROOT / "pyproject.toml").read_text()
    assert '"data/**/*"' in pyproject and '"models/**/*"' in pyproject, "the wheel must ship both"


def test_importing_the_package_reads_no_data_file():
    """Every module imports without opening a data file (the calibrations, object files and
    studies are read when first needed): importing stays quick and never fails on a data file."""
    import subprocess
    import sys

    code = """
import builtins, io, importlib, pathlib, pkgutil
opened = []
def spy(orig):
    def wrapped(file, *a, **k):
        opened.append(str(file))
        return orig(file, *a, **k)
    return wrapped
builtins.open = spy(builtins.open)
io.open = builtins.open
pathlib.Path.read_text = (lambda orig: lambda self, *a, **k: (opened.append(str(self)), orig(self, *a, **k))[1])(
    pathlib.Path.read_text)
pathlib.Path.read_bytes = (lambda orig: lambda self, *a, **k: (opened.append(str(self)), orig(self, *a, **k))[1])(
    pathlib.Path.read_bytes)
import gripper
for m in pkgutil.walk_packages(gripper.__path__, "gripper."):
    if not m.name.startswith(("gripper.rl", "gripper.envs.sb3")):  # the rl extra's modules
        importlib.import_module(m.name)
print("\\n".join(f for f in opened if "/gripper/" in f and "dist-info" not in f and not f.endswith(".py")))
"""
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "", done.stdout


def test_no_module_imports_itself_through_others():
    """No import cycle between the package's modules, function-level imports included (the
    layers contract checks the arrows between layers; this, the modules within one)."""
    import grimp

    graph = grimp.build_graph("gripper")
    imports = {m: graph.find_modules_directly_imported_by(m) for m in graph.modules}
    state: dict[str, int] = {}  # 1: on the path, 2: done
    cycles = []

    def visit(module: str, path: list[str]) -> None:
        state[module] = 1
        path.append(module)
        for other in sorted(imports[module]):
            if state.get(other) == 1:
                cycles.append(" -> ".join(path[path.index(other):] + [other]))
            elif other not in state:
                visit(other, path)
        path.pop()
        state[module] = 2

    for module in sorted(imports):
        if module not in state:
            visit(module, [])
    assert not cycles, "\n".join(cycles)
