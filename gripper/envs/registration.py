"""Registration of the environments with Gymnasium (run when ``gripper`` is imported).

Only the ids and entry points are registered here; the environment modules are imported by
``gymnasium.make`` when an environment is made.
"""

from __future__ import annotations

ENV_ID = "SoftGripperGrasp-v12"
# The goal-conditioned variant (gripper.envs.goal_env): a lift target, dict observations, HER's interface
GOAL_ENV_ID = "SoftGripperGraspGoal-v12"
# An episode's length in control steps: 300 x 20 ms = 6 s, a grasp and a 1 s hold with room to spare.
MAX_EPISODE_STEPS = 300


def register_envs() -> None:
    import gymnasium

    if ENV_ID not in gymnasium.registry:
        gymnasium.register(
            id=ENV_ID, entry_point="gripper.envs.grasp_env:SoftGripperGraspEnv",
            vector_entry_point="gripper.envs.vector_env:SoftGripperGraspVectorEnv",
            max_episode_steps=MAX_EPISODE_STEPS)
    if GOAL_ENV_ID not in gymnasium.registry:
        gymnasium.register(
            id=GOAL_ENV_ID, entry_point="gripper.envs.goal_env:SoftGripperGraspGoalEnv",
            vector_entry_point="gripper.envs.goal_env:SoftGripperGraspGoalVectorEnv",
            max_episode_steps=MAX_EPISODE_STEPS)
