"""``gripper calibrate``: fit the hinge springs."""

from __future__ import annotations

import sys

from gripper.cli.inputs import (
    given,
    number,
)
from gripper.cli.options import (
    design,
)
from gripper.core.atomic import check_output_dir


def add(sub) -> None:
    cal = sub.add_parser(
        "calibrate", help="fit the hinge springs to the flex reference finger or to bench data",
        description="Run the flexible-multibody reference bending test (a tetrahedral flex of "
                    "the finger, 2 s at 5e-4 s) and fit every hinge's stiffness and damping to "
                    "it, or fit the stiffness to bench data (--data CSV, columns in "
                    "gripper/calibration/measured.py). Writes calibration.json, report.png and "
                    "errors.csv into --out.")
    cal.add_argument("--params", metavar="FILE", help="gripper parameter file; defaults if omitted")
    cal.add_argument("--data", metavar="CSV", help="bench data instead of the reference run")
    cal.add_argument("--out", default="runs/calibration", help="output folder (default runs/calibration)")
    cal.add_argument("--reference", choices=("continuum", "fmbs", "actuator"), default="continuum",
                     help="reference kind: the continuum body (default), paper 000's flexible "
                          "multibody model (elements as flexible bodies, Table 2's hinge springs), or "
                          "'actuator': the pneumatic finger fitted to paper 001's actuator in finite "
                          "elements (0-250 kPa and its sag; about 4 minutes)")
    cal.add_argument("--reading", choices=("per_degree", "per_radian"), default="per_degree",
                     help="fmbs: read Table 2's 1.9e-3 spring per degree (as printed) or per radian")
    cal.add_argument("--no-converge", action="store_true",
                     help="skip the mesh-convergence study and its stiffness correction (quick looks)")
    cal.add_argument("--write-default", action="store_true",
                     help="regenerate the default design's committed calibration in "
                          "gripper/data/calibration/default (34 minutes measured on 2 shared cores, most "
                          "of it the reference's rest points)")
    cal.add_argument("--write-surrogate", action="store_true",
                     help="regenerate the committed stiffness surrogate of the design studies "
                          "(gripper/data/studies/stiffness_surrogate.json: six convergence studies "
                          "and 41 linear solves, about 25 minutes on 2 cores)")
    number(cal, "--mesh-scale", int, lo=1, hi=4, default=1,
           help="reference mesh refinement: 1, 2 halves every cell (slow), up to 4")
    number(cal, "--tension-max", float, lo=0, lo_open=True, hi=10.0,
           help="highest cable tension of the reference run [N]; default: the design's own (fmbs: "
                "scaled to the reading's spring)")
    number(cal, "--levels", int, lo=2, hi=50, default=5, help="tension levels")
    cal.add_argument("--held-out", default="2",
                     help="comma-separated static points left out of the fit (default 2)")
    cal.set_defaults(func=run)


def run(args) -> int:
    from gripper.calibration.calfile import PAPER_STIFFNESS_NM_PER_DEG
    from gripper.calibration.fit import FitConfig
    from gripper.calibration.pipeline import calibrate, write_default_calibration
    from gripper.calibration.report import error_table, format_table
    from gripper.references.continuum import ReferenceConfig
    from gripper.references.finger_mesh import MeshResolution
    from gripper.references.fmbs import FmbsConfig

    _check_applies(args)
    if args.write_surrogate:
        from gripper.calibration.surrogate import StiffnessSurrogate, correction_model

        say = lambda m: print(m, file=sys.stderr)  # noqa: E731
        sur = StiffnessSurrogate.build(correction=correction_model(on_progress=say),
                                       on_progress=say)
        path = sur.save()
        print(f"wrote {path}: {len(sur.samples)} designs, leave-one-out stiffness error "
              f"{100 * sur.loo_error.max():.2f} % at most")
        return 0
    if args.reference == "actuator":
        return _run_actuator(args)
    if args.write_default:
        if args.params or args.data or args.reference != "continuum":
            raise ValueError("--write-default: takes no --params, --data or --reference (it "
                             "calibrates the default design on the continuum reference)")
        cal = write_default_calibration(on_progress=lambda m: print(m, file=sys.stderr))
        print(f"wrote gripper/data/calibration/default/calibration.json: stiffness "
              f"{', '.join(f'{k:.4g}' for k in cal.stiffness)} N·m/rad")
        return 0
    from gripper.calibration.pipeline import DEFAULT_FILES

    check_output_dir(args.out, files=DEFAULT_FILES)
    p = design(args, simulates=False)  # the calibration runs its own reference; a bad design fails it
    ref = None
    if args.mesh_scale != 1 or args.tension_max is not None or args.levels != 5:
        ref = ReferenceConfig(mesh=MeshResolution(scale=args.mesh_scale),
                              tension_max=args.tension_max or ReferenceConfig().tension_max,
                              n_levels=args.levels)
    try:
        held = tuple(int(v) for v in args.held_out.split(",") if v.strip()) if args.held_out else ()
    except ValueError:
        raise ValueError(f"--held-out: expected comma-separated level indices, got "
                         f"{args.held_out!r}") from None
    fit = FitConfig(fit_damping=args.data is None, held_out=held)
    fmbs = FmbsConfig(reading=args.reading) if args.reference == "fmbs" else None
    cal, result, record = calibrate(args.out, p, data=args.data, reference=ref, fit=fit,
                                    kind=args.reference, fmbs=fmbs,
                                    converge=not args.no_converge, auto_tension=args.tension_max is None,
                                    on_progress=lambda m: print(m, file=sys.stderr))
    print(format_table(error_table(record, result)))
    m = cal.metrics
    if m.get("tip_rms_frac") is not None:
        print(f"tip RMS error {m['tip_rms_m'] * 1e3:.2f} mm = {100 * m['tip_rms_frac']:.2f} % "
              f"of the finger length")
    for h in m["held_out"]:
        parts = [f"held-out level {h['level']} ({h['tension_N']:.3g} N):"]
        if h["tip_error_frac"] is not None:
            parts.append(f"tip error {100 * h['tip_error_frac']:.2f} % of length")
        if h["bending_error_frac"] is not None:
            parts.append(f"bending angle error {100 * h['bending_error_frac']:.2f} %")
        print(" ".join(parts))
    settled = m.get("settled")
    if settled and settled.get("tip_rms_frac") is not None:
        errs = ", ".join(f"{lv['tension_N']:.3g} N: {100 * lv['bending_error_frac']:.1f} %"
                         for lv in settled["levels"] if lv["bending_error_frac"] is not None)
        print(f"fitted finger at rest at the static points: tip RMS error "
              f"{100 * settled['tip_rms_frac']:.2f} % of length; bending angle error {errs}")
    print(f"paper 000 Table 2: {PAPER_STIFFNESS_NM_PER_DEG:g} N·m/deg per hinge")
    print(f"fit {m['fit_wall_time_s']:.1f} s wall; wrote {args.out}/calibration.json, "
          f"report.png, errors.csv")
    return 0


def _run_actuator(args) -> int:
    """``--reference actuator``: the pneumatic finger against paper 001's actuator."""
    from gripper.calibration.pneumatic_fit import (
        PNEUMATIC_FILES,
        calibrate_pneumatic,
        write_default_pneumatic_calibration,
    )

    say = lambda m: print(m, file=sys.stderr)  # noqa: E731
    if args.data or args.mesh_scale != 1 or args.tension_max is not None:
        raise ValueError("--reference actuator: takes no --data, --mesh-scale or --tension-max (the reference is "
                         "the finite-element actuator on the studies' mesh)")
    if args.write_default:
        if args.params:
            raise ValueError("--write-default: takes no --params (it calibrates the default pneumatic finger)")
        cal = write_default_pneumatic_calibration(on_progress=say)
        out = "gripper/data/calibration/pneumatic"
    else:
        check_output_dir(args.out, files=PNEUMATIC_FILES)
        p = design(args, simulates=False)
        cal, _, _ = calibrate_pneumatic(args.out, p, on_progress=say)
        out = args.out
    m = cal["metrics"]
    print(f"tip RMS error {100 * m['tip_rms_frac']:.2f} % of the length over the fitted pressures "
          f"(largest {100 * m['tip_max_frac']:.2f} %); sag {100 * m['sag_tip_error_frac']:.2f} %")
    for h in m["held_out"]:
        print(f"held-out {h['pressure_kPa']:g} kPa: tip error {100 * h['tip_error_frac']:.2f} % of the length")
    print("fitted: " + ", ".join(f"{k} {v:.4g}" for k, v in cal["fitted"].items()))
    print(f"fit {m['fit_wall_time_s']:.1f} s wall; wrote {out}/calibration.json, reference.json, report.png")
    return 0


# The options that set up the reference run: bench data (--data) replaces that run.
REFERENCE_OPTIONS = ("reference", "reading", "mesh_scale", "tension_max", "levels", "no_converge")


def _check_applies(args) -> None:
    """Refuse an option the chosen calibration would ignore, naming it."""
    if args.data:
        for dest in REFERENCE_OPTIONS:
            if given(args, dest):
                raise ValueError(f"--{dest.replace('_', '-')}: sets up the reference run, which --data replaces "
                                 "(bench data is fitted as measured); leave one of them out")
    if given(args, "reading") and args.reference != "fmbs":
        raise ValueError("--reading: how paper 000's spring is read by --reference fmbs; this calibration uses "
                         f"--reference {args.reference}")
