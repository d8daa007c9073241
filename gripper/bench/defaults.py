"""Defaults of a benchmark run that the API and the command line share (standard library only,
so that ``gripper --help`` stays quick)."""

from __future__ import annotations

# Local worker processes when none are given: this project's 2-core machines. Results do not
# depend on it (every trial's perturbation is seeded by the run's seed and its index).
DEFAULT_WORKERS = 2
# Trials per object of a benchmark run (the README's main command).
DEFAULT_TRIALS = 10
