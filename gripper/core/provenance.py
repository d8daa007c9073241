"""Provenance of results: the versions of the packages that computed them."""

from __future__ import annotations

from functools import cache
from importlib.metadata import PackageNotFoundError, version


@cache
def package_version() -> str:
    """This package's version, from its installed metadata (``pyproject.toml``)."""
    try:
        return version("gripper")
    except PackageNotFoundError:  # a source tree on sys.path, not installed
        return "0+unknown"


def versions() -> dict[str, str]:
    """Versions of the packages that decide a result: MuJoCo, this package, NumPy."""
    import mujoco
    import numpy as np

    return {"mujoco": mujoco.__version__, "gripper": package_version(), "numpy": np.__version__}
