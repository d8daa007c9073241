"""Files shipped with the package, found the same way in a source checkout and in an installed
wheel.

- ``models/<name>/`` (the repository's top-level ``models/``, reached through the package's
  ``gripper/models`` link and carried inside the wheel): each shipped gripper's MJCF in MuJoCo
  Menagerie layout (``soft_gripper``: the cable gripper, ``pneumatic_gripper``): ``<name>.xml``,
  ``scene.xml`` (which includes it), README with a picture, CHANGELOG, LICENSE
  (:mod:`gripper.sim.model_files`);
- ``gripper/data/calibration/``: an example bench-data CSV for ``gripper calibrate --data``, and
  ``default/``, the default design's committed calibration (``calibration.json``, its
  reference run, convergence study, error table and report), and ``pneumatic/``, the default
  pneumatic finger's (fitted to paper 001's actuator in finite elements);
- ``gripper/data/studies/``: example study files and the committed stiffness surrogate;
- ``gripper/data/objects/``: the built-in grasp objects' object files.
"""

from __future__ import annotations

from importlib.resources import files
from pathlib import Path

PACKAGE_DIR = Path(str(files("gripper")))
DATA_DIR = PACKAGE_DIR / "data"
MODELS_DIR = PACKAGE_DIR / "models"
STUDIES_DIR = DATA_DIR / "studies"
CALIBRATION_EXAMPLES_DIR = DATA_DIR / "calibration"
DEFAULT_CALIBRATION_DIR = CALIBRATION_EXAMPLES_DIR / "default"
PNEUMATIC_CALIBRATION_DIR = CALIBRATION_EXAMPLES_DIR / "pneumatic"
OBJECTS_DIR = DATA_DIR / "objects"


def checkout_models_dir() -> Path | None:
    """The repository's top-level ``models/`` when the package runs from a source checkout (an
    editable install), else None: an installed wheel's copy is never written to."""
    if (PACKAGE_DIR / "models").is_symlink():
        return (PACKAGE_DIR / "models").resolve()
    return None
