"""The simulation steps the experiments use, each with its reason, in one place [s]."""

from __future__ import annotations

# Grasp trials, the environment, the crush test: 2 ms with MuJoCo's discrete integrator. The
# flex objects (balloon, paper box, bag) are stable there, and the closed cuts are matched to
# their design under that integrator at this step (gripper.model.closure), so the outcome does
# not change with the step (the model README's convergence check).
TRIAL_TIMESTEP = 2.0e-3

# Paper 000's bending test: 5e-4 s (§IV, the ADAMS run: 2 s at 5e-4 s).
PAPER_BENDING_TIMESTEP = 5.0e-4
