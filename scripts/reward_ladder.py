"""The reward ladder: the returns of the reference policies (idle, hovering closed, hovering
open, touching, holding) under the environment's dense reward (v12) and under v11's, side by side.

Run: .venv/bin/python scripts/reward_ladder.py [--episodes 8] [--xy]
"""

import argparse

from gripper.envs.reference_policies import LADDER, ladder_returns


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--episodes", type=int, default=8)
    ap.add_argument("--xy", action="store_true", help="with the palm's x/y actions")
    args = ap.parse_args()
    table = {obj: ladder_returns(args.episodes, objects=obj, action_mode="synergy", xy_actions=args.xy)
             for obj in ("block", "cylinder")}
    print("| policy | " + " | ".join(f"{o}: v11 return | {o}: v12 return | {o}: held" for o in table) + " |")
    print("|---|" + "---|---|---|" * len(table))
    for name in LADDER:
        cells = [f"{t[name]['return_v11']:.1f} | {t[name]['return']:.1f} | {t[name]['success']:.0%}"
                 for t in table.values()]
        print(f"| {name} | " + " | ".join(cells) + " |")
    print(f"\n{args.episodes} episodes per policy and object (seeds 0-{args.episodes - 1}), "
          f"synergy{' with x/y' if args.xy else ''}, 300 steps")


if __name__ == "__main__":
    main()
