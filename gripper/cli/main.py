"""The ``gripper`` command.

Subcommands: ``bend`` (paper 000's bending test), ``servo`` (servo model against its
datasheet), ``params`` (write the default parameter file), ``write-models`` (regenerate
``models/soft_gripper``), ``check`` (step the scene under random servo commands), ``bench``
(the grasp benchmark), ``pullout`` (holding force), ``video`` (render one trial), ``train``
(PPO or SAC on the environment) and ``play`` (video of a trained policy).

Errors in input (bad parameter, malformed file) print one line on stderr and exit with code 2.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import textwrap

from gripper.bench.defaults import DEFAULT_TRIALS, DEFAULT_WORKERS
from gripper.bench.execution import check_scheduler
from gripper.cli.inputs import (
    MAX_SIMULATED_S,
    PIXELS,
    TRIALS_MAX,
    WORKERS_MAX,
    OneLineParser,
    field_option,
    names,
    number,
    numbers,
    seed_option,
)
from gripper.core.atomic import check_output_dir, check_output_file
from gripper.core.params import GripperParams, parameter_help
from gripper.experiments.protocol import (
    APPROACHES,
    CRUSH_DEPTH,
    CRUSH_HOLD_S,
    CRUSH_SPEED,
    GRASP_CHOICES,
    POLICIES,
    PULL_MAX,
    PULL_RATE,
    BendingConfig,
    GraspProtocol,
    TrialNoise,
)

EXIT_BAD_INPUT = 2
EXIT_UNSTABLE = 3
EXIT_BROKEN_PIPE = 1
EXIT_INTERRUPTED = 130  # 128 + SIGINT, as shells report a command ended by Ctrl-C


def _params(args, *, simulates: bool = True) -> GripperParams:
    """The parameters the options give; ``simulates``: also check, before any work and any file,
    that the design can be stepped at all (:func:`gripper.sim.preflight.check_design`)."""
    p = _read_params(args)
    if simulates:
        from gripper.sim.preflight import check_design

        check_design(p, "--params" if args.params else "--calibration")
    return p


def _read_params(args) -> GripperParams:
    p = GripperParams.load(args.params) if args.params else GripperParams().validate()
    springs = getattr(args, "springs", "calibrated")
    if springs != "calibrated":
        if getattr(args, "calibration", None):
            raise ValueError("--springs: give either --springs or --calibration, not both")
        from gripper.core.params import HingeSprings

        reading = "per_degree" if springs == "paper" else "per_radian"
        p = p.replace(springs=HingeSprings.paper(reading, closure=p.springs.closure,
                                                 closure_stiffness=p.springs.closure_stiffness))
        p = p.validate()
    if getattr(args, "calibration", None):
        from gripper.calibration.calfile import apply_calibration

        p = apply_calibration(p, args.calibration, force=args.force_calibration)
    return p


def _cmd_bend(args) -> int:
    from gripper.experiments.bending import BendingConfig, run_bending_test

    cfg = BendingConfig(r_max=args.r_max, duration=args.duration, timestep=args.timestep,
                        mode=args.mode, n_points=args.points)
    if args.figure:
        from gripper.render.figures import bending_figure

        res = bending_figure(args.figure, cfg, _params(args))
        print(f"wrote {args.figure}", file=sys.stderr if args.json else sys.stdout)
    else:
        res = run_bending_test(cfg, _params(args))
    if args.json:
        json.dump(res.to_json_dict(), sys.stdout)
        sys.stdout.write("\n")
        return 0
    print(f"bending test ({cfg.mode}, {cfg.duration:g} s at {cfg.timestep:g} s step, "
          f"wall {res.wall_time_s:.3f} s, {res.warnings} MuJoCo warnings)")
    print(f"{'r':>7} {'tension N':>10} {'bend deg':>9}  tip x,y,z [mm]")
    stride = max(1, len(res.r) // 10)
    for i in sorted({*range(0, len(res.r), stride), len(res.r) - 1}):
        tip = ", ".join(f"{v * 1e3:6.1f}" for v in res.tip_xyz_m[i])
        print(f"{res.r[i]:7.3f} {res.tension_N[i]:10.3f} {res.bending_angle_deg[i]:9.2f}  {tip}")
    return 0


def _cmd_servo(args) -> int:
    from gripper.experiments.servo_check import measure_servo

    m = measure_servo(_params(args))
    print(f"servo preset {m.datasheet.name}: {m.datasheet.description}")
    print(f"{'figure':<24} {'model':>10} {'datasheet':>10} {'error':>8}")
    for name, model, sheet in m.rows():
        print(f"{name:<24} {model:10.4f} {sheet:10.4f} {100 * (model / sheet - 1):7.2f}%")
    print(f"max cable tension: {m.max_cable_tension:.2f} N (stall torque / spool radius)")
    return 0


def _cmd_params(args) -> int:
    check_output_file(args.out, "--out", (".json", ".toml"))
    path = _params(args, simulates=False).save(args.out)
    print(f"wrote {path}")
    return 0


def _cmd_write_models(args) -> int:
    from gripper.sim.model_files import GRIPPER_FILE, SCENE_FILE, default_model_dir, write_model_files

    target = args.out or default_model_dir()
    if target is None:
        raise ValueError("--out: give a folder (outside a source checkout there is no models/ to refresh, "
                         "and the installed package's copy is not written to)")
    out = check_output_dir(target, files=(GRIPPER_FILE, SCENE_FILE, "README.md"))
    for path in write_model_files(out, _params(args, simulates=False)):
        print(f"wrote {path}")
    return 0


def _cmd_check(args) -> int:
    from gripper.core.timesteps import check_step_budget
    from gripper.experiments.smoke import random_control_rollout

    p = _params(args)
    check_step_budget(args.duration, p.sim.timestep, "--duration")
    res = random_control_rollout(p, duration=args.duration, seed=args.seed)
    print(f"{res['steps']} steps, {res['sim_time_s']:.2f} s simulated in {res['wall_time_s']:.2f} "
          f"s wall ({res['realtime_factor']:.1f}× real time), MuJoCo warnings: 0, state finite")
    return 0


def _objects(text: str, flag: str = "--objects") -> tuple[str, ...]:
    """Object specs, each resolved once here so a bad one is refused before any work."""
    from gripper.objects.library import get_object

    specs = names(text, flag)
    for spec in specs:
        try:
            get_object(spec)
        except ValueError as e:
            text = str(e)
            raise ValueError(f"{flag}: {text.removeprefix('objects: ')}") from None
    return specs


def _check_runner(args) -> None:
    """Refuse an unreachable --scheduler before any work (--workers is bounded by its type)."""
    check_scheduler(args.scheduler)


def _cmd_bench(args) -> int:
    from gripper.bench.benchmark import RUN_FILES, BenchConfig, format_table, run_benchmark

    check_output_dir(args.out, files=RUN_FILES)
    _check_runner(args)
    proto, noise = _protocol_and_noise(args)
    cfg = BenchConfig(objects=_objects(args.objects), trials=args.trials, seed=args.seed,
                      params=_params(args), protocol=proto, noise=noise).validate()
    if args.plot:
        check_output_file(args.plot, "--plot", (".png",))  # before the run: a bad path must not cost one
    summary = run_benchmark(cfg, args.out, workers=args.workers, scheduler=args.scheduler,
                            progress=not args.no_progress)
    print(format_table(summary))
    print(f"wrote {args.out}/trials.jsonl, summary.csv, summary.json")
    if args.plot:
        from gripper.render.figures import success_plot

        success_plot(summary, args.plot)
        print(f"wrote {args.plot}")
    errors = sum(s["errors"] for s in summary["objects"].values())
    return EXIT_UNSTABLE if errors else 0


def _protocol_and_noise(args):
    proto = GraspProtocol(close_command_scale=args.close_scale, release=args.release, policy=args.policy,
                          grip_tension=args.grip_tension, approach=args.approach, grasp=args.grasp,
                          centre=not args.no_centre).validate()
    noise = TrialNoise(xy=args.noise, mass_frac=args.mass_noise, friction_frac=args.friction_noise).validate()
    return proto, noise


def _cmd_video(args) -> int:
    from gripper.objects.library import get_object
    from gripper.render.video import VIDEO_SUFFIXES, record_trial_video

    check_output_file(args.out, "--out", VIDEO_SUFFIXES)
    if args.still:
        check_output_file(args.still, "--still", (".png",))
    proto, noise = _protocol_and_noise(args)
    obj = get_object(_objects(args.object, "--object")[0])
    res = record_trial_video(obj, args.out, seed=args.seed, index=args.index, params=_params(args),
                             protocol=proto, noise=noise, width=args.width, height=args.height, fps=args.fps,
                             camera=args.camera, overlay=not args.no_overlay, still=args.still,
                             on_progress=lambda msg: print(msg, file=sys.stderr, flush=True))
    outcome = "error" if res["status"] == "error" else ("success" if res["success"] else
                                                        f"failed ({res['failed_phase']})")
    print(f"{res['trial_id']}: {outcome}; wrote {res['video']} ({res['frames']} frames, "
          f"{res['width']}x{res['height']} at {res['fps']:g} fps); simulate {res['simulate_s']:.1f} s, "
          f"render {res['render_s']:.1f} s ({res['render_fps']:.1f} frames/s), encode {res['encode_s']:.1f} s")
    return EXIT_UNSTABLE if res["status"] == "error" else 0


def _needs_rl(command: str) -> None:
    import importlib.util

    if importlib.util.find_spec("stable_baselines3") is None or importlib.util.find_spec("torch") is None:
        raise ValueError(f"{command}: needs the rl extra (stable-baselines3 and torch): "
                         "pip install 'gripper[rl]' (in this repository: .venv/bin/pip install -e '.[rl]')")


def _hyperparam_overrides(items: list[str], flag: str = "--set") -> dict:
    out = {}
    for item in items or []:
        key, sep, value = item.partition("=")
        if not sep or not key:
            raise ValueError(f"{flag}: expected KEY=VALUE, got {item!r}")
        try:
            out[key.strip()] = json.loads(value)
        except json.JSONDecodeError:
            out[key.strip()] = value.strip()
    return out


def _cmd_train(args) -> int:
    from gripper.rl.config import TrainConfig

    cfg = TrainConfig(algo=args.algo, objects=_objects(args.objects),
                      action_mode=args.action_mode, xy_actions=args.xy, steps=args.steps, seed=args.seed,
                      n_envs=args.n_envs, chunk_steps=args.chunk_steps, eval_episodes=args.eval_episodes,
                      hyperparams=_hyperparam_overrides(args.set),
                      reward_weights=_hyperparam_overrides(args.reward_weight, "--reward-weight")).validate()
    from gripper.rl.training import RUN_FILES as TRAIN_FILES

    check_output_dir(args.out, files=TRAIN_FILES)
    if args.video:
        from gripper.render.video import VIDEO_SUFFIXES

        check_output_file(args.video, "--video", VIDEO_SUFFIXES)
    _needs_rl("train")
    from gripper.rl.training import train

    def show(row):
        per = " ".join(f"{k[5:]} {v:.2f}" for k, v in row.items() if k.startswith("eval_") and k not in (
            "eval_success", "eval_return"))
        # no training episode has ended yet: nothing to average (the row holds NaN)
        train = (f"success {row['train_success']:.2f}, return {row['train_return']:7.1f}"
                 if row["train_episodes"] else "no episode ended yet")
        print(f"{row['steps']:>9} steps {row['wall_s']:>8.0f} s  train: {row['train_episodes']:>4} episodes, "
              f"{train}  eval: success {row['eval_success']:.2f} ({per})", flush=True)

    rows = train(cfg, args.out, resume=args.resume, on_progress=show)
    print(f"wrote {args.out}/policy.zip and progress.csv ({len(rows)} evaluations)")
    if args.video:
        return _play(args.out, args.video, args.video_seed, 640, 480, "front")
    return 0


def _play(run, out, seed, width, height, camera) -> int:
    from gripper.rl.policy_video import record_policy_video
    from gripper.rl.training import load_policy

    cfg, act = load_policy(run)
    res = record_policy_video(act, cfg.env_kwargs(), out, seed=seed, width=width, height=height, camera=camera,
                              on_progress=lambda msg: print(msg, file=sys.stderr, flush=True))
    print(f"{res['object']}, seed {seed}: {'held' if res['success'] else 'not held'}; wrote {res['video']} "
          f"({res['frames']} frames at {res['fps']:g} fps)")
    return 0


def _cmd_play(args) -> int:
    from gripper.render.video import VIDEO_SUFFIXES

    check_output_file(args.out, "--out", VIDEO_SUFFIXES)
    _needs_rl("play")
    return _play(args.run, args.out, args.seed, args.width, args.height, args.camera)


def _cmd_calibrate(args) -> int:
    from gripper.calibration.calfile import PAPER_STIFFNESS_NM_PER_DEG
    from gripper.calibration.fit import FitConfig
    from gripper.calibration.fmbs import FmbsConfig
    from gripper.calibration.mesh import MeshResolution
    from gripper.calibration.pipeline import calibrate, write_default_calibration
    from gripper.calibration.reference import ReferenceConfig
    from gripper.calibration.report import error_table, format_table

    if args.write_surrogate:
        from gripper.calibration.surrogate import StiffnessSurrogate, correction_model

        say = lambda m: print(m, file=sys.stderr)  # noqa: E731
        sur = StiffnessSurrogate.build(correction=correction_model(on_progress=say),
                                       on_progress=say)
        path = sur.save()
        print(f"wrote {path}: {len(sur.samples)} designs, leave-one-out stiffness error "
              f"{100 * sur.loo_error.max():.2f} % at most")
        return 0
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
    p = _params(args, simulates=False)  # the calibration runs its own reference; a bad design fails it
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


def _cmd_study(args) -> int:
    from gripper.studies.study import RUN_FILES, load_study, run_study

    check_output_dir(args.out, files=RUN_FILES)
    study = load_study(args.file)
    _check_runner(args)
    records = run_study(study, args.out, workers=args.workers, scheduler=args.scheduler,
                        progress=not args.no_progress)
    failed = sum(r["status"] != "ok" for r in records)
    print((open(f"{args.out}/recommendations.md").read()).rstrip())
    print(f"{len(records)} design points ({failed} failed); wrote {args.out}/results.jsonl, results.csv, "
          "plot_*.png, recommendations.md")
    return 0


def _cmd_pullout(args) -> int:
    from gripper.experiments.protocol import GraspProtocol
    from gripper.experiments.pullout import run_pullout

    objects = _objects(args.objects)
    policy = args.policy
    base = GraspProtocol(policy=policy)
    grips = numbers(args.grip_tension, "--grip-tension", lo=0, lo_open=True) if policy == "controller" else (
        base.grip_tension,)
    protos = [base.replace(grip_tension=g) for g in grips]
    if args.plot:
        check_output_file(args.plot, "--plot", (".png",))
    params = _params(args)
    results = []
    for name in objects:
        for proto in protos:
            res = run_pullout(name, params=params, protocol=proto, rate=args.rate, max_force=args.max_force)
            results.append(res)
            bound = ">=" if res["held_at_max"] else ""
            grip = f"grip {res['grip_tension_N']:g} N: " if res["grip_tension_N"] is not None else "per_object: "
            print(f"{name:<10} {grip}holding force {bound}{res['holding_force_N']:.2f} N "
                  f"(pull ramp {res['rate_N_per_s']:g} N/s until {res['slip_m'] * 1e3:g} mm slip)")
    if args.plot:
        from gripper.render.figures import holding_force_plot

        holding_force_plot(results, args.plot)
        print(f"wrote {args.plot}")
    return 0


def _cmd_envelope(args) -> int:
    from gripper.studies.envelope import RUN_FILES, load_envelope, run_envelope

    check_output_dir(args.out, files=RUN_FILES)
    lists = {key: (names(v, "--shapes") if key == "shapes" else numbers(v, f"--{key}", lo=0, lo_open=True))
             for key in ("shapes", "sizes", "masses", "frictions") if (v := getattr(args, key)) is not None}
    env = load_envelope(args.file, trials=args.trials, seed=args.seed, grip_tension=args.grip_tension, **lists)
    _check_runner(args)
    summary = run_envelope(env, args.out, workers=args.workers, scheduler=args.scheduler,
                           progress=not args.no_progress)
    print(f"capability envelope at a grip of {summary['grip_tension_N']:g} N "
          f"(held: at least {summary['held_fraction']:.0%} of {env.trials} trials)")
    for shape, s in summary["shapes"].items():
        rng = s["gripping_range_m"]
        grip = f"{rng[0] * 1e3:g}-{rng[1] * 1e3:g} mm" if rng else "none held"
        pay = f"{s['payload_kg']:g} kg" if s["payload_kg"] is not None else "none held"
        print(f"{shape:<10} gripping range {grip:<14} payload {pay}")
    print(f"{summary['errors']} unstable trials, {summary.get('no_object', 0)} with no object seen, "
          f"{summary['warnings']} MuJoCo warnings; wrote {args.out}/"
          "trials.jsonl, envelope.csv, summary.json, map_*.png")
    return EXIT_UNSTABLE if summary["errors"] else 0


def _cmd_crush(args) -> int:
    from gripper.experiments.crush import crush_test

    params = _params(args)
    for name in _objects(args.objects):
        res = crush_test(name, args.depth, speed=args.speed, hold_s=args.hold, params=params)
        if args.json:
            print(json.dumps(res))
            continue
        flag = "DAMAGED" if res["damaged"] else "intact"
        print(f"{name:<10} pressed {res['depth_m'] * 1e3:g} mm: {flag}, {res['damage_measure_name']} "
              f"{res['damage_measure']:.4g} (limit {res['damage_limit']:g}), peak plate force "
              f"{res['peak_plate_force_N']:.2f} N")
    return 0


def _version_text() -> str:
    from importlib.metadata import version

    import mujoco

    return f"gripper {version('gripper')} (MuJoCo {mujoco.__version__})"


def build_parser() -> argparse.ArgumentParser:
    parser = OneLineParser(
        prog="gripper",
        description="Simulate a four-finger cable-driven soft gripper in MuJoCo. "
                    "All quantities in SI units unless a name says otherwise.")
    parser.add_argument("--version", action="version", version=_version_text())
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND",
                                title="commands (gripper COMMAND --help for each)")

    def with_protocol(p):
        proto = GraspProtocol()
        field_option(p, "--noise", TrialNoise, "xy", "x/y placement noise half-range [m]")
        field_option(p, "--mass-noise", TrialNoise, "mass_frac", "mass noise fraction, e.g. 0.2")
        field_option(p, "--friction-noise", TrialNoise, "friction_frac", "friction noise fraction")
        p.add_argument("--policy", choices=POLICIES, default=proto.policy,
                       help="controller: close each finger until its cable tension reaches --grip-tension, "
                            "knowing nothing of the object; per_object: each object's own closing command "
                            "(default %(default)s)")
        field_option(p, "--grip-tension", GraspProtocol, "grip_tension",
                     "the controller's grip set-point: cable tension per finger [N]", metavar="N")
        field_option(p, "--close-scale", GraspProtocol, "close_command_scale",
                     "per_object: multiplier on each object's closing command, >1 squeezes harder")
        p.add_argument("--release", action="store_true", help="open the fingers at the end of each trial")
        p.add_argument("--approach", choices=APPROACHES, default=proto.approach,
                       help="sensed: the palm camera finds the object; catalogue: the object's size, centred "
                            "under the palm (0.11.0's rule) (default %(default)s)")
        p.add_argument("--grasp", choices=GRASP_CHOICES, default=proto.grasp,
                       help="auto: the fingertip grasp where the tips reach the table beside the object, else "
                            "the envelope; or force one (default %(default)s)")
        p.add_argument("--no-centre", action="store_true",
                       help="sensed approach: do not centre the palm over the sensed object")
        return p

    def with_runner(p):
        number(p, "--workers", int, lo=1, hi=WORKERS_MAX, default=DEFAULT_WORKERS, help="local worker processes")
        p.add_argument("--scheduler", metavar="ADDRESS", help="existing Dask scheduler, e.g. tcp://host:8786")
        p.add_argument("--no-progress", action="store_true", help="no progress bar")
        return p

    def with_params(p):
        p.add_argument("--params", metavar="FILE",
                       help="gripper parameter file (.json or .toml); defaults if omitted")
        p.add_argument("--calibration", metavar="FILE",
                       help="calibration file from 'gripper calibrate': its fitted hinge springs "
                            "replace those of the parameters")
        p.add_argument("--force-calibration", action="store_true",
                       help="apply --calibration even if it was made for another design")
        from gripper.core.params import SPRING_SETS

        p.add_argument("--springs", choices=SPRING_SETS, default="calibrated",
                       help="hinge springs: the committed calibration (default), or paper 000's "
                            "Table 2 spring read as printed (paper: 1.9e-3 N·m/deg) or per "
                            "radian (paper_per_radian), for comparison")
        return p

    b = with_params(sub.add_parser(
        "bend", help="paper 000's bending test of one finger",
        description="Ramp the cable shortening rate r from 0 to r_max over the run (dynamic) or "
                    "hold each of --points set-points until at rest (quasi_static); record "
                    "hinge angles, bending angle, tip position and cable tension."))
    b.add_argument("--json", action="store_true",
                   help="print a JSON object with arrays r, tension_N, joint_angles_deg, "
                        "bending_angle_deg, tip_xyz_m")
    b.add_argument("--mode", choices=("dynamic", "quasi_static"), default=BendingConfig().mode,
                   help="dynamic: one ramp, as paper 000 ran it; quasi_static: each set-point held until at rest "
                        "(default %(default)s)")
    b.add_argument("--figure", metavar="FILE.png",
                   help="also write a PNG: side-view montage of the finger at six shortening rates "
                        "and the bending-angle curve")
    field_option(b, "--r-max", BendingConfig, "r_max", "final shortening rate")
    field_option(b, "--duration", BendingConfig, "duration", "ramp time [s]")
    field_option(b, "--timestep", BendingConfig, "timestep", "step [s], paper 000 §IV")
    field_option(b, "--points", BendingConfig, "n_points", "samples or set-points")
    b.set_defaults(func=_cmd_bend)

    s = with_params(sub.add_parser(
        "servo", help="servo model against its datasheet",
        description="Measure the servo model (the gripper's dcmotor actuator and its position loop) as "
                    "a bench would: no-load speed, stall torque, and the cable tension they give, each "
                    "against the datasheet of the --params servo preset."))
    s.set_defaults(func=_cmd_servo)

    p = with_params(sub.add_parser(
        "params", help="write a parameter file (defaults or --params)",
        description=textwrap.fill("Write the gripper parameters (the defaults, or --params with any "
                                  "--springs or --calibration applied) to a .json or .toml file. Every "
                                  "field, its unit, allowed range and source:", 78),
        epilog=parameter_help(), formatter_class=argparse.RawDescriptionHelpFormatter))
    p.add_argument("--out", required=True, metavar="FILE", help=".json or .toml")
    p.set_defaults(func=_cmd_params)

    w = with_params(sub.add_parser(
        "write-models", help="regenerate models/soft_gripper (the MJCF the trials run)",
        description="Write the gripper's MJCF (soft_gripper.xml, scene.xml) for the parameters, as "
                    "the trials run it, and refresh the model README's parameter table, into --out."))
    w.add_argument("--out", metavar="DIR",
                   help="output folder (default: the source checkout's models/soft_gripper; an installed "
                        "package's own copy is never written)")
    w.set_defaults(func=_cmd_write_models)

    c = with_params(sub.add_parser(
        "check", help="step the scene under random servo commands",
        description="A smoke test of a design: step the gripper scene with every actuator given a "
                    "uniform random command over its range, renewed every 0.1 s; fail on any MuJoCo "
                    "warning or non-finite state."))
    number(c, "--duration", float, lo=0, lo_open=True, hi=MAX_SIMULATED_S, default=2.0, help="simulated time [s]")
    seed_option(c, help="seed of the random commands", default=0)
    c.set_defaults(func=_cmd_check)

    from gripper.objects.library import DEFAULT_OBJECTS
    bn = with_params(sub.add_parser(
        "bench", help="grasp benchmark: seeded scripted trials on each object",
        description="Run --trials scripted grasp trials per object (settle, approach, close, lift "
                    "0.10 m, hold 2 s, shake ±10 mm at 2 Hz for 2 s) and write trials.jsonl, "
                    "summary.csv and summary.json into --out. Rerunning into the same folder resumes. "
                    "Objects: " + ", ".join(DEFAULT_OBJECTS) + ", or mesh:PATH (STL/OBJ/PLY, metres)."))
    bn.add_argument("--objects", default=",".join(DEFAULT_OBJECTS), help="comma-separated names")
    number(bn, "--trials", int, lo=1, hi=TRIALS_MAX, default=DEFAULT_TRIALS, help="trials per object")
    seed_option(bn, default=0)
    bn.add_argument("--out", default="runs/bench", metavar="DIR", help="output folder (default runs/bench)")
    with_runner(with_protocol(bn))
    bn.add_argument("--plot", metavar="FILE.png", help="also write the success rates with Wilson 95 %% intervals")
    bn.set_defaults(func=_cmd_bench)

    from gripper.render.renderer import CAMERAS
    v = with_protocol(with_params(sub.add_parser(
        "video", help="render one scripted trial to MP4 or GIF (headless)",
        description="Run one scripted grasp trial (the benchmark's protocol and options), record its "
                    "state at the video rate and render it offscreen with MuJoCo (MUJOCO_GL=egl by "
                    "default), then write H.264 MP4 or GIF with mediapy.")))
    v.add_argument("--object", required=True, help="object name (" + ", ".join(DEFAULT_OBJECTS) + ") or mesh:PATH")
    seed_option(v, default=0)
    number(v, "--index", int, lo=0, hi=TRIALS_MAX - 1, default=0, help="trial index within the seed")
    v.add_argument("--out", required=True, metavar="FILE", help="output .mp4 or .gif")
    v.add_argument("--camera", default="front", help="camera preset: " + ", ".join(CAMERAS) + " (default front)")
    number(v, "--width", int, lo=PIXELS[0], hi=PIXELS[1], default=640, help="pixels")
    number(v, "--height", int, lo=PIXELS[0], hi=PIXELS[1], default=480, help="pixels")
    number(v, "--fps", float, lo=1, hi=240, default=30.0, help="frames per second")
    v.add_argument("--no-overlay", action="store_true", help="no text overlay (phase, time, cable tensions)")
    v.add_argument("--still", metavar="FILE.png", help="also write the first frame of the hold phase as PNG")
    v.set_defaults(func=_cmd_video)

    st = sub.add_parser(
        "study", help="design-parameter study from a TOML file (paper 001's method)",
        description="Vary design parameters (one at a time, factorial or Latin hypercube), compute the "
                    "responses of every design point on Dask, and write results.jsonl, results.csv, one "
                    "plot per parameter and recommendations.md into --out. Rerunning resumes.")
    st.add_argument("file", metavar="FILE.toml",
                    help="a study file, or a shipped study by name: one_at_a_time, latin_hypercube")
    st.add_argument("--out", required=True, metavar="DIR", help="run folder (new, or the study's own to resume)")
    with_runner(st)
    st.set_defaults(func=_cmd_study)

    ev = sub.add_parser(
        "envelope", help="capability envelope: shapes x sizes x masses x frictions under the controller",
        description="Grasp rigid spheres, cylinders and boxes over a grid of sizes, masses and frictions "
                    "with the grasp controller at one set-point; write trials.jsonl, envelope.csv, "
                    "summary.json (gripping range and payload per shape) and map_<shape>.png into --out. "
                    "Rerunning resumes.")
    ev.add_argument("file", nargs="?", default="default", metavar="FILE.toml",
                    help="an envelope file, or the shipped one by name: default (the default)")
    ev.add_argument("--out", required=True, metavar="DIR", help="run folder (new, or the envelope's own to resume)")
    ev.add_argument("--shapes", metavar="S[,S...]", help="sphere, cylinder, box (default: the file's)")
    ev.add_argument("--sizes", metavar="M[,M...]", help="widths [m], sphere: diameter (default: the file's)")
    ev.add_argument("--masses", metavar="KG[,KG...]", help="masses [kg] (default: the file's)")
    ev.add_argument("--frictions", metavar="MU[,MU...]", help="friction coefficients (default: the file's)")
    number(ev, "--trials", int, lo=1, hi=TRIALS_MAX, help="trials per point; default: the file's")
    seed_option(ev, help="base seed; default: the file's")
    field_option(ev, "--grip-tension", GraspProtocol, "grip_tension", "set-point [N]; default: the file's, "
                 "else the protocol's", metavar="N", default=None)
    with_runner(ev)
    ev.set_defaults(func=_cmd_envelope)

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
    cal.add_argument("--reference", choices=("continuum", "fmbs"), default="continuum",
                     help="reference kind: the continuum body (default) or paper 000's flexible "
                          "multibody model (elements as flexible bodies, Table 2's hinge springs)")
    cal.add_argument("--reading", choices=("per_degree", "per_radian"), default="per_degree",
                     help="fmbs: read Table 2's 1.9e-3 spring per degree (as printed) or per radian")
    cal.add_argument("--no-converge", action="store_true",
                     help="skip the mesh-convergence study and its stiffness correction (quick looks)")
    cal.add_argument("--write-default", action="store_true",
                     help="regenerate the default design's committed calibration in "
                          "gripper/data/calibration/default (about 6 minutes on 2 cores)")
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
    cal.set_defaults(func=_cmd_calibrate)

    po = with_params(sub.add_parser(
        "pullout", help="holding force: pull the held object until it slips 5 mm",
        description="Grasp and lift as in a trial, then pull the object straight down at --rate until it "
                    "slips 5 mm; with the controller, once per --grip-tension set-point."))
    po.add_argument("--objects", default="block,cylinder", help="comma-separated names")
    po.add_argument("--policy", choices=POLICIES, default=GraspProtocol().policy,
                    help="controller (default) or per_object closing")
    po.add_argument("--grip-tension", default=str(GraspProtocol().grip_tension), metavar="N[,N...]",
                    help="controller set-points [N], comma-separated (default %(default)s)")
    po.add_argument("--plot", metavar="FILE.png", help="also write holding force against set-point")
    number(po, "--rate", float, lo=0, lo_open=True, hi=1000, default=PULL_RATE, help="pull ramp [N/s]")
    number(po, "--max-force", float, lo=0, lo_open=True, hi=1000, default=PULL_MAX, help="largest pull [N]")
    po.set_defaults(func=_cmd_pullout)

    cr = with_params(sub.add_parser(
        "crush", help="press objects between the floor and a plate, report their damage measure",
        description="Platen crush test: a rigid plate presses each object --depth below its top at "
                    "--speed, holds --hold seconds and lifts off; prints the object's damage measure "
                    "(balloon/bag: peak edge strain; paper box: permanent dent; rigid: plate force)."))
    cr.add_argument("--objects", default="balloon,paper_box", help="comma-separated names")
    number(cr, "--depth", float, lo=0, lo_open=True, hi=0.2, default=CRUSH_DEPTH,
           help="press depth below the object's top [m]")
    number(cr, "--speed", float, lo=0, lo_open=True, hi=1.0, default=CRUSH_SPEED, help="plate speed [m/s]")
    number(cr, "--hold", float, lo=0, hi=60, default=CRUSH_HOLD_S, help="hold time at depth [s]")
    cr.add_argument("--json", action="store_true", help="one JSON object per line")
    cr.set_defaults(func=_cmd_crush)

    from gripper.rl.config import EVAL_SEED, TrainConfig

    tc = TrainConfig()
    tr = sub.add_parser(
        "train", help="train PPO or SAC on the grasp environment (needs the rl extra)",
        description="Train Stable-Baselines3 PPO or SAC on SoftGripperGrasp through the native vector "
                    "env, with the documented hyper-parameters (gripper/rl/hyperparams.py). Every "
                    "--chunk-steps it evaluates the deterministic policy on --eval-episodes unseen seeds, "
                    "appends a row to progress.csv and writes a checkpoint; --resume continues from the "
                    "latest one, bitwise as if never stopped. Writes policy.zip at the end.")
    tr.add_argument("--algo", choices=("ppo", "sac"), default=tc.algo,
                    help="PPO (on-policy) or SAC (off-policy) (default %(default)s)")
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
    tr.add_argument("--set", action="append", metavar="KEY=VALUE",
                    help="override a hyper-parameter, e.g. --set n_epochs=5 (repeatable)")
    tr.add_argument("--reward-weight", action="append", metavar="TERM=W",
                    help="override a dense reward weight, e.g. --reward-weight contact=1 (repeatable)")
    tr.add_argument("--out", required=True, metavar="DIR", help="run folder")
    tr.add_argument("--resume", action="store_true", help="continue the run in --out from its latest checkpoint")
    tr.add_argument("--video", metavar="FILE.mp4", help="also write a video of the final policy")
    seed_option(tr, "--video-seed", help="the video's episode seed", default=EVAL_SEED)
    tr.set_defaults(func=_cmd_train)

    pl = sub.add_parser("play", help="video of a trained policy's episode (needs the rl extra)",
                        description="Run one episode of a run folder's final policy (deterministic) and "
                                    "write its video (H.264 MP4 or GIF).")
    pl.add_argument("--run", required=True, metavar="DIR", help="run folder of 'gripper train'")
    pl.add_argument("--out", required=True, metavar="FILE", help="output .mp4 or .gif")
    seed_option(pl, help="episode seed", default=EVAL_SEED)
    pl.add_argument("--camera", default="front", help="camera preset (default front)")
    number(pl, "--width", int, lo=PIXELS[0], hi=PIXELS[1], default=640, help="pixels")
    number(pl, "--height", int, lo=PIXELS[0], hi=PIXELS[1], default=480, help="pixels")
    pl.set_defaults(func=_cmd_play)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as e:  # --help, --version (0) or a usage error (2, one line said already)
        return int(e.code or 0)
    from gripper.sim.stability import SimulationUnstable  # after parsing: --help stays quick

    try:
        return args.func(args)
    except ValueError as e:
        print(f"gripper {args.command}: error: {e}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except SimulationUnstable as e:
        print(f"gripper {args.command}: unstable simulation: {e}", file=sys.stderr)
        return EXIT_UNSTABLE
    except KeyboardInterrupt:
        # Ctrl-C: one line, not a traceback. Records are appended and flushed one by one and
        # every summary is written atomically, so what finished is kept and a rerun resumes.
        print(f"gripper {args.command}: interrupted; finished results are kept (rerun to resume)",
              file=sys.stderr)
        return EXIT_INTERRUPTED
    except BrokenPipeError:
        # the reader stopped early (``gripper bend | head``): end quietly, as Python's docs
        # advise, with stdout pointed at devnull so the interpreter's final flush cannot fail
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return EXIT_BROKEN_PIPE


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
