"""The RL baselines' table and learning curves, from ``gripper train`` run folders.

For every run folder given (each holds ``config.json`` and ``progress.csv``), prints one row of a
panda-gym-style table: algorithm, task variant, seed, the deterministic policy's success on the
unseen evaluation seeds at the last evaluation, the first environment step at which it reached
80 %, the training wall time on this machine, and then the mean over seeds per (algorithm,
variant). ``--plot FILE.png`` draws success against environment steps, one line per run.

Run: .venv/bin/python scripts/rl_table.py runs/train/ppo-bc-s* [--plot docs/rl_ppo.png]
"""

import argparse
import csv
import json
from collections import defaultdict
from pathlib import Path


def load(run: Path) -> dict:
    cfg = json.loads((run / "config.json").read_text())
    with open(run / "progress.csv", newline="") as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    c = cfg["config"]
    variant = "+".join(c["objects"]) + (", x/y" if c["xy_actions"] else "") + f", {c['action_mode']}"
    return {"run": run.name, "algo": c["algo"].upper(), "variant": variant, "seed": c["seed"], "rows": rows,
            "hyperparams": cfg["hyperparams"]}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", type=Path)
    ap.add_argument("--threshold", type=float, default=0.8)
    ap.add_argument("--plot", metavar="FILE.png")
    args = ap.parse_args()
    runs = [load(r) for r in args.runs if (r / "progress.csv").exists()]
    print("| algorithm | task | seed | steps | success (last eval) | best eval | first step at "
          f"≥ {args.threshold:.0%} | wall time |")
    print("|---|---|---|---|---|---|---|---|")
    groups = defaultdict(list)
    for r in sorted(runs, key=lambda r: (r["algo"], r["variant"], r["seed"])):
        rows = r["rows"]
        last = rows[-1]
        first = next((int(x["steps"]) for x in rows if x["eval_success"] >= args.threshold - 1e-9), None)
        best = max(x["eval_success"] for x in rows)
        groups[(r["algo"], r["variant"])].append((last["eval_success"], first, last["wall_s"]))
        print(f"| {r['algo']} | {r['variant']} | {r['seed']} | {int(last['steps']):,} | {last['eval_success']:.0%} "
              f"| {best:.0%} | {f'{first:,}' if first else 'not reached'} | {last['wall_s'] / 60:.0f} min |")
    print()
    for (algo, variant), g in groups.items():
        succ = [x[0] for x in g]
        print(f"{algo} {variant}: mean success {sum(succ) / len(succ):.0%} over {len(g)} seeds "
              f"(min {min(succ):.0%}); all seeds >= {args.threshold:.0%}: "
              f"{'yes' if all(x[1] is not None for x in g) else 'no'}")
    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(6.4, 3.6))
        for r in runs:
            ax.plot([x["steps"] for x in r["rows"]], [x["eval_success"] for x in r["rows"]], marker=".",
                    label=f"{r['algo']} {r['variant']} s{r['seed']}")
        ax.axhline(args.threshold, color="gray", lw=0.8, ls="--")
        ax.set_xlabel("environment steps")
        ax.set_ylabel("success, deterministic policy, unseen seeds")
        ax.set_ylim(-0.02, 1.02)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
        print(f"wrote {args.plot}")


if __name__ == "__main__":
    main()
