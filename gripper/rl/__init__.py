"""Reinforcement learning on ``SoftGripperGrasp``: training, evaluation and the baselines' setup.

Needs the ``rl`` extra (``pip install -e ".[rl]"``: stable-baselines3 and the CPU build of
PyTorch); nothing else in the package imports this subpackage.

- :mod:`gripper.rl.config`: :class:`TrainConfig`, one training run (algorithm, task, steps, seed).
- :mod:`gripper.rl.hyperparams`: the documented PPO and SAC hyper-parameters of the baselines.
- :mod:`gripper.rl.evaluation`: the deterministic policy's success over unseen seeds.
- :mod:`gripper.rl.training`: :func:`train`, chunked, checkpointed and resumable.
- :mod:`gripper.rl.policy_video`: a video of a saved policy.

Example:
    >>> from gripper.rl.config import TrainConfig                    # doctest: +SKIP
    >>> from gripper.rl.training import train                        # doctest: +SKIP
    >>> rows = train(TrainConfig(algo="ppo", steps=200_000), "runs/train/ppo")  # doctest: +SKIP
    >>> rows[-1]["eval_success"]                                     # doctest: +SKIP
"""
