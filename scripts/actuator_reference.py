"""Paper 001's actuator: the measurements ``docs/pneumatic.md`` shows, regenerated.

    .venv/bin/python scripts/actuator_reference.py convergence   # three meshes, 0-250 kPa (~40 min)
    .venv/bin/python scripts/actuator_reference.py section       # the duct's section under pressure (~3 min)
    .venv/bin/python scripts/actuator_reference.py studies runs/paper001_*   # after the five studies
    .venv/bin/python scripts/actuator_reference.py pictures [--video runs/actuator_inflation.mp4]

``convergence`` solves the sweep on the mesh levels 1, 2 and 3
(:meth:`gripper.references.actuator_mesh.MeshSize.at_refinement`; about 3, 10 and 25 minutes on
one core), extrapolates the bending angle at each pressure (Richardson, with the grid
convergence index of Celik et al. 2008) and puts the semi-analytical model's curve beside the
studies' mesh; ``section`` measures the duct's cross-section under pressure. ``studies`` collects the five case
studies' curves and per-design times from their run folders. Both write
``gripper/data/actuator/reference_results.json``, from which the docs build makes the page's
tables (``docs/hooks/generate.py``); ``pictures`` draws the deformed actuator into
``docs/actuator_inflation.png`` and, with ``--video``, writes an offscreen video of the sweep.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from gripper.bench.execution import read_jsonl  # noqa: E402
from gripper.core.atomic import write_text_atomic  # noqa: E402
from gripper.experiments.actuator_responses import STUDY_REFINEMENT  # noqa: E402
from gripper.references.actuator_fe import inflate  # noqa: E402
from gripper.references.actuator_mesh import MeshSize  # noqa: E402
from gripper.references.actuator_section import duct_section, mid_station  # noqa: E402
from gripper.references.bending_moment_model import bending_angle_deg, bending_curve_deg  # noqa: E402
from gripper.references.convergence import richardson  # noqa: E402
from gripper.references.pneumatic_params import PneumaticActuator  # noqa: E402

RESULTS = ROOT / "gripper" / "data" / "actuator" / "reference_results.json"
PRESSURES = np.linspace(0.0, 250e3, 11)  # Pa, the studies' sweep
REFINEMENTS = (1, 2, 3)
PICTURE = ROOT / "docs" / "actuator_inflation.png"
CHECK_PLOT = ROOT / "docs" / "actuator_check.png"
STUDIES_PLOT = ROOT / "docs" / "actuator_studies.png"


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def check_plot(data: dict) -> None:
    """The bending curves of the three meshes and of the semi-analytical model."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(5.5, 4.0))
    for ratio, sweep in sorted(data["sweeps"].items()):
        ax.plot(sweep["pressure_kPa"], sweep["angle_deg"], "o-", ms=3,
                label=f"finite elements, refinement {ratio} ({sweep['unknowns']} unknowns)")
    sa = data["semi_analytical"]
    ax.plot(sa["pressure_kPa"], sa["angle_deg"], "k--", label="semi-analytical (Polygerinos-style)")
    ax.set_xlabel("pressure [kPa]")
    ax.set_ylabel("bending angle [deg]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(CHECK_PLOT, dpi=110)
    plt.close(fig)


def studies_plot(data: dict) -> None:
    """Paper 001's Figs. 12-16: bending angle against pressure, one panel per case study."""
    plt = _plt()
    cases = list(data["studies"].values())
    fig, axes = plt.subplots(1, len(cases), figsize=(3.3 * len(cases), 3.4), squeeze=False)
    for ax, case in zip(axes[0], cases, strict=True):
        for pt in case["points"]:
            if pt["status"] != "ok":
                continue
            key, value = next(iter(pt["changes"].items()), (case["key"], case["base_value"]))
            label = f"{value:g}°" if key.endswith("_deg") else f"{value * 1e3:g} mm"
            ax.plot(pt["curve"]["pressure_kPa"], pt["curve"]["bending_angle_deg"], "o-", ms=2, label=label)
        ax.set_title(case["name"].replace("paper 001 ", ""), fontsize=8)
        ax.set_xlabel("pressure [kPa]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=6)
    axes[0][0].set_ylabel("bending angle [deg]")
    fig.tight_layout()
    fig.savefig(STUDIES_PLOT, dpi=100)
    plt.close(fig)


def load() -> dict:
    return json.loads(RESULTS.read_text()) if RESULTS.is_file() else {}


def save(data: dict) -> None:
    RESULTS.parent.mkdir(parents=True, exist_ok=True)
    write_text_atomic(RESULTS, json.dumps(data, indent=1, sort_keys=True) + "\n")


def convergence(data: dict) -> dict:
    sweeps = data.setdefault("sweeps", {})
    for ratio in REFINEMENTS:
        size = MeshSize.at_refinement(ratio)
        r = inflate(PneumaticActuator(), PRESSURES, size)
        if r.failed_at is not None:
            raise SystemExit(f"refinement {ratio}: the sweep failed at {r.failed_at:g} Pa")
        points, cells = r.mesh.quadratic()
        sweeps[str(ratio)] = {"pressure_kPa": (r.pressures / 1e3).tolist(), "angle_deg": r.angles_deg.tolist(),
                              "cells": int(len(cells)), "unknowns": int(3 * len(points)),
                              "wall_time_s": round(r.wall_time_s, 1), "newton_iterations": r.newton_iterations}
        print(f"refinement {ratio}: {r.angles_deg[-1]:.3f} deg at 250 kPa, {len(cells)} cells, "
              f"{r.wall_time_s:.0f} s", flush=True)
        save(data)
    extrapolate(data)
    data["semi_analytical"] = {"pressure_kPa": (PRESSURES / 1e3).tolist(),
                               "angle_deg": bending_curve_deg(PneumaticActuator(), PRESSURES).tolist()}
    save(data)
    check_plot(data)
    return data


def extrapolate(data: dict) -> dict:
    """Richardson extrapolation of the bending (less its value at 0 kPa, gravity's) at each
    pressure of the three meshes' sweeps, and the grid convergence index of each mesh,
    GCI = 1.25 |f - f_extrapolated| / |f| (Celik et al. 2008's safety factor for three meshes;
    for the finest mesh it is their GCI_fine); the studies' mesh is the coarsest."""
    from gripper.references.convergence import GCI_SAFETY_FACTOR

    sweeps = data["sweeps"]
    ratios = sorted(int(k) for k in sweeps)
    # the representative cell size, (volume / cells)^(1/3) (Celik et al. 2008): the levels share
    # one volume (to 1e-5), so the cell counts alone set the ratios
    h = tuple(sweeps[str(r)]["cells"] ** (-1.0 / 3.0) for r in ratios)
    rows = []
    for i, p in enumerate(sweeps[str(ratios[0])]["pressure_kPa"]):
        if i == 0:
            continue
        f = tuple(sweeps[str(r)]["angle_deg"][i] - sweeps[str(r)]["angle_deg"][0] for r in ratios)
        studies = f[ratios.index(STUDY_REFINEMENT)]
        if (f[1] - f[0]) * (f[2] - f[1]) <= 0:
            # oscillatory convergence: no observed order exists (Celik et al. 2008); the
            # uncertainty is then half the three solutions' range (Stern et al. 2001), here
            # relative to the studies' mesh's value
            rows.append({"pressure_kPa": p, "angles_deg": list(f), "order": None, "extrapolated_deg": None,
                         "oscillation_range": (max(f) - min(f)) / abs(studies),
                         "uncertainty_studies_mesh": 0.5 * (max(f) - min(f)) / abs(studies)})
            continue
        rich = richardson(h, f)  # raises when the observed order is outside 0.05-10
        gci = [GCI_SAFETY_FACTOR * abs(fi - rich.extrapolated) / abs(fi) for fi in f]
        rows.append({"pressure_kPa": p, "angles_deg": list(f), "order": rich.order,
                     "extrapolated_deg": rich.extrapolated, "gci_fine": rich.gci_fine, "gci_by_mesh": gci,
                     "gci_studies_mesh": gci[ratios.index(STUDY_REFINEMENT)],
                     "asymptotic_ratio": rich.asymptotic_ratio})
    data["richardson"] = {"refinements": ratios, "studies_refinement": STUDY_REFINEMENT, "by_pressure": rows,
                          "cell_size_ratios": [h[0] / x for x in h]}
    save(data)
    return data


def studies(data: dict, folders: list[Path]) -> dict:
    from gripper.studies.study_file import get_dotted, load_study

    out = {}
    for folder in folders:
        rows = read_jsonl(folder / "results.jsonl")
        study = load_study(folder.name)  # the shipped study of that name
        key = next(iter(study.vary))
        out[folder.name] = {"name": study.name, "key": key, "base_value": get_dotted(study.base, key),
                            "fixed": study.base.to_dict()["actuator"], "points": [
            {"changes": r["changes"], "status": r["status"], "wall_time_s": round(r["wall_time_s"], 1),
             "curve": r.get("curves", {}), "error": r.get("error", "")}
            for r in sorted(rows, key=lambda r: r["point"])]}
    data["studies"] = out
    save(data)
    studies_plot(data)
    return data


def section_check(data: dict) -> dict:
    """How the duct's cross-section changes under pressure at mid-length (the semi-analytical
    model's assumption that it keeps its shape), on the studies' mesh."""
    r = inflate(PneumaticActuator(), PRESSURES, MeshSize.at_refinement(STUDY_REFINEMENT), keep_shapes=True)
    z0 = mid_station(r.mesh)
    rows = [duct_section(r.mesh, s, z0) for s in r.shapes]
    data["section"] = {"z_m": z0, "pressure_kPa": (r.pressures / 1e3).tolist(),
                       "area_ratio": [row["area"] / rows[0]["area"] for row in rows],
                       "first_moment_ratio": [row["first_moment"] / rows[0]["first_moment"] for row in rows],
                       "height_ratio": [row["height"] / rows[0]["height"] for row in rows]}
    # the moment balance again, its pressure's lever the deformed section's (p Q(p) for p Q₀):
    # what is left between it and the finite elements is not the section's change of shape
    q_ratio = data["section"]["first_moment_ratio"]
    data["section"]["semi_analytical_deformed_deg"] = [
        bending_angle_deg(PneumaticActuator(), float(p) * q) for p, q in zip(r.pressures, q_ratio, strict=True)]
    data["section"]["finite_element_deg"] = (r.angles_deg - r.angles_deg[0]).tolist()
    save(data)
    for p, row in zip(r.pressures, rows, strict=True):
        print(f"{p / 1e3:5.0f} kPa: duct area x{row['area'] / rows[0]['area']:.3f}, "
              f"first moment x{row['first_moment'] / rows[0]['first_moment']:.3f}")
    return data


def pictures(video: Path | None) -> None:
    from gripper.render.actuator_views import inflation_pictures, inflation_video

    r = inflate(PneumaticActuator(), PRESSURES, MeshSize.at_refinement(STUDY_REFINEMENT), keep_shapes=True)
    cells = r.mesh.cells
    inflation_pictures(r.pressures, r.shapes, cells, PICTURE)
    print(f"wrote {PICTURE}")
    if video is not None:
        fine = np.linspace(0.0, 250e3, 51)
        rv = inflate(PneumaticActuator(), fine, MeshSize.at_refinement(STUDY_REFINEMENT), keep_shapes=True)
        inflation_video(rv.pressures, rv.shapes, cells, video)
        print(f"wrote {video}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="what", required=True)
    sub.add_parser("convergence")
    sub.add_parser("extrapolate", help="redo the extrapolation from the saved sweeps")
    sub.add_parser("section", help="the duct's cross-section under pressure at mid-length (studies' mesh)")
    st = sub.add_parser("studies")
    st.add_argument("folders", nargs="+", type=Path)
    pi = sub.add_parser("pictures")
    pi.add_argument("--video", type=Path)
    args = ap.parse_args()
    data = load()
    if args.what == "convergence":
        convergence(data)
    elif args.what == "extrapolate":
        extrapolate(data)
    elif args.what == "section":
        section_check(data)
    elif args.what == "studies":
        studies(data, args.folders)
    else:
        pictures(args.video)


if __name__ == "__main__":
    main()
