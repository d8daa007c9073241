"""The RL baselines' table and learning curves, from ``gripper train`` run folders.

For every run folder given (each holds ``config.json`` and ``progress.csv``; the committed ones
are under ``docs/rl/``), prints one row per run (algorithm, task, seed, the deterministic policy's
success on the 50 unseen evaluation episodes at each evaluation, the first step at which it
reached 80 %, wall time), then one row per (recipe, task) over its seeds: the success at the last
evaluation as mean ± standard deviation (sample, n − 1), the steps to 80 % as mean ± standard
deviation over the seeds that reached it, how many seeds reached 80 % by the budget, and the
evaluation episodes' mean return at the first and the last evaluation (what RL added to a
cloned policy that already holds: faster, steadier grasps pay more held steps). Steps
to 80 % count the demonstrations' environment steps (``demo_steps``) with the training's: a
cloned policy that holds 80 % at step 0 took the demonstrations' steps to get there.
``--plot FILE.png`` draws success against environment steps, one panel per task.

Run: .venv/bin/python scripts/rl_table.py docs/rl/* --plot docs/rl/curves.png
"""

import argparse
import csv
import json
import math
import statistics
from collections import defaultdict
from pathlib import Path


def load(run: Path) -> dict:
    cfg = json.loads((run / "config.json").read_text())
    with open(run / "progress.csv", newline="") as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    c = cfg["config"]
    task = ("goal-conditioned " if c.get("goal_conditioned") else "") + " + ".join(c["objects"]) + (
        ", x/y" if c["xy_actions"] else "") + f", {c['action_mode']}"
    recipe = c["algo"].upper() + (f" + {c['demo_episodes']} demos" if c["demo_episodes"] else "") + (
        " + HER" if c.get("goal_conditioned") and c["algo"] != "ppo" else "")
    if c["hyperparams"].get("bc_weight", 0) > 0:
        recipe += " + BC term"
    if c["algo"] == "ppo":  # the starting exploration noise, e^log_std_init
        recipe += f", σ₀ {math.exp(cfg['hyperparams']['log_std_init']):.1f}"
    return {"run": run.name, "recipe": recipe, "task": task, "seed": c["seed"], "rows": rows,
            "budget": int(c["steps"])}


def mean_sd(xs: list[float], fmt: str) -> str:
    if not xs:
        return "-"
    sd = statistics.stdev(xs) if len(xs) > 1 else 0.0
    return f"{format(statistics.mean(xs), fmt)} ± {format(sd, fmt)}"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", type=Path)
    ap.add_argument("--threshold", type=float, default=0.8)
    ap.add_argument("--plot", metavar="FILE.png")
    args = ap.parse_args()
    runs = sorted((load(r) for r in args.runs if (r / "progress.csv").exists()),
                  key=lambda r: (r["task"], r["recipe"], r["seed"]))
    th = args.threshold
    print(f"| recipe | task | seed | success at each evaluation (steps) | first step at ≥ {th:.0%} | wall time |")
    print("|---|---|---|---|---|---|")
    groups = defaultdict(list)
    for r in runs:
        rows = r["rows"]
        # environment steps, the demonstrations' own (demo_steps) counted in
        first = next((int(x["steps"] + x.get("demo_steps", 0)) for x in rows if x["eval_success"] >= th - 1e-9), None)
        groups[(r["recipe"], r["task"])].append((rows[-1]["eval_success"], first, int(rows[-1]["steps"]), r["budget"],
                                                 rows[0]["eval_return"], rows[-1]["eval_return"]))
        curve = ", ".join(f"{x['eval_success']:.0%} ({int(x['steps']):,})" for x in rows)
        reach = f"{first:,}" if first is not None else "not reached"
        print(f"| {r['recipe']} | {r['task']} | {r['seed']} | {curve} | {reach} | {rows[-1]['wall_s'] / 60:.0f} min |")
    print()
    print(f"| recipe | task | seeds | steps | success at the last evaluation | steps to {th:.0%} "
          f"| seeds at ≥ {th:.0%} | return, first → last evaluation |")
    print("|---|---|---|---|---|---|---|---|")
    for (recipe, task), g in groups.items():
        last = [x[0] * 100 for x in g]
        reached = [x[1] for x in g if x[1] is not None]
        steps = sorted({x[2] for x in g})
        print(f"| {recipe} | {task} | {len(g)} | {', '.join(f'{s:,}' for s in steps)} | {mean_sd(last, '.1f')} % "
              f"| {mean_sd([float(x) for x in reached], ',.0f')} | {len(reached)} of {len(g)} "
              f"| {mean_sd([x[4] for x in g], '.1f')} → {mean_sd([x[5] for x in g], '.1f')} |")
    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        tasks = list(dict.fromkeys(r["task"] for r in runs))
        fig, axes = plt.subplots(1, len(tasks), figsize=(4.2 * len(tasks), 3.4), squeeze=False)
        for ax, task in zip(axes[0], tasks, strict=True):
            for r in (r for r in runs if r["task"] == task):
                ax.plot([x["steps"] for x in r["rows"]], [x["eval_success"] for x in r["rows"]], marker=".",
                        label=f"{r['recipe']}, seed {r['seed']}")
            ax.axhline(th, color="gray", lw=0.8, ls="--")
            ax.set_title(task, fontsize=9)
            ax.set_xlabel("environment steps")
            ax.set_ylim(-0.02, 1.02)
            ax.legend(fontsize=6)
        axes[0][0].set_ylabel("success, deterministic policy,\n50 unseen episodes")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)
        print(f"\nwrote {args.plot}")


if __name__ == "__main__":
    main()
