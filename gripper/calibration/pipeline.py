"""``gripper calibrate``: reference run (or bench data) -> hinge fit -> calibration file + report.

Example:
    >>> from gripper.calibration.pipeline import calibrate
    >>> cal, fit, record = calibrate("runs/calibration")         # doctest: +SKIP
"""

from __future__ import annotations

import json
from dataclasses import asdict
from pathlib import Path

from gripper.calibration.calfile import Calibration, design_hash
from gripper.calibration.fit import FitConfig, FitResult, fit_hinges
from gripper.calibration.measured import read_measured_csv
from gripper.calibration.reference import BendingRecord, ReferenceConfig, run_reference
from gripper.calibration.report import write_report
from gripper.params import GripperParams


def calibrate(out_dir: str | Path, params: GripperParams | None = None, *,
              data: str | Path | None = None, reference: ReferenceConfig | None = None,
              fit: FitConfig | None = None, on_progress=None
              ) -> tuple[Calibration, FitResult, BendingRecord]:
    """Run the reference (or read ``data``), fit, write ``calibration.json`` and the report.

    Files in ``out_dir``: ``calibration.json``, ``report.png``, ``errors.csv`` and, for a
    reference run, ``reference.json`` (the reference record).

    Raises:
        ValueError: bad parameters, settings or data file.
        SimulationUnstable: the reference run went unstable.
    """
    p = (params or GripperParams()).validate()
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    say = on_progress or (lambda msg: None)
    if data is not None:
        fit_cfg = fit or FitConfig(fit_damping=False)
        if fit_cfg.fit_damping:
            raise ValueError("fit.fit_damping: bench data are static points; damping needs the "
                             "reference's transient")
        record = read_measured_csv(data, p.finger.n_segments, min_points=p.finger.n_hinges,
                                   closure_angle_deg=p.finger.closure_angle_deg)
        source, settings = "measured", {"data": str(data)}
        say(f"read {len(record.static)} static points from {data}")
    else:
        ref_cfg = (reference or ReferenceConfig()).validate()
        fit_cfg = fit or FitConfig()
        say("reference run (flex finger, this takes several minutes) ...")
        record = run_reference(p, ref_cfg)
        source, settings = "reference", {"reference": ref_cfg.to_dict()}
        (out / "reference.json").write_text(json.dumps(record.to_json_dict()) + "\n")
        say(f"reference: {record.wall_time_s:.1f} s wall")
    say("fitting the hinge model ...")
    result = fit_hinges(record, p, fit_cfg)
    settings["fit"] = asdict(fit_cfg)
    metrics = dict(result.metrics, fit_wall_time_s=result.wall_time_s,
                   fit_iterations=result.iterations)
    if source == "reference":
        metrics["reference_wall_time_s"] = record.wall_time_s
    cal = Calibration(design_hash=design_hash(p), source=source,
                      stiffness=tuple(float(v) for v in result.stiffness),
                      damping=tuple(float(v) for v in result.damping),
                      rest_angle_deg=tuple(float(v) for v in result.rest_angle_deg),
                      metrics=metrics, settings=settings)
    cal.save(out / "calibration.json")
    write_report(out, record, result, title=source)
    return cal, result, record
