"""Options and input handling that several commands share: the design (``--params``,
``--springs``, ``--calibration``), the trial protocol and noise, the runner (workers, scheduler),
object lists and the exit codes.
"""

from __future__ import annotations

from gripper.bench.defaults import DEFAULT_WORKERS
from gripper.bench.execution import check_scheduler
from gripper.cli.inputs import WORKERS_MAX, field_option, given, names, number
from gripper.core.params import ACTUATIONS, GripperParams
from gripper.experiments.protocol import APPROACHES, GRASP_CHOICES, POLICIES, WRIST_RULES, GraspProtocol, TrialNoise

# What --grip-pressure allows: the field's bound is the regulator class's, but a run refuses more
# than the design's own pneumatic.pressure_max (the calibration's range), which the help says.
GRIP_PRESSURE_RANGE = "in (0, pneumatic.pressure_max]: 250,000 for the default design"

EXIT_BAD_INPUT = 2
EXIT_UNSTABLE = 3
EXIT_BROKEN_PIPE = 1
EXIT_INTERRUPTED = 130  # 128 + SIGINT, as shells report a command ended by Ctrl-C
EXIT_TERMINATED = 143  # 128 + SIGTERM
EXIT_FAILED = 1  # the run ended, but nothing it set out to measure was measured (every study point failed)


def design(args, *, simulates: bool = True, cable_only: str | None = None) -> GripperParams:
    """The parameters the options give; ``simulates``: also check, before any work and any file,
    that the design can be stepped at all (:func:`gripper.sim.preflight.check_design`).
    ``cable_only``: the command (e.g. ``"gripper bend"``) tests the cable finger only, and refuses
    the pneumatic gripper in one line."""
    p = _read_params(args)
    if cable_only and p.actuation.kind != "cable":
        raise ValueError(f"--actuation: {cable_only} tests the cable finger (its cable, servo and cuts); the "
                         "pneumatic gripper runs bench, envelope, video, check, study and the environment")
    if simulates:
        from gripper.sim.preflight import check_design

        check_design(p, "--params" if args.params else "--calibration")
    return p


def _read_params(args) -> GripperParams:
    p = GripperParams.load(args.params) if args.params else GripperParams().validate()
    actuation = getattr(args, "actuation", None)
    if actuation is not None:
        p = p.replace(actuation=p.actuation.replace(kind=actuation)).validate()
    springs = getattr(args, "springs", "calibrated")
    if p.actuation.kind != "cable" and (springs != "calibrated" or getattr(args, "calibration", None)):
        raise ValueError("--springs/--calibration: set the cable finger's springs; the pneumatic finger's come "
                         "from its own calibration ('gripper calibrate --reference actuator')")
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


def object_specs(text: str, flag: str = "--objects") -> tuple[str, ...]:
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


def check_runner(args) -> None:
    """Refuse an unreachable --scheduler before any work (--workers is bounded by its type)."""
    check_scheduler(args.scheduler)


def check_applies(args, params: GripperParams) -> None:
    """Refuse, in one line naming it, an option the command line gave that this run would
    ignore: a set-point of the other gripper, ``--close-scale`` under the controller, a set-point
    under ``--policy per_object``, ``--no-centre`` with the catalogue approach,
    ``--force-calibration`` without a calibration."""
    kind = params.actuation.kind
    if given(args, "grip_pressure") and kind != "pneumatic":
        raise ValueError(f"--grip-pressure: sets the pneumatic gripper's chamber pressure; this run drives the {kind} "
                         "gripper (add --actuation pneumatic, or leave --grip-pressure out)")
    if given(args, "grip_tension") and kind != "cable":
        raise ValueError(f"--grip-tension: sets the cable gripper's cable tension; this run drives the {kind} gripper "
                         "(its set-point is --grip-pressure)")
    policy = getattr(args, "policy", None)
    for dest in ("grip_tension", "grip_pressure"):
        if policy == "per_object" and given(args, dest):
            flag = "--" + dest.replace("_", "-")
            raise ValueError(f"{flag}: a set-point of --policy controller; --policy per_object closes each finger to "
                             "the object's own command (scale it with --close-scale)")
    if policy == "controller" and given(args, "close_scale"):
        raise ValueError("--close-scale: scales --policy per_object's closing commands; the controller (the default "
                         "policy) closes to its set-point (--grip-tension, --grip-pressure)")
    if getattr(args, "approach", None) == "catalogue" and given(args, "no_centre"):
        raise ValueError("--no-centre: applies to --approach sensed (the palm camera's centring); --approach "
                         "catalogue places the palm by the object's catalogue size")
    if getattr(args, "approach", None) == "catalogue" and given(args, "wrist"):
        raise ValueError("--wrist: applies to --approach sensed (the turn follows the camera's footprint); --approach "
                         "catalogue keeps the palm at zero yaw")
    if given(args, "wrist") and not params.lift.yaw_enabled:
        raise ValueError("--wrist: this design has no wrist (lift.yaw_enabled = false in its parameters)")
    if given(args, "force_calibration") and not getattr(args, "calibration", None):
        raise ValueError("--force-calibration: applies a --calibration made for another design; give --calibration "
                         "FILE, or leave --force-calibration out")


def protocol_and_noise(args, params: GripperParams):
    """The protocol and noise the options give, once :func:`check_applies` has passed."""
    check_applies(args, params)
    proto = GraspProtocol(close_command_scale=args.close_scale, release=args.release, policy=args.policy,
                          grip_tension=args.grip_tension, grip_pressure=args.grip_pressure, approach=args.approach,
                          grasp=args.grasp, centre=not args.no_centre, wrist=args.wrist).validate()
    noise = TrialNoise(xy=args.noise, mass_frac=args.mass_noise, friction_frac=args.friction_noise).validate()
    return proto, noise


def needs_rl(command: str, contrib: bool = False) -> None:
    """Refuse ``command`` in one line unless the rl extra is installed (``contrib``: sb3-contrib too)."""
    import importlib.util

    names = ("stable_baselines3", "torch") + (("sb3_contrib",) if contrib else ())
    if any(importlib.util.find_spec(n) is None for n in names):
        raise ValueError(f"{command}: needs the rl extra (stable-baselines3, sb3-contrib and torch): "
                         "pip install 'gripper[rl]' (in this repository: .venv/bin/pip install -e '.[rl]')")


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
    field_option(p, "--grip-pressure", GraspProtocol, "grip_pressure",
                 "the pneumatic gripper's grip set-point: chamber pressure [Pa]", metavar="PA",
                 range_help=GRIP_PRESSURE_RANGE)
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
    p.add_argument("--wrist", choices=WRIST_RULES, default=proto.wrist,
                   help="sensed approach: footprint turns the palm so a finger pair closes across the part's "
                        "width, or straddles a long part; fixed keeps the palm at zero yaw (default %(default)s)")
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
    p.add_argument("--actuation", choices=ACTUATIONS, default=None,
                   help="the fingers: cable (paper 000's, the default) or pneumatic (paper 001's actuator as a "
                        "calibrated hinge chain, fed by a proportional regulator); overrides --params")
    p.add_argument("--force-calibration", action="store_true",
                   help="apply --calibration even if it was made for another design")
    from gripper.core.params import SPRING_SETS

    p.add_argument("--springs", choices=SPRING_SETS, default="calibrated",
                   help="hinge springs: the committed calibration (default), or paper 000's "
                        "Table 2 spring read as printed (paper: 1.9e-3 N·m/deg) or per "
                        "radian (paper_per_radian), for comparison")
    return p
