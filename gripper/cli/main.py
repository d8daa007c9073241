"""The ``gripper`` command.

Subcommands: ``bend`` (paper 000's bending test), ``servo`` (servo model against its
datasheet), ``params`` (write the default parameter file), ``write-models`` (regenerate
``gripper/data/soft_gripper``), ``check`` (step the scene under random servo commands), ``bench``
(the grasp benchmark), ``pullout`` (holding force), ``video`` (render one trial), ``train``
(PPO or SAC on the environment) and ``play`` (video of a trained policy).

Errors in input (bad parameter, malformed file) print one line on stderr and exit with code 2.
"""

from __future__ import annotations

import argparse
import json
import os
import sys

from gripper.bench.defaults import DEFAULT_TRIALS, DEFAULT_WORKERS
from gripper.bench.execution import check_scheduler
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


def _params(args) -> GripperParams:
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
    for i in list(range(0, len(res.r), stride)) + [len(res.r) - 1]:
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
    path = _params(args).save(args.out)
    print(f"wrote {path}")
    return 0


def _cmd_write_models(args) -> int:
    from gripper.model.menagerie import REPO_MODELS, write_model_files

    out = check_output_dir(args.out or REPO_MODELS)
    for path in write_model_files(out, _params(args)):
        print(f"wrote {path}")
    return 0


def _cmd_check(args) -> int:
    from gripper.experiments.smoke import random_control_rollout

    res = random_control_rollout(_params(args), duration=args.duration, seed=args.seed)
    print(f"{res['steps']} steps, {res['sim_time_s']:.2f} s simulated in {res['wall_time_s']:.2f} "
          f"s wall ({res['realtime_factor']:.1f}× real time), MuJoCo warnings: 0, state finite")
    return 0


def _csv_objects(text: str) -> tuple[str, ...]:
    names = tuple(n.strip() for n in text.split(",") if n.strip())
    if not names:
        raise ValueError("--objects: give at least one object name")
    return names


def _check_runner(args) -> None:
    """Refuse a bad --workers or an unreachable --scheduler before any work."""
    if args.workers < 1:
        raise ValueError(f"--workers: must be >= 1, got {args.workers}")
    check_scheduler(args.scheduler)


def _cmd_bench(args) -> int:
    from gripper.bench.benchmark import BenchConfig, format_table, run_benchmark

    if args.trials < 1:
        raise ValueError(f"--trials: must be >= 1, got {args.trials}")
    check_output_dir(args.out)
    _check_runner(args)
    proto, noise = _protocol_and_noise(args)
    cfg = BenchConfig(objects=_csv_objects(args.objects), trials=args.trials, seed=args.seed,
                      params=_params(args), protocol=proto, noise=noise).validate()
    if args.plot:
        from gripper.render.figures import check_png_path

        check_png_path(args.plot, "--plot")  # before the run: a bad path must not cost a benchmark
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
    from gripper.experiments.protocol import (
    GraspProtocol,
    TrialNoise,
)

    if args.noise < 0:
        raise ValueError(f"--noise: must be >= 0 m, got {args.noise}")
    proto = GraspProtocol(close_command_scale=args.close_scale, release=args.release, policy=args.policy,
                          grip_tension=args.grip_tension, approach=args.approach, grasp=args.grasp,
                          centre=not args.no_centre).validate()
    noise = TrialNoise(xy=args.noise, mass_frac=args.mass_noise, friction_frac=args.friction_noise).validate()
    return proto, noise


def _cmd_video(args) -> int:
    from gripper.objects.library import get_object
    from gripper.render.video import record_trial_video

    proto, noise = _protocol_and_noise(args)
    obj = get_object(args.object)
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
                         "pip install -e '.[rl]'")


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

    cfg = TrainConfig(algo=args.algo, objects=tuple(o.strip() for o in args.objects.split(",") if o.strip()),
                      action_mode=args.action_mode, xy_actions=args.xy, steps=args.steps, seed=args.seed,
                      n_envs=args.n_envs, chunk_steps=args.chunk_steps, eval_episodes=args.eval_episodes,
                      hyperparams=_hyperparam_overrides(args.set),
                      reward_weights=_hyperparam_overrides(args.reward_weight, "--reward-weight")).validate()
    check_output_dir(args.out)
    if args.video:
        from gripper.render.video import check_output_path

        check_output_path(args.video)
    _needs_rl("train")
    from gripper.rl.training import train

    def show(row):
        per = " ".join(f"{k[5:]} {v:.2f}" for k, v in row.items() if k.startswith("eval_") and k not in (
            "eval_success", "eval_return"))
        print(f"{row['steps']:>9} steps {row['wall_s']:>8.0f} s  train: {row['train_episodes']:>4} episodes, "
              f"success {row['train_success']:.2f}, return {row['train_return']:7.1f}  "
              f"eval: success {row['eval_success']:.2f} ({per})", flush=True)

    rows = train(cfg, args.out, resume=args.resume, on_progress=show)
    print(f"wrote {args.out}/policy.zip and progress.csv ({len(rows)} evaluations)")
    if args.video:
        return _play(args.out, args.video, args.video_seed, 640, 480, "front")
    return 0


def _play(run, out, seed, width, height, camera) -> int:
    from gripper.rl.policy_video import record_policy_video
    from gripper.rl.training import load_policy

    cfg, act = load_policy(run)
    res = record_policy_video(act, cfg.env_kwargs(), out, seed=seed, width=width, height=height, camera=camera)
    print(f"{res['object']}, seed {seed}: {'held' if res['success'] else 'not held'}; wrote {res['video']} "
          f"({res['frames']} frames at {res['fps']:g} fps)")
    return 0


def _cmd_play(args) -> int:
    from gripper.render.video import check_output_path

    check_output_path(args.out)
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
        print(f"wrote gripper/data/soft_gripper/calibration.json: stiffness "
              f"{', '.join(f'{k:.4g}' for k in cal.stiffness)} N·m/rad")
        return 0
    check_output_dir(args.out)
    p = _params(args)
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
                                    converge=not args.no_converge,
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
    from gripper.studies.study import load_study, run_study

    check_output_dir(args.out)
    study = load_study(args.file)
    _check_runner(args)
    records = run_study(study, args.out, workers=args.workers, scheduler=args.scheduler,
                        progress=not args.no_progress)
    failed = sum(r["status"] != "ok" for r in records)
    print((open(f"{args.out}/recommendations.md").read()).rstrip())
    print(f"{len(records)} design points ({failed} failed); wrote {args.out}/results.jsonl, results.csv, "
          "plot_*.png, recommendations.md")
    return 0


def _csv_floats(text: str, flag: str) -> tuple[float, ...]:
    try:
        vals = tuple(float(v) for v in text.split(",") if v.strip())
    except ValueError:
        raise ValueError(f"{flag}: expected comma-separated numbers, got {text!r}") from None
    if not vals:
        raise ValueError(f"{flag}: give at least one number")
    return vals


def _cmd_pullout(args) -> int:
    from gripper.experiments.protocol import GraspProtocol
    from gripper.experiments.pullout import run_pullout

    objects = _csv_objects(args.objects)
    policy = args.policy
    base = GraspProtocol(policy=policy)
    grips = _csv_floats(args.grip_tension, "--grip-tension") if policy == "controller" else (base.grip_tension,)
    protos = [base.replace(grip_tension=g) for g in grips]
    if args.plot:
        from gripper.render.figures import check_png_path

        check_png_path(args.plot, "--plot")
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
    from gripper.studies.envelope import load_envelope, run_envelope

    check_output_dir(args.out)
    lists = {key: (_csv_objects(v) if key == "shapes" else _csv_floats(v, f"--{key}"))
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

    for name in _csv_objects(args.objects):
        res = crush_test(name, args.depth, speed=args.speed, hold_s=args.hold, params=_params(args))
        if args.json:
            print(json.dumps(res))
            continue
        flag = "DAMAGED" if res["damaged"] else "intact"
        print(f"{name:<10} pressed {res['depth_m'] * 1e3:g} mm: {flag}, {res['damage_measure_name']} "
              f"{res['damage_measure']:.4g} (limit {res['damage_limit']:g}), peak plate force "
              f"{res['peak_plate_force_N']:.2f} N")
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="gripper",
        description="Simulate a four-finger cable-driven soft gripper in MuJoCo. "
                    "All quantities in SI units unless a name says otherwise.")
    sub = parser.add_subparsers(dest="command", required=True)

    def with_protocol(p):
        noise, proto = TrialNoise(), GraspProtocol()
        p.add_argument("--noise", type=float, default=noise.xy,
                       help="x/y placement noise half-range [m] (default %(default)s)")
        p.add_argument("--mass-noise", type=float, default=noise.mass_frac,
                       help="mass noise fraction, e.g. 0.2 (default %(default)s)")
        p.add_argument("--friction-noise", type=float, default=noise.friction_frac,
                       help="friction noise fraction (default %(default)s)")
        p.add_argument("--policy", choices=POLICIES, default=proto.policy,
                       help="controller: close each finger until its cable tension reaches --grip-tension, "
                            "knowing nothing of the object; per_object: each object's own closing command "
                            "(default %(default)s)")
        p.add_argument("--grip-tension", type=float, default=proto.grip_tension, metavar="N",
                       help="the controller's grip set-point: cable tension per finger [N] (default %(default)s)")
        p.add_argument("--close-scale", type=float, default=proto.close_command_scale,
                       help="per_object: multiplier on each object's closing command (default %(default)s; "
                            ">1 squeezes harder)")
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
        p.add_argument("--workers", type=int, default=DEFAULT_WORKERS,
                       help="local worker processes (default %(default)s)")
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

    bend = BendingConfig()
    b = with_params(sub.add_parser(
        "bend", help="paper 000's bending test of one finger",
        description="Ramp the cable shortening rate r from 0 to r_max over the run (dynamic) or "
                    "hold each of --points set-points until at rest (quasi_static); record "
                    "hinge angles, bending angle, tip position and cable tension."))
    b.add_argument("--json", action="store_true",
                   help="print a JSON object with arrays r, tension_N, joint_angles_deg, "
                        "bending_angle_deg, tip_xyz_m")
    b.add_argument("--mode", choices=("dynamic", "quasi_static"), default=bend.mode)
    b.add_argument("--figure", metavar="FILE.png",
                   help="also write a PNG: side-view montage of the finger at six shortening rates "
                        "and the bending-angle curve")
    b.add_argument("--r-max", type=float, default=bend.r_max, help="final shortening rate (default %(default)s)")
    b.add_argument("--duration", type=float, default=bend.duration, help="ramp time [s] (default %(default)s)")
    b.add_argument("--timestep", type=float, default=bend.timestep,
                   help="step [s] (default %(default)s, paper 000 §IV)")
    b.add_argument("--points", type=int, default=bend.n_points, help="samples or set-points (default %(default)s)")
    b.set_defaults(func=_cmd_bend)

    s = with_params(sub.add_parser("servo", help="servo model against its datasheet"))
    s.set_defaults(func=_cmd_servo)

    p = with_params(sub.add_parser(
        "params", help="write a parameter file (defaults or --params)",
        description="Write the gripper parameters (the defaults, or --params with any --springs or "
                    "--calibration applied) to a .json or .toml file. Every field, its unit, "
                    "allowed range and source:",
        epilog=parameter_help(), formatter_class=argparse.RawDescriptionHelpFormatter))
    p.add_argument("--out", required=True, metavar="FILE", help=".json or .toml")
    p.set_defaults(func=_cmd_params)

    w = with_params(sub.add_parser("write-models", help="regenerate gripper/data/soft_gripper"))
    w.add_argument("--out", metavar="DIR", help="output folder (default gripper/data/soft_gripper)")
    w.set_defaults(func=_cmd_write_models)

    c = with_params(sub.add_parser("check", help="step the scene under random servo commands"))
    c.add_argument("--duration", type=float, default=2.0, help="simulated time [s]")
    c.add_argument("--seed", type=int, default=0)
    c.set_defaults(func=_cmd_check)

    from gripper.objects.library import DEFAULT_OBJECTS
    bn = with_params(sub.add_parser(
        "bench", help="grasp benchmark: seeded scripted trials on each object",
        description="Run --trials scripted grasp trials per object (settle, approach, close, lift "
                    "0.10 m, hold 2 s, shake ±10 mm at 2 Hz for 2 s) and write trials.jsonl, "
                    "summary.csv and summary.json into --out. Rerunning into the same folder resumes. "
                    "Objects: " + ", ".join(DEFAULT_OBJECTS) + ", or mesh:PATH (STL/OBJ/PLY, metres)."))
    bn.add_argument("--objects", default=",".join(DEFAULT_OBJECTS), help="comma-separated names")
    bn.add_argument("--trials", type=int, default=DEFAULT_TRIALS, help="trials per object (default %(default)s)")
    bn.add_argument("--seed", type=int, default=0, help="base seed (default 0)")
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
    v.add_argument("--seed", type=int, default=0, help="base seed (default 0)")
    v.add_argument("--index", type=int, default=0, help="trial index within the seed (default 0)")
    v.add_argument("--out", required=True, metavar="FILE", help="output .mp4 or .gif")
    v.add_argument("--camera", default="front", help="camera preset: " + ", ".join(CAMERAS) + " (default front)")
    v.add_argument("--width", type=int, default=640, help="pixels (default 640)")
    v.add_argument("--height", type=int, default=480, help="pixels (default 480)")
    v.add_argument("--fps", type=float, default=30.0, help="frames per second (default 30)")
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
    st.add_argument("--out", required=True, metavar="DIR")
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
    ev.add_argument("--out", required=True, metavar="DIR")
    ev.add_argument("--shapes", metavar="S[,S...]", help="sphere, cylinder, box (default: the file's)")
    ev.add_argument("--sizes", metavar="M[,M...]", help="widths [m], sphere: diameter (default: the file's)")
    ev.add_argument("--masses", metavar="KG[,KG...]", help="masses [kg] (default: the file's)")
    ev.add_argument("--frictions", metavar="MU[,MU...]", help="friction coefficients (default: the file's)")
    ev.add_argument("--trials", type=int, help="trials per point (default: the file's)")
    ev.add_argument("--seed", type=int, help="base seed (default: the file's)")
    ev.add_argument("--grip-tension", type=float, metavar="N", help="set-point [N] (default: the file's, "
                    "else the protocol's)")
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
                          "gripper/data/soft_gripper (about 6 minutes on 2 cores)")
    cal.add_argument("--write-surrogate", action="store_true",
                     help="regenerate the committed stiffness surrogate of the design studies "
                          "(gripper/data/studies/stiffness_surrogate.json: six convergence studies "
                          "and 41 linear solves, about 25 minutes on 2 cores)")
    cal.add_argument("--mesh-scale", type=int, default=1,
                     help="reference mesh refinement: 1 default, 2 halves every cell (slow)")
    cal.add_argument("--tension-max", type=float, default=None,
                     help="highest cable tension of the reference run [N] (default 0.25; fmbs: "
                          "scaled to the reading's spring)")
    cal.add_argument("--levels", type=int, default=5, help="tension levels (default 5)")
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
    po.add_argument("--rate", type=float, default=PULL_RATE, help="pull ramp [N/s] (default %(default)s)")
    po.add_argument("--max-force", type=float, default=PULL_MAX, help="largest pull [N] (default %(default)s)")
    po.set_defaults(func=_cmd_pullout)

    cr = with_params(sub.add_parser(
        "crush", help="press objects between the floor and a plate, report their damage measure",
        description="Platen crush test: a rigid plate presses each object --depth below its top at "
                    "--speed, holds --hold seconds and lifts off; prints the object's damage measure "
                    "(balloon/bag: peak edge strain; paper box: permanent dent; rigid: plate force)."))
    cr.add_argument("--objects", default="balloon,paper_box", help="comma-separated names")
    cr.add_argument("--depth", type=float, default=CRUSH_DEPTH,
                    help="press depth below the object's top [m] (default %(default)s)")
    cr.add_argument("--speed", type=float, default=CRUSH_SPEED, help="plate speed [m/s] (default %(default)s)")
    cr.add_argument("--hold", type=float, default=CRUSH_HOLD_S, help="hold time at depth [s] (default %(default)s)")
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
    tr.add_argument("--algo", choices=("ppo", "sac"), default=tc.algo)
    tr.add_argument("--objects", default=",".join(tc.objects), help="comma-separated names (default %(default)s)")
    tr.add_argument("--action-mode", choices=("synergy", "fingers"), default=tc.action_mode)
    tr.add_argument("--xy", action="store_true", help="add the palm's x/y velocity actions")
    tr.add_argument("--steps", type=int, default=tc.steps, help="environment steps (default %(default)s)")
    tr.add_argument("--seed", type=int, default=tc.seed, help="seed (default %(default)s)")
    tr.add_argument("--n-envs", type=int, default=tc.n_envs, help="environments (default %(default)s)")
    tr.add_argument("--chunk-steps", type=int, default=tc.chunk_steps,
                    help="steps between evaluations and checkpoints (default %(default)s)")
    tr.add_argument("--eval-episodes", type=int, default=tc.eval_episodes,
                    help=f"evaluation episodes, seeds from {EVAL_SEED} on (default %(default)s)")
    tr.add_argument("--set", action="append", metavar="KEY=VALUE",
                    help="override a hyper-parameter, e.g. --set n_epochs=5 (repeatable)")
    tr.add_argument("--reward-weight", action="append", metavar="TERM=W",
                    help="override a dense reward weight, e.g. --reward-weight contact=1 (repeatable)")
    tr.add_argument("--out", required=True, metavar="DIR", help="run folder")
    tr.add_argument("--resume", action="store_true", help="continue the run in --out from its latest checkpoint")
    tr.add_argument("--video", metavar="FILE.mp4", help="also write a video of the final policy")
    tr.add_argument("--video-seed", type=int, default=EVAL_SEED, help="the video's episode seed (default %(default)s)")
    tr.set_defaults(func=_cmd_train)

    pl = sub.add_parser("play", help="video of a trained policy's episode (needs the rl extra)",
                        description="Run one episode of a run folder's final policy (deterministic) and "
                                    "write its video (H.264 MP4 or GIF).")
    pl.add_argument("--run", required=True, metavar="DIR", help="run folder of 'gripper train'")
    pl.add_argument("--out", required=True, metavar="FILE", help="output .mp4 or .gif")
    pl.add_argument("--seed", type=int, default=EVAL_SEED, help="episode seed (default %(default)s)")
    pl.add_argument("--camera", default="front", help="camera preset (default front)")
    pl.add_argument("--width", type=int, default=640, help="pixels (default 640)")
    pl.add_argument("--height", type=int, default=480, help="pixels (default 480)")
    pl.set_defaults(func=_cmd_play)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    from gripper.sim.stability import SimulationUnstable  # after parsing: --help stays quick

    try:
        return args.func(args)
    except ValueError as e:
        print(f"gripper {args.command}: error: {e}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except SimulationUnstable as e:
        print(f"gripper {args.command}: unstable simulation: {e}", file=sys.stderr)
        return EXIT_UNSTABLE
    except BrokenPipeError:
        # the reader stopped early (``gripper bend | head``): end quietly, as Python's docs
        # advise, with stdout pointed at devnull so the interpreter's final flush cannot fail
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return EXIT_BROKEN_PIPE


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
