"""Every module's docstring example runs and prints what it shows (examples marked
``# doctest: +SKIP`` run simulations of minutes and are kept out; the docs site hides the mark)."""

from __future__ import annotations

import doctest
import importlib
import importlib.util
import pkgutil

import pytest

import gripper

NEEDS_RL = ("gripper.envs.sb3", "gripper.rl.")
MODULES = sorted(m.name for m in pkgutil.walk_packages(gripper.__path__, "gripper.")
                 if not m.name.startswith("gripper.models"))


@pytest.mark.parametrize("name", MODULES)
def test_the_docstring_examples_run(name, tmp_path, monkeypatch):
    if name.startswith(NEEDS_RL) and importlib.util.find_spec("stable_baselines3") is None:
        pytest.skip("needs the rl extra")
    monkeypatch.chdir(tmp_path)  # an example that writes a file writes it here
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS, report=True)
    assert result.failed == 0, f"{name}: {result.failed} of {result.attempted} examples failed"
