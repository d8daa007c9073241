"""The changes of 0.12.0 one at a time and all together, side by side on the same trials.

Variants (``GraspProtocol`` switches and the bag object):

- ``0.11.0``: the catalogue approach (the object's size, centred under the palm), the
  envelope grasp, the pack-in-a-bag as the bag;
- ``sensing``: the palm camera's estimate and centring alone (envelope grasp, old bag);
- ``fingertip``: the fingertip grasp alone (catalogue approach, old bag);
- ``new bag``: 0.11.0's grasp on the zipper storage bag;
- ``all``: the default of 0.12.0 (sensed, centred, the grasp rule) with the zipper bag.

Each variant runs the same trials (seed, indices, placements) of the five default objects and
the envelope's lower ends (50 g spheres, cylinders and boxes of the given widths, 60 mm tall,
three trials each: held at 2 of 3). The contact law and the friction coefficients did not
change in 0.12.0 (docs/limitations.md), so they have no row.

    .venv/bin/python scripts/ablation.py --trials 10 --seed 1
"""

from __future__ import annotations

import argparse
import multiprocessing as mp
import time

from gripper.experiments.protocol import GraspProtocol
from gripper.experiments.trial import run_trial
from gripper.objects.grasp_object import GraspObject
from gripper.objects.library import get_object
from gripper.studies.envelope import ENVELOPE_HEIGHT, SHAPES

VARIANTS = {
    "0.11.0": ({"approach": "catalogue", "grasp": "envelope"}, "bag_pack"),
    "sensing": ({"approach": "sensed", "grasp": "envelope"}, "bag_pack"),
    "fingertip": ({"approach": "catalogue", "grasp": "fingertip"}, "bag_pack"),
    "new bag": ({"approach": "catalogue", "grasp": "envelope"}, "bag"),
    "all": ({}, "bag"),
}
OBJECTS = ("balloon", "block", "cylinder", "paper_box", "bag")


def _small(shape: str, width: float) -> GraspObject:
    size = (width / 2,) * 3 if shape == "sphere" else (width / 2, width / 2, ENVELOPE_HEIGHT / 2)
    return GraspObject(name=f"{shape}-{width * 1e3:.0f}", kind=SHAPES[shape], size=size, mass=0.05, friction=0.6,
                       yaw_symmetric=shape != "box", close_command=3.0, damage="none", damage_limit=0.0)


def _job(args):
    variant, what, index, seed = args
    kw, bag = VARIANTS[variant]
    obj = get_object(bag if what == "bag" else what) if isinstance(what, str) else _small(*what)
    t = time.perf_counter()
    rec = run_trial(obj, seed=seed, index=index, protocol=GraspProtocol(**kw))
    return variant, what, bool(rec.success), bool(rec.get("damaged")), rec.warnings, time.perf_counter() - t


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--trials", type=int, default=10)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--widths", default="0.020,0.025,0.030,0.036,0.040")
    ap.add_argument("--workers", type=int, default=2)
    a = ap.parse_args()
    widths = [float(w) for w in a.widths.split(",")]
    small = [(s, w) for s in SHAPES for w in widths]
    jobs = [(v, o, i, a.seed) for v in VARIANTS for o in OBJECTS for i in range(a.trials)]
    jobs += [(v, sw, i, a.seed) for v in VARIANTS for sw in small for i in range(3)]
    with mp.Pool(a.workers) as pool:
        out = pool.map(_job, jobs, chunksize=1)
    print("| variant | " + " | ".join(OBJECTS) + " | lower end: sphere | cylinder | box | warnings |")
    print("|---|" + "---|" * (len(OBJECTS) + 4))
    for v in VARIANTS:
        cells = []
        for o in OBJECTS:
            got = [r for r in out if r[0] == v and r[1] == o]
            dmg = sum(r[3] for r in got)
            cells.append(f"{sum(r[2] for r in got)}/{len(got)}" + (f" ({dmg} damaged)" if dmg else ""))
        for s in SHAPES:
            held = [w for w in widths if sum(r[2] for r in out if r[0] == v and r[1] == (s, w)) >= 2]
            cells.append(f"{min(held) * 1e3:.0f} mm" if held else "none")
        warn = sum(r[4] for r in out if r[0] == v)
        print(f"| {v} | " + " | ".join(cells) + f" | {warn} |")


if __name__ == "__main__":
    main()
