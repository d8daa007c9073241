"""``gripper train``: train PPO, SAC or TQC on the environment."""

from __future__ import annotations

from gripper.cli.commands.play import play_policy
from gripper.cli.inputs import (
    TRIALS_MAX,
    WORKERS_MAX,
    number,
    seed_option,
)
from gripper.cli.options import (
    needs_rl,
    object_specs,
)
from gripper.core.atomic import check_output_dir, check_output_file
from gripper.core.user_files import parse_user_data


def add(sub) -> None:
    from gripper.rl.config import EVAL_SEED, TrainConfig
    from gripper.rl.hyperparams import RECOMMENDED

    tc = TrainConfig()
    tr = sub.add_parser(
        "train", help="train PPO, SAC or TQC on the grasp environment (needs the rl extra)",
        description="Train Stable-Baselines3 PPO, SAC or TQC on SoftGripperGrasp (or SoftGripperGraspGoal) "
                    "through the native vector env, with the documented hyper-parameters "
                    "(gripper/rl/hyperparams.py). Every "
                    "--chunk-steps it evaluates the deterministic policy on --eval-episodes unseen seeds, "
                    "appends a row to progress.csv and writes a checkpoint; --resume continues from the "
                    "latest one, bitwise as if never stopped. Writes policy.zip at the end.")
    tr.add_argument("--algo", choices=("ppo", "sac", "tqc"), default=tc.algo,
                    help="PPO (on-policy), SAC or TQC (off-policy; TQC from sb3-contrib) (default %(default)s)")
    tr.add_argument("--goal", action="store_true",
                    help="the goal-conditioned task (SoftGripperGraspGoal: lift the object to a target); "
                         "SAC and TQC then replay hindsight goals (HER)")
    tr.add_argument("--objects", default=",".join(tc.objects), help="comma-separated names (default %(default)s)")
    tr.add_argument("--action-mode", choices=("synergy", "fingers"), default=tc.action_mode,
                    help="synergy: one closing command for all fingers; fingers: one per finger "
                         "(default %(default)s)")
    tr.add_argument("--xy", action="store_true", help="add the palm's x/y velocity actions")
    number(tr, "--steps", int, lo=1, hi=10**9, default=tc.steps, help="environment steps")
    seed_option(tr, help="seed", default=tc.seed)
    number(tr, "--n-envs", int, lo=1, hi=WORKERS_MAX, default=tc.n_envs, help="environments")
    number(tr, "--chunk-steps", int, lo=1, hi=10**9, default=tc.chunk_steps,
           help="steps between evaluations and checkpoints")
    number(tr, "--eval-episodes", int, lo=1, hi=TRIALS_MAX, default=tc.eval_episodes,
           help=f"evaluation episodes, seeds from {EVAL_SEED} on")
    number(tr, "--demos", int, lo=0, hi=10_000, default=None,
           help=f"episodes of the scripted grasp to clone before RL (SAC also replays them); "
                f"0: none (default {tc.demo_episodes}; {RECOMMENDED['demo_episodes']} with --recommended)")
    number(tr, "--demo-noise", float, lo=0.0, hi=1.0, default=None,
           help=f"DART noise on the demonstrations' actions (default {tc.demo_noise}; "
                f"{RECOMMENDED['demo_noise']} with --recommended)")
    tr.add_argument("--recommended", action="store_true",
                    help="the recommended recipe: PPO from demonstrations, regularised towards them "
                         f"({', '.join(f'{k}={v}' for k, v in RECOMMENDED['hyperparams'].items())}); "
                         "--demos, --demo-noise and --set still override its values")
    tr.add_argument("--set", action="append", metavar="KEY=VALUE",
                    help="override a hyper-parameter, e.g. --set n_epochs=5 (repeatable)")
    tr.add_argument("--reward-weight", action="append", metavar="TERM=W",
                    help="override a dense reward weight, e.g. --reward-weight contact=1 (repeatable)")
    number(tr, "--threads", int, lo=1, hi=64, default=1,
           help="MuJoCo threads stepping the envs (the curve is the same for any number)")
    tr.add_argument("--out", required=True, metavar="DIR", help="run folder")
    tr.add_argument("--resume", action="store_true", help="continue the run in --out from its latest checkpoint")
    tr.add_argument("--video", metavar="FILE.mp4", help="also write a video of the final policy")
    seed_option(tr, "--video-seed", help="the video's episode seed", default=EVAL_SEED)
    tr.set_defaults(func=run)


def run(args) -> int:
    from gripper.rl.config import TrainConfig
    from gripper.rl.hyperparams import RECOMMENDED

    base = RECOMMENDED if args.recommended else {}
    if args.recommended and args.algo != "ppo":
        raise ValueError(f"--recommended: the recipe is PPO's; drop --algo {args.algo}")
    tc = TrainConfig()
    demos = args.demos if args.demos is not None else base.get("demo_episodes", tc.demo_episodes)
    noise = args.demo_noise if args.demo_noise is not None else base.get("demo_noise", tc.demo_noise)
    cfg = TrainConfig(algo=args.algo, goal_conditioned=args.goal, objects=object_specs(args.objects),
                      action_mode=args.action_mode, xy_actions=args.xy, steps=args.steps, seed=args.seed,
                      n_envs=args.n_envs, chunk_steps=args.chunk_steps, eval_episodes=args.eval_episodes,
                      demo_episodes=demos, demo_noise=noise,
                      hyperparams={**base.get("hyperparams", {}), **_hyperparam_overrides(args.set)},
                      reward_weights=_hyperparam_overrides(args.reward_weight, "--reward-weight")).validate()
    from gripper.rl.training import RUN_FILES as TRAIN_FILES

    check_output_dir(args.out, files=TRAIN_FILES)
    if args.video:
        from gripper.render.video import VIDEO_SUFFIXES

        check_output_file(args.video, "--video", VIDEO_SUFFIXES)
    needs_rl("train", contrib=cfg.algo == "tqc")
    from gripper.rl.training import train

    def show(row):
        per = " ".join(f"{k[5:]} {v:.2f}" for k, v in row.items() if k.startswith("eval_") and k not in (
            "eval_success", "eval_return"))
        # no training episode has ended yet: nothing to average (the row holds NaN)
        train = (f"success {row['train_success']:.2f}, return {row['train_return']:7.1f}"
                 if row["train_episodes"] else "no episode ended yet")
        print(f"{row['steps']:>9} steps {row['wall_s']:>8.0f} s  train: {row['train_episodes']:>4} episodes, "
              f"{train}  eval: success {row['eval_success']:.2f} ({per})", flush=True)

    rows = train(cfg, args.out, resume=args.resume, on_progress=show, nthread=args.threads)
    print(f"wrote {args.out}/policy.zip and progress.csv ({len(rows)} evaluations)")
    if args.video:
        return play_policy(args.out, args.video, args.video_seed, 640, 480, "front")
    return 0


def _hyperparam_overrides(items: list[str], flag: str = "--set") -> dict:
    out = {}
    for item in items or []:
        key, sep, value = item.partition("=")
        if not sep or not key:
            raise ValueError(f"{flag}: expected KEY=VALUE, got {item!r}")
        try:
            out[key.strip()] = parse_user_data(value, "json", f"{flag} {key.strip()}")
        except ValueError as e:
            if "not valid JSON" not in str(e):  # too deep, a number that is not a float
                raise
            out[key.strip()] = value.strip()
    return out
