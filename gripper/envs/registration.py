"""Registration of the environments with Gymnasium (run when ``gripper`` is imported).

Only the ids and entry points are registered here; the environment modules are imported by
``gymnasium.make`` when an environment is made.
"""

from __future__ import annotations

ENV_ID = "SoftGripperGrasp-v11"
# An episode's length in control steps: 300 x 20 ms = 6 s, a grasp and a 1 s hold with room to spare.
MAX_EPISODE_STEPS = 300


def register_envs() -> None:
    import gymnasium

    if ENV_ID not in gymnasium.registry:
        gymnasium.register(
            id=ENV_ID, entry_point="gripper.envs.grasp_env:SoftGripperGraspEnv",
            vector_entry_point="gripper.envs.vector_env:SoftGripperGraspVectorEnv",
            max_episode_steps=MAX_EPISODE_STEPS)
