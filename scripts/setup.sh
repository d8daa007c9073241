#!/usr/bin/env bash
# Create .venv (if missing) and install the package with its dev extras. Idempotent and quiet:
# pip's output is shown only if the install fails.
set -euo pipefail
cd "$(dirname "$0")/.."
PY="${PYTHON:-python3}"
if [ ! -x .venv/bin/python ]; then "$PY" -m venv .venv; fi
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
if ! { .venv/bin/python -m pip install --quiet --upgrade pip && \
       .venv/bin/python -m pip install --quiet -e ".[dev]"; } >"$log" 2>&1; then
  cat "$log" >&2
  echo "setup: installing the package into .venv failed (pip's output above)" >&2
  exit 1
fi
# mediapy (the package's video reader and writer) looks for an `ffmpeg` program on PATH; the
# environment's own is imageio-ffmpeg's binary. Link it into .venv/bin, so an activated
# environment reads and writes video with no system ffmpeg (`import gripper` also points
# mediapy at it: gripper.render.backend).
if [ ! -e .venv/bin/ffmpeg ]; then  # missing, or a link left dangling by an upgrade
  ln -sf "$(.venv/bin/python -c 'import imageio_ffmpeg; print(imageio_ffmpeg.get_ffmpeg_exe())')" .venv/bin/ffmpeg
fi
# ... and the environment's interpreter puts its own bin/ on PATH when it starts (a one-line
# .pth file: Python runs it at start-up), so `.venv/bin/python -c "import mediapy; ..."` finds
# that ffmpeg without activation too.
site="$(.venv/bin/python -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"
if [ ! -e "$site/gripper_venv_bin.pth" ]; then
  echo 'import os, sys; b = os.path.dirname(sys.executable); p = os.environ.get("PATH", ""); os.environ["PATH"] = p if b in p.split(os.pathsep) else b + os.pathsep + p' > "$site/gripper_venv_bin.pth"
fi
