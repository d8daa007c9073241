"""Keep PPO near the demonstrations while it learns: a behaviour-cloning term in every update's
loss, and a critic warm-up with the actor frozen (``gripper train --demos N --set bc_weight=…``).

Why: a policy cloned from the scripted grasp starts at its demonstrator's success, and the first
policy-gradient updates, driven by a critic that has not yet seen the cloned policy's own returns,
undo it (issue 49: seed 0 fell from 100 % to 26 % in the first updates, seed 3's block from 100 %
to 59 %). Two standard remedies, both measured in ``docs/environment.md`` ("Reinforcement learning
from demonstrations"):

- **Behaviour-cloning term** (DAPG, Rajeswaran et al., 2018; also Nair et al., 2018): each
  mini-batch step of PPO minimises ``L_PPO + λ_k · mean‖μ(s_d) − a_d‖²`` over a mini-batch of
  demonstration pairs ``(s_d, a_d)`` of the same size, ``λ_k = bc_weight · bc_decay^k`` at PPO
  update ``k``. The gradient of the second term is added to the first's (after PPO's gradient
  clipping) by a pre-step hook on the policy's optimiser, so SB3's PPO runs unchanged.
- **Critic warm-up** (as in Rajeswaran et al.'s and many fine-tuning recipes): for the first
  ``critic_warmup`` updates only the value network learns (the actor's gradients are dropped),
  so the advantages are the cloned policy's own before the policy moves.

The demonstration mini-batches are drawn from a generator seeded with ``(seed, update,
mini-batch)``, so a resumed run draws what the uninterrupted one drew.

Example:
    >>> from gripper.rl.demo_regulariser import DemoRegulariser           # doctest: +SKIP
    >>> reg = DemoRegulariser(model, demo, weight=1.0, decay=1.0, critic_warmup=4, seed=0)  # doctest: +SKIP
    >>> model.learn(65_536)                                                 # doctest: +SKIP
    >>> reg.remove()                                                        # doctest: +SKIP
"""

from __future__ import annotations

import numpy as np

# Parameters of SB3's ActorCriticPolicy that belong to the critic (separate networks: net_arch
# {"pi": ..., "vf": ...}); every other trainable parameter is the actor's.
CRITIC_PREFIXES = ("mlp_extractor.value_net", "value_net")


class DemoRegulariser:
    """Hooks ``model`` (an SB3 PPO) so that its updates carry the behaviour-cloning term and,
    for the first ``critic_warmup`` updates, leave the actor unchanged. ``remove()`` unhooks."""

    def __init__(self, model, demo, weight: float, decay: float, critic_warmup: int, seed: int,
                 batch_size: int | None = None):
        import torch

        self.model = model
        self.weight, self.decay = float(weight), float(decay)
        self.critic_warmup, self.seed = int(critic_warmup), int(seed)
        self.obs = torch.as_tensor(demo.obs, dtype=torch.float32)
        self.label = torch.as_tensor(demo.label, dtype=torch.float32)
        self.batch = int(batch_size or model.batch_size)
        policy = model.policy
        self.actor = [p for name, p in policy.named_parameters()
                      if p.requires_grad and not name.startswith(CRITIC_PREFIXES)]
        self._update, self._minibatch = -1, 0
        self.last_bc_mse = float("nan")
        self._handle = policy.optimizer.register_step_pre_hook(self._pre_step)

    def update_index(self) -> int:
        """The PPO update under way (SB3 adds ``n_epochs`` to ``_n_updates`` after each)."""
        return int(self.model._n_updates // self.model.n_epochs)

    def _pre_step(self, optimizer, args, kwargs) -> None:
        import torch

        k = self.update_index()
        if k != self._update:
            self._update, self._minibatch = k, 0
        self._minibatch += 1
        if k < self.critic_warmup:
            for p in self.actor:
                p.grad = None  # Adam skips a parameter without a gradient: the actor stays as cloned
            return
        lam = self.weight * self.decay ** (k - self.critic_warmup)
        if lam <= 0.0:
            return
        idx = np.random.default_rng([self.seed, k, self._minibatch]).integers(0, len(self.obs), self.batch)
        o, a = self.obs[idx], self.label[idx]
        with torch.enable_grad():
            mean = self.model.policy.get_distribution(o).distribution.mean
            loss = torch.mean((mean - a) ** 2)
            grads = torch.autograd.grad(lam * loss, self.actor, allow_unused=True)
        for p, g in zip(self.actor, grads, strict=True):
            if g is None:
                continue
            p.grad = g.detach() if p.grad is None else p.grad + g.detach()
        self.last_bc_mse = float(loss.detach())

    def remove(self) -> None:
        self._handle.remove()
