"""Run a set-up function on a third-party module once it is imported, without importing it.

``import gripper`` must stay quick and must not load MuJoCo or mediapy (MuJoCo binds its OpenGL
backend at import, mediapy pulls in matplotlib), yet both need one setting from this package
whenever they are used: :func:`after_import` applies it now if the module is loaded, else right
after its first import, through a one-shot finder on ``sys.meta_path``.

Example:
    >>> from gripper.core.after_import import after_import
    >>> after_import("json", lambda m: None)  # json is loaded: runs at once
"""

from __future__ import annotations

import importlib.abc
import importlib.util
import sys
from collections.abc import Callable
from types import ModuleType


class _AfterImport(importlib.abc.MetaPathFinder):
    """Finds nothing itself: on the first import of ``name`` it lets the other finders find the
    module, then runs ``setup`` on it as soon as the module has been executed."""

    def __init__(self, name: str, setup: Callable[[ModuleType], object]):
        self.name, self.setup = name, setup

    def find_spec(self, fullname, path=None, target=None):
        if fullname != self.name:
            return None
        if self in sys.meta_path:
            sys.meta_path.remove(self)  # one shot, and no recursion through find_spec below
        spec = importlib.util.find_spec(fullname)
        loader = getattr(spec, "loader", None)
        if loader is None or not hasattr(loader, "exec_module"):
            return spec
        exec_module = loader.exec_module
        setup = self.setup

        def exec_and_setup(module):
            exec_module(module)
            setup(module)

        loader.exec_module = exec_and_setup  # this spec's own loader instance
        return spec


def after_import(name: str, setup: Callable[[ModuleType], object]) -> None:
    """Run ``setup(module)`` on top-level module ``name``: now if it is imported, else right after
    its first import (once per process and name)."""
    if name in sys.modules:
        setup(sys.modules[name])
    elif not any(isinstance(f, _AfterImport) and f.name == name for f in sys.meta_path):
        sys.meta_path.insert(0, _AfterImport(name, setup))
