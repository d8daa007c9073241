"""Design-parameter studies (paper 001's automated parameter investigation) on this gripper: a
study (:mod:`gripper.studies.study_file`) run on the benchmark's execution layer,
the tidy table, the plots and the recommendations. The file format, the execution and how each
point's hinge springs follow its design: ``docs/studies.md``.

Example:
    >>> from gripper.studies.study import run_study
    >>> from gripper.studies.study_file import load_study
    >>> run_study(load_study("one_at_a_time"), "runs/oat")   # doctest: +SKIP
"""

from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Any

from gripper.bench.defaults import DEFAULT_WORKERS
from gripper.core.arguments import check_instance
from gripper.core.atomic import write_csv_atomic, write_text_atomic
from gripper.experiments.actuator_responses import inflation_response
from gripper.experiments.design_responses import measure_responses
from gripper.studies.study_file import ActuatorDesign, Study, apply_point, metric_names


def run_point(study: Study, index: int, changes: dict, run_hash: str | None = None) -> dict:
    """Every response of one design point (:func:`gripper.experiments.design_responses.measure_responses`);
    errors are recorded, not raised. ``run_hash``: the study's, kept in the record so that a
    resume can tell the study's own records from another's."""
    t0 = time.perf_counter()
    rec: dict[str, Any] = {"point": index, "changes": changes, "status": "ok", "metrics": {}, "curves": {},
                           "run_config_hash": run_hash}
    try:
        p, reasons = apply_point(study.base, changes)
        rec["calibrated"] = not reasons
        rec["calibration_note"] = "; ".join(reasons)
        if isinstance(p, ActuatorDesign):
            rec["metrics"], rec["curves"] = inflation_response(p.actuator, study.responses["inflation"])
        else:
            protocol, placement = study.trial_setup(changes)
            rec["metrics"], rec["curves"] = measure_responses(p, study.responses, study.seed, protocol=protocol,
                                                              placement=placement)
    except Exception as e:  # a failing point is recorded and the study goes on
        rec.update(status="error", error=f"{type(e).__name__}: {e}")
    rec["wall_time_s"] = time.perf_counter() - t0
    return rec


# --- running, tables, plots ------------------------------------------------------------------

# The files of a study's run folder (and one plot_<parameter>.png per varied parameter).
RUN_FILES = ("study.json", "results.jsonl", "results.csv", "recommendations.md")


def run_study(study: Study, out: str | Path, *, workers: int = DEFAULT_WORKERS, scheduler: str | None = None,
              progress: bool = True) -> list[dict]:
    """Run (or resume) the study into ``out``; write the table, plots and recommendations."""
    from gripper.bench.resumable import ResumableRun

    check_instance("study", study, Study, optional=False)
    check_instance("out", out, (str, Path), optional=False)
    run_hash = study.hash()
    points = study.design_points()
    run = ResumableRun(marker="study.json", key="study", other="another study", files=RUN_FILES,
                       records="results.jsonl", label="design points", run_hash=run_hash,
                       identity=study.identity(), jobs=range(len(points)),
                       job_args=lambda i: (study, i, points[i], run_hash), fn=run_point,
                       record_key=lambda r: r.get("point"), describe=lambda r: f"point {r.get('point')}",
                       check=lambda records, path: _check_points(records, path, points))
    with run.open(out, workers=workers, scheduler=scheduler, progress=progress) as done:
        write_table(done.records, study, done.out / "results.csv")
        write_plots(done.records, study, done.out)
        write_text_atomic(done.out / "recommendations.md", recommendations(done.records, study))
        return done.records


def _check_points(records: list[dict], path: Path, points: list[dict]) -> None:
    """Refuse a record that is not a point of this study (its index or its changes)."""
    for n, r in enumerate(records, start=1):
        if r.get("point") not in range(len(points)) or \
                json.dumps(r.get("changes"), sort_keys=True) != json.dumps(points[r["point"]], sort_keys=True):
            raise ValueError(f"--out: {path}: record {n} (point {r.get('point')}) is not a point of this study; "
                             "choose another --out folder")


def _shown(key: str, v):
    """A varied value in the table: a mesh resolution as ``NXxNYxNZ``, another list's first entry."""
    if key == "object.mesh_points":
        return "x".join(str(int(x)) for x in v) if v else "default"
    return v[0] if isinstance(v, tuple | list) else v


def _numeric(v, categories: list) -> float | None:
    """A varied value on a plot's axis: a mesh resolution by its point count (None: the objects'
    own resolutions, which have no one count); a text value (a choice such as
    ``springs.closure``) by its place in ``categories`` (the base's value, then the study's in
    the order given)."""
    if v is None:
        return None
    if isinstance(v, str):
        return float(categories.index(v)) if v in categories else None
    if isinstance(v, tuple | list):
        return float(v[0] * v[1] * v[2])
    return float(v)


def _categories(study: Study, key: str) -> list:
    values = study.vary[key] if isinstance(study.vary[key], list) else []
    return list(dict.fromkeys([study.value(key), *values]))


def _label(study: Study, key: str, r: dict) -> str:
    """The value of ``key`` at point ``r``, as the recommendations show it."""
    v = r["changes"].get(key, study.value(key))
    v = _shown(key, v)
    return f"{v:g}" if isinstance(v, float) else str(v)


def write_table(records: list[dict], study: Study, path: Path) -> None:
    """Tidy CSV: one row per point and metric, with the varied parameters as columns."""
    keys = list(study.vary)
    rows = []
    for r in records:
        vals = [r["changes"].get(k, study.value(k)) for k in keys]
        vals = [_shown(k, v) for k, v in zip(keys, vals, strict=True)]
        if r["status"] != "ok":
            rows.append([r["point"], *vals, "error", "", "", "", r.get("error", "")])
            continue
        rows += [[r["point"], *vals, "ok", r["calibrated"], name, value, ""] for name, value in r["metrics"].items()]
    write_csv_atomic(path, ["point", *keys, "status", "calibrated", "metric", "value", "error"], rows)


def _series(records: list[dict], study: Study, key: str) -> list[tuple[float, dict]]:
    """(value of ``key``, record) of the points that show the effect of ``key``: the base plus
    the points varying only ``key`` (one-at-a-time), or every point (factorial, hypercube)."""
    out = []
    base_value = study.value(key)
    base_value = base_value[0] if isinstance(base_value, tuple) else base_value
    for r in records:
        if r["status"] != "ok":
            continue
        if study.design == "one_at_a_time" and set(r["changes"]) - {key}:
            continue
        x = _numeric(r["changes"].get(key, base_value), _categories(study, key))
        if x is not None:
            out.append((x, r))
    return sorted(out, key=lambda vr: vr[0])


def write_plots(records: list[dict], study: Study, out: Path) -> list[Path]:
    """One PNG per varied parameter (:func:`gripper.render.study_plots.parameter_plots`)."""
    from gripper.render.study_plots import parameter_plots

    series = {key: _series(records, study, key) for key in study.vary}
    return parameter_plots(series, metric_names(study.responses), out, title=study.name,
                           connect=study.design == "one_at_a_time")


def recommendations(records: list[dict], study: Study) -> str:
    """Markdown table: per varied parameter, the value that best meets the objective, and why."""
    names = metric_names(study.responses)
    sense, metric = study.objective or ("maximize", names[0])
    def admissible(r) -> bool:
        for bound, k, v in study.limits:
            x = r["metrics"].get(k)
            if x is None or (x < v if bound == "at_least" else x > v):
                return False
        return True

    rule = "".join(f"; only points with {k} {'>=' if b == 'at_least' else '<='} {v:g}" for b, k, v in study.limits)
    lines = [f"# {study.name}: recommendations", "",
             f"Objective: {sense} `{metric}`{rule}. One-at-a-time: each parameter moves alone from the base "
             "design; other designs: the best point overall per parameter.", "",
             "| parameter | recommended value | reason from the data | calibrated |", "|---|---|---|---|"]
    base = next((r for r in records if r["point"] == 0 and r["status"] == "ok"), None)
    base_val = base["metrics"].get(metric) if base else None
    for key in study.vary:
        given = [(v, r) for v, r in _series(records, study, key) if r["metrics"].get(metric) is not None]
        series = [(v, r) for v, r in given if admissible(r)]
        if not series:
            lines.append(f"| {key} | - | no point gave `{metric}` within the limits | - |")
            continue
        pick = (max if sense == "maximize" else min)(series, key=lambda vr: vr[1]["metrics"][metric])
        vals = [r["metrics"][metric] for _, r in series]
        reason = (f"{metric} = {pick[1]['metrics'][metric]:.4g} (range {min(vals):.4g} to {max(vals):.4g} over "
                  f"{len(series)} points" + (f"; base {base_val:.4g})" if base_val is not None else ")"))
        excluded = [_label(study, key, r) for _, r in given if not admissible(r)]
        if excluded:
            reason += f"; {', '.join(excluded)} excluded by the limits"
        failed = sum(1 for r in records if r["status"] != "ok" and key in r["changes"])
        if failed:
            reason += f"; {failed} point(s) failed"
        calibrated = "yes" if pick[1]["calibrated"] else "no"
        lines.append(f"| {key} | {_label(study, key, pick[1])} | {reason} | {calibrated} |")
    notes = sorted({r["calibration_note"] for r in records if r["status"] == "ok" and r.get("calibration_note")})
    if notes:
        lines += ["", "Not calibrated: " + " / ".join(notes) + "."]
    return "\n".join(lines) + "\n"
