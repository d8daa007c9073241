"""The simulation steps the experiments use, each with its reason, in one place [s]."""

from __future__ import annotations

# Grasp trials, the environment, the crush test: 2 ms with MuJoCo's discrete integrator. The
# flex objects (balloon, paper box, bag) are stable there, and the closed cuts are matched to
# their design under that integrator at this step (gripper.drives.cable.closure), so the outcome does
# not change with the step (the model README's convergence check).
TRIAL_TIMESTEP = 2.0e-3

# Paper 000's bending test: 5e-4 s (§IV, the ADAMS run: 2 s at 5e-4 s).
PAPER_BENDING_TIMESTEP = 5.0e-4

# The most steps one command's single rollout may take (a bending test, a random-control check):
# about five minutes of wall time for the gripper scene on one core. Longer runs are refused
# up front instead of appearing to hang.
MAX_STEPS = 2_000_000


def check_step_budget(duration: float, timestep: float, what: str) -> None:
    """Refuse ``duration`` / ``timestep`` above :data:`MAX_STEPS` (ValueError naming ``what``)."""
    steps = duration / timestep
    if steps > MAX_STEPS:
        raise ValueError(f"{what}: {duration:g} s at a {timestep:g} s step is {steps:,.0f} steps; at most "
                         f"{MAX_STEPS:,} (shorten the duration or lengthen the step)")
