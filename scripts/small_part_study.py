"""What it would take to hold 10-20 mm parts: the palm radius swept, with the sensed approach
and the default grasp rule, against the fingers' free-closing reach.

For each palm radius (the distance from the palm axis to the open fingers' grasping faces, an
assumed dimension of the default design), prints how close to the axis the free-closing fingers
come and how many of ``--trials`` trials hold a 50 g sphere, cylinder (60 mm tall) and square
box (60 mm tall) of each width, with the benchmark's ±10 mm placement noise, seed 0; a point is
held at 2 of 3, as in the envelope. The springs are the calibrated default's (the palm radius
does not enter the finger's calibration).

    .venv/bin/python scripts/small_part_study.py --radii 0.040,0.035,0.030 --sizes 0.010,0.020,0.030
"""

from __future__ import annotations

import argparse
import multiprocessing as mp

from gripper.core.params import GripperParams
from gripper.experiments.approach import finger_reach
from gripper.experiments.protocol import GraspProtocol
from gripper.experiments.trial import run_trial
from gripper.objects.grasp_object import GraspObject
from gripper.studies.envelope import ENVELOPE_HEIGHT, SHAPES


def _design(radius: float) -> GripperParams:
    p = GripperParams()
    return p.replace(layout=p.layout.replace(palm_radius=radius)).validate()


def _object(shape: str, width: float) -> GraspObject:
    kind = SHAPES[shape]
    size = (width / 2,) * 3 if shape == "sphere" else (width / 2, width / 2, ENVELOPE_HEIGHT / 2)
    return GraspObject(name=f"{shape}-{width * 1e3:.0f}mm", kind=kind, size=size, mass=0.05, friction=0.6,
                       yaw_symmetric=shape != "box", close_command=3.0, damage="none", damage_limit=0.0,
                       oversize=True)


def _job(args):
    radius, shape, width, index = args
    rec = run_trial(_object(shape, width), seed=0, index=index, params=_design(radius), protocol=GraspProtocol())
    return radius, shape, width, bool(rec.success), rec.get("grasp")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--radii", default="0.040,0.035,0.030")
    ap.add_argument("--sizes", default="0.010,0.020,0.030,0.075,0.090")
    ap.add_argument("--shapes", default="sphere,cylinder,box")
    ap.add_argument("--trials", type=int, default=3)
    ap.add_argument("--workers", type=int, default=2)
    a = ap.parse_args()
    radii = [float(v) for v in a.radii.split(",")]
    sizes = [float(v) for v in a.sizes.split(",")]
    shapes = a.shapes.split(",")
    for r in radii:
        p = _design(r)
        _, low, radial = finger_reach(p.replace(sim=p.sim.replace(timestep=GraspProtocol().timestep)))
        print(f"palm radius {r * 1e3:.0f} mm: the free-closing fingers come {radial.min() * 1e3:.1f} mm from the axis")
    jobs = [(r, s, w, i) for r in radii for s in shapes for w in sizes for i in range(a.trials)]
    with mp.Pool(a.workers) as pool:
        out = pool.map(_job, jobs, chunksize=1)
    print("| palm radius | shape | " + " | ".join(f"{w * 1e3:.0f} mm" for w in sizes) + " |")
    print("|---|---|" + "---|" * len(sizes))
    for r in radii:
        for s in shapes:
            cells = []
            for w in sizes:
                got = [o for o in out if o[0] == r and o[1] == s and o[2] == w]
                held = sum(o[3] for o in got)
                cells.append(f"{held}/{len(got)}" + (" **held**" if held >= 2 * len(got) / 3 else ""))
            print(f"| {r * 1e3:.0f} mm | {s} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
