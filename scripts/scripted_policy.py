"""A scripted grasp policy that drives ``SoftGripperGrasp-v8`` through its public API only.

The policy centres the palm over the object (``xy_actions``: it reads the object's offset from
the observation, ``object_pos_rel_palm``, at the start of the episode), then does what the
benchmark protocol does: lower the palm until the fingertips are 8 mm
above the floor, reel all cables in together at 2 rad/s of spool (0.04 m/s of cable) to 3.0 rad
(the servo stalls on a rigid part), wait 0.4 s, lift the palm to its home height (0.25 m) at
0.1 m/s, and hold. It reads the palm height from the observation (``palm_height``) and turns
heights and spool angles into actions with ``env.unwrapped.lift_action`` and ``servo_action``.

Run: .venv/bin/python scripts/scripted_policy.py --objects block,cylinder --episodes 50
     [--params FILE]   (e.g. 0.5.1's design: 3 mm bridge, paper 000's spring per degree)
Prints the success rate per object with its Wilson 95 % interval.
"""

import argparse

import gymnasium as gym
import numpy as np

import gripper  # noqa: F401  (registers the environment)
from gripper.bench.benchmark import wilson_interval

TIP_CLEARANCE = 0.008   # m, fingertips above the floor at the grasp (as GraspProtocol)
APPROACH_SPEED = 0.10   # m/s
CLOSE_RATE = 2.0        # rad/s of spool (0.04 m/s of cable on the 20 mm spool)
CLOSE_ANGLE = 3.0       # rad (RIGID_CLOSE of the object library)
CLOSE_HOLD = 0.4        # s
LIFT_SPEED = 0.10       # m/s
LIFT_TOP = 0.25         # m, the lift's home height


class ScriptedGrasp:
    def __init__(self, env):
        self.env = env
        u = env.unwrapped
        self.dt = u.config.control_period
        self.finger_length = u.config.params.finger.length
        self.n_servo = u.config.n_fingers if u.config.action_mode == "fingers" else 1
        self.i_height = u.observation_structure["palm_height"][0]
        self.i_rel = u.observation_structure["object_pos_rel_palm"][0]
        self.xy = u.config.xy_actions

    def reset(self, obs):
        self.t = 0.0
        self.z0 = float(obs[self.i_height])
        self.z_grasp = self.finger_length + TIP_CLEARANCE
        self.t_app = max(0.0, self.z0 - self.z_grasp) / APPROACH_SPEED
        self.t_close = CLOSE_ANGLE / CLOSE_RATE
        self.target_xy = obs[self.i_rel:self.i_rel + 2].copy()  # palm starts on its home axis

    def act(self, obs):
        u = self.env.unwrapped
        t = self.t
        self.t += self.dt
        t1 = self.t_app + 0.1
        t2 = t1 + self.t_close + CLOSE_HOLD
        if t < t1:
            z = self.z0 + (self.z_grasp - self.z0) * min(1.0, t / max(self.t_app, 1e-9))
            servo = 0.0
        elif t < t2:
            z = self.z_grasp
            servo = min(CLOSE_ANGLE, CLOSE_RATE * (t - t1))
        else:
            z = min(LIFT_TOP, self.z_grasp + LIFT_SPEED * (t - t2))
            servo = CLOSE_ANGLE
        a = np.full(u.action_space.shape, 0.0, dtype=np.float32)
        a[:self.n_servo] = u.servo_action(servo)
        a[self.n_servo] = u.lift_action(z)
        if self.xy:
            a[self.n_servo + 1] = u.xy_action(float(self.target_xy[0]))
            a[self.n_servo + 2] = u.xy_action(float(self.target_xy[1]))
        return a


def run(objects, episodes, seed, params=None):
    out = {}
    for name in objects:
        env = gym.make("gripper:SoftGripperGrasp-v8", objects=name, xy_actions=True, params=params,
                       scale_observations=False,  # it reads heights and offsets in metres
                       palm_control="position", servo_control="position")
        policy = ScriptedGrasp(env)
        wins = 0
        for ep in range(episodes):
            obs, _ = env.reset(seed=seed + ep)
            policy.reset(obs)
            done = False
            success = False
            while not done:
                obs, _, term, trunc, info = env.step(policy.act(obs))
                success = success or info["is_success"]
                done = term or trunc
            wins += success
        lo, hi = wilson_interval(wins, episodes)
        out[name] = (wins, episodes, lo, hi)
        print(f"{name:<10} {wins}/{episodes} success {wins / episodes:.2f} (Wilson 95 %: {lo:.2f}-{hi:.2f})",
              flush=True)
    return out


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--objects", default="block,cylinder")
    ap.add_argument("--episodes", type=int, default=50)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--params", metavar="FILE", help="gripper parameter file (default design if omitted)")
    args = ap.parse_args()
    params = None
    if args.params:
        from gripper.core.params import GripperParams

        params = GripperParams.load(args.params)
    run(args.objects.split(","), args.episodes, args.seed, params)
