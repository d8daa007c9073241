"""Files shipped with the package (package data under ``gripper/data``), found the same way in a
source checkout and in an installed wheel.

Layout (MuJoCo Menagerie style for the model):

- ``soft_gripper/``: the committed MJCF (``soft_gripper.xml``, ``scene.xml``), its README and
  CHANGELOG, and the default design's calibration (``calibration.json`` and its report);
- ``studies/``: example study files and the committed stiffness surrogate;
- ``calibration/``: an example bench-data CSV for ``gripper calibrate --data``;
- ``objects/``: the built-in grasp objects' object files.
"""

from __future__ import annotations

from importlib.resources import files
from pathlib import Path

DATA_DIR = Path(str(files("gripper").joinpath("data")))
MODEL_DIR = DATA_DIR / "soft_gripper"
STUDIES_DIR = DATA_DIR / "studies"
CALIBRATION_EXAMPLES_DIR = DATA_DIR / "calibration"
OBJECTS_DIR = DATA_DIR / "objects"
