"""The hostile-input campaign (issue 46): what a careless user, another tool or an attacker can
hand the command line and the Python API, by kind, each case as its own process with a time
limit. ``scripts/bad_input_campaign.py`` runs every case (``--hostile-only``: these alone; else
with the typo grid of ``tests/test_bad_input_campaign.py``) and prints the totals;
``tests/test_hostile_inputs.py`` runs the first case of each kind in the default suite and the
rest as slow tests.

A case is classed:

- ``refused``: exit 2 (143 for SIGTERM, 130 for SIGINT), exactly one line on stderr, no traceback,
  and the case's folder exactly as it was (nothing new, nothing changed, nothing lost);
- ``accepted``: exit 0: a silent accept, a defect for every case here;
- ``traceback``, ``hang`` (no end within the time limit), ``other``: defects.

An API case runs ``python -c`` and is refused when it raises ValueError or TypeError whose
message names the argument (``expect``).
"""

from __future__ import annotations

import atexit
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
GRIPPER = [sys.executable, "-m", "gripper.cli.main"]
TIMEOUT = 120.0  # s per case: the slowest (a bench trial into a prepared folder) takes about 10 s
BENCH = ("bench", "--objects", "block", "--trials", "1", "--workers", "1", "--no-progress")
ENVELOPE = ("envelope", "--shapes", "box", "--sizes", "0.04", "--masses", "0.05", "--frictions", "0.6",
            "--trials", "1", "--workers", "1", "--no-progress")
ENVELOPE_FILE = '[envelope]\nshapes = ["box"]\nsizes = [0.04]\nmasses = [0.05]\nfrictions = [0.6]\ntrials = 1\n'
OBJECT = '[object]\nname = "part"\nkind = "rigid_box"\nsize = [0.02, 0.02, 0.03]\nmass = 0.05\nfriction = 0.6\n' \
         '[damage]\ncriterion = "none"\n'
STL = ("solid c\n" + "".join(
    f"facet normal 0 0 0\nouter loop\nvertex {a}\nvertex {b}\nvertex {c}\nendloop\nendfacet\n"
    for a, b, c in [("0 0 0", "0.03 0 0", "0 0.03 0"), ("0 0 0", "0 0 0.03", "0.03 0 0"),
                    ("0 0 0", "0 0.03 0", "0 0 0.03"), ("0.03 0 0", "0 0 0.03", "0 0.03 0")]) + "endsolid c\n")


@dataclass(frozen=True)
class Case:
    """One hostile input. ``files``: name -> text, bytes, ``"FIFO"``, ``"->TARGET"`` (a symlink)
    or ``"BENCH:SEED"`` (a finished one-trial bench folder of that seed); ``prepare``: more set-up
    in the folder; ``api``: Python code instead of a command; ``fsize``: a file size limit [bytes]
    (a full disk); ``stdout``: a path stdout is sent to; ``term_after``: (file, lines): SIGTERM
    once the file holds that many lines; ``hold_lock``: a folder whose lock another process holds."""

    kind: str
    name: str
    argv: tuple[str, ...] = ()
    files: dict[str, str | bytes] = field(default_factory=dict)
    api: str = ""
    expect: str = ""  # words the one line must contain
    fsize: int | None = None
    stdout: str | None = None
    term_after: tuple[str, int] | None = None
    hold_lock: str | None = None
    prepare: Callable[[Path], None] | None = None


def _obj(**changes: str) -> str:
    """The base object file with ``key = value`` lines replaced or added in [object]."""
    text = OBJECT
    for k, v in changes.items():
        lines = [ln for ln in text.splitlines() if not ln.startswith(f"{k} =")]
        lines.insert(1, f"{k} = {v}")
        text = "\n".join(lines) + "\n"
    return text


def _deformable(kind: str, material: str, size: str = "[0.02, 0.02, 0.02]", limit: str = "0.2") -> str:
    crit = {"balloon": "strain", "paper_box": "dent", "bag": "strain"}[kind]
    return (f'[object]\nname = "soft"\nkind = "{kind}"\nsize = {size}\nmass = 0.01\nfriction = 0.6\n'
            f'close_command = 1.0\n[damage]\ncriterion = "{crit}"\nlimit = {limit}\n[material]\n{material}\n')


def _trial(args: str) -> str:
    """Python code that calls ``run_trial(args)``."""
    return f"from gripper.experiments.trial import run_trial\nrun_trial({args})"


def _study(vary: str, responses: str = 'bending = { r_max = 0.1 }', design: str = "one_at_a_time") -> str:
    return f'[study]\nname = "s"\ndesign = "{design}"\n[vary]\n{vary}\n[responses]\n{responses}\n'


CASES: list[Case] = [
    # --- run folders: records of another run, a lost config, two writers, another command ---
    Case("mixed_records", "a trial of another seed appended to a bench folder",
         (*BENCH, "--trials", "2", "--out", "run"), {"run": "BENCH:0", "other": "BENCH:5"},
         prepare=lambda d: (d / "run" / "trials.jsonl").open("a").write(
             (d / "other" / "trials.jsonl").read_text().splitlines()[0] + "\n"), expect="run"),
    Case("mixed_records", "a duplicated record", (*BENCH, "--trials", "2", "--out", "run"), {"run": "BENCH:0"},
         prepare=lambda d: (d / "run" / "trials.jsonl").open("a").write(
             (d / "run" / "trials.jsonl").read_text()), expect="run"),
    Case("lost_config", "config.json removed, rerun with another seed", (*BENCH, "--seed", "7", "--out", "run"),
         {"run": "BENCH:0"}, prepare=lambda d: (d / "run" / "config.json").unlink(), expect="run"),
    Case("concurrent_writers", "a second bench into a folder another run holds", (*BENCH, "--out", "run"),
         hold_lock="run", expect="another run"),
    Case("foreign_folder", "an envelope into a bench folder", (*ENVELOPE, "--out", "run"), {"run": "BENCH:0"},
         expect="benchmark"),
    Case("foreign_folder", "a bench into an envelope folder", (*BENCH, "--out", "env"),
         prepare=lambda d: (d / "env").mkdir() or (d / "env" / "envelope.json").write_text('{"envelope_hash": "0"}'),
         expect="envelope"),
    # --- numbers a file can hold that are not floats ---
    Case("huge_number", "a 400-digit integer in a TOML parameter file", ("check", "--duration", "0.01", "--params",
         "p.toml"), {"p.toml": "[finger]\npitch = 1" + "0" * 400 + "\n"}, expect="finger.pitch"),
    Case("huge_number", "a 5000-digit integer in a JSON parameter file", ("check", "--duration", "0.01", "--params",
         "p.json"), {"p.json": '{"finger": {"pitch": 1' + "0" * 5000 + "}}"}, expect="p.json"),
    Case("huge_number", "1e999 in an object file", (*BENCH, "--objects", "o.toml", "--out", "run"),
         {"o.toml": _obj(mass="1e999")}, expect="object.mass"),
    Case("huge_number", "a 400-digit integer as an envelope seed", ("envelope", "e.toml", "--out", "env"),
         {"e.toml": ENVELOPE_FILE + "seed = 1" + "0" * 400 + "\n"}, expect="seed"),
    # --- files nested thousands of levels deep ---
    Case("deep_nesting", "a JSON parameter file nested 100 000 deep", ("check", "--duration", "0.01", "--params",
         "p.json"), {"p.json": '{"finger": ' + "[" * 100_000 + "]" * 100_000 + "}"}, expect="p.json"),
    Case("deep_nesting", "a TOML object file nested 5000 deep", (*BENCH, "--objects", "o.toml", "--out", "run"),
         {"o.toml": "x = " + "[" * 5000 + "]" * 5000 + "\n"}, expect="o.toml"),
    Case("deep_nesting", "a study nested 3000 deep", ("study", "s.toml", "--out", "st", "--no-progress"),
         {"s.toml": "a = " + "[" * 3000 + "]" * 3000 + "\n"}, expect="s.toml"),
    # --- special files: FIFOs, devices, links to them, folders ---
    Case("special_file", "a FIFO as the parameter file", ("check", "--duration", "0.01", "--params", "p.toml"),
         {"p.toml": "FIFO"}, expect="p.toml"),
    Case("special_file", "a link to /dev/zero as the parameter file", ("check", "--duration", "0.01", "--params",
         "z.toml"), {"z.toml": "->/dev/zero"}, expect="z.toml"),
    Case("special_file", "/dev/zero as bench data", ("calibrate", "--out", "cal", "--data", "/dev/zero"),
         expect="/dev/zero"),
    Case("special_file", "a FIFO as a mesh", (*BENCH, "--objects", "mesh:m.stl", "--out", "run"), {"m.stl": "FIFO"},
         expect="m.stl"),
    Case("special_file", "a link to /dev/urandom as an object file", (*BENCH, "--objects", "o.toml", "--out", "run"),
         {"o.toml": "->/dev/urandom"}, expect="o.toml"),
    Case("special_file", "a FIFO as a study", ("study", "s.toml", "--out", "st", "--no-progress"), {"s.toml": "FIFO"},
         expect="s.toml"),
    Case("special_file", "a FIFO as a calibration file", (*BENCH, "--calibration", "c.json", "--out", "run"),
         {"c.json": "FIFO"}, expect="c.json"),
    Case("special_file", "a 60 MB parameter file", ("check", "--duration", "0.01", "--params", "p.toml"),
         {"p.toml": "# " + "x" * 60_000_000 + "\n"}, expect="p.toml"),
    # --- CSV cells and rows ---
    Case("csv_bounds", "a CSV cell of 200 000 characters", ("calibrate", "--out", "cal", "--data", "d.csv"),
         {"d.csv": "tension_N,tip_x_m,tip_z_m\n" + "1" * 200_000 + ",0.09,0.01\n"}, expect="d.csv"),
    Case("csv_bounds", "a CSV row of 100 000 columns", ("calibrate", "--out", "cal", "--data", "d.csv"),
         {"d.csv": "tension_N,tip_x_m,tip_z_m" + ",x" * 100_000 + "\n1,0.09,0.01\n"}, expect="d.csv"),
    Case("csv_bounds", "a CSV of 200 000 rows", ("calibrate", "--out", "cal", "--data", "d.csv"),
         {"d.csv": "tension_N,tip_x_m,tip_z_m\n" + "1,0.09,0.01\n" * 200_000}, expect="d.csv"),
    # --- object and design fields without physical limits ---
    Case("physical_range", "a 1000 t block", (*BENCH, "--objects", "o.toml", "--out", "run"),
         {"o.toml": _obj(mass="1e6")}, expect="mass"),
    Case("physical_range", "a 1 µg part", (*BENCH, "--objects", "o.toml", "--out", "run"),
         {"o.toml": _obj(mass="1e-9")}, expect="mass"),
    Case("physical_range", "friction 1e6", (*BENCH, "--objects", "o.toml", "--out", "run"),
         {"o.toml": _obj(friction="1e6")}, expect="friction"),
    Case("physical_range", "a density of 1e9", (*BENCH, "--objects", "o.toml", "--out", "run"),
         {"o.toml": _obj(mass="", density="1e9").replace("mass = \n", "")}, expect="density"),
    Case("physical_range", "a 1 mPa balloon", (*BENCH, "--objects", "o.toml", "--out", "run"),
         {"o.toml": _deformable("balloon", "youngs_modulus = 1e-3")}, expect="youngs_modulus"),
    Case("physical_range", "a card that yields at 500 %", (*BENCH, "--objects", "o.toml", "--out", "run"),
         {"o.toml": _deformable("paper_box", "youngs_modulus = 3e9\nthickness = 2e-4\nyield_strain = 5.0",
                                "[0.03, 0.03, 0.03]", "0.002")}, expect="yield_strain"),
    Case("physical_range", "a part 4 µm in size", (*BENCH, "--objects", "o.toml", "--out", "run"),
         {"o.toml": _obj(size="[2e-6, 2e-6, 2e-6]")}, expect="size"),
    Case("physical_range", "a mesh 30 µm in size", (*BENCH, "--objects", "mesh:m.stl::0.01", "--out", "run"),
         {"m.stl": STL.replace("0.03", "0.00003")}, expect="m.stl"),
    Case("physical_range", "a finger pitch of 1 km", ("check", "--duration", "0.01", "--params", "p.toml"),
         {"p.toml": "[finger]\npitch = 1000.0\n"}, expect="finger.pitch"),
    Case("physical_range", "a silicone of density 1e9", ("check", "--duration", "0.01", "--params", "p.toml"),
         {"p.toml": "[material]\ndensity = 1e9\n"}, expect="material.density"),
    Case("physical_range", "a cable 1 m thick", ("check", "--duration", "0.01", "--params", "p.toml"),
         {"p.toml": "[cable]\ndiameter = 1.0\n"}, expect="cable.diameter"),
    # --- options that do not apply ---
    Case("not_applicable", "a grip pressure on the cable gripper", (*BENCH, "--grip-pressure", "20000", "--out",
         "run"), expect="--grip-pressure"),
    Case("not_applicable", "a grip tension on the pneumatic gripper", (*BENCH, "--actuation", "pneumatic",
         "--grip-tension", "5", "--out", "run"), expect="--grip-tension"),
    Case("not_applicable", "--close-scale with the controller", (*BENCH, "--close-scale", "1.2", "--out", "run"),
         expect="--close-scale"),
    Case("not_applicable", "a grip pressure in a cable envelope", (*ENVELOPE, "--grip-pressure", "20000", "--out",
         "env"), expect="--grip-pressure"),
    Case("not_applicable", "a reference together with --data", ("calibrate", "--out", "cal", "--data",
         "gripper/data/calibration/example_bench.csv", "--reference", "fmbs"), expect="--reference"),
    Case("not_applicable", "--no-centre with the catalogue approach", (*BENCH, "--approach", "catalogue",
         "--no-centre", "--out", "run"), expect="--no-centre"),
    Case("not_applicable", "--force-calibration without a calibration", (*BENCH, "--force-calibration", "--out",
         "run"), expect="--force-calibration"),
    Case("not_applicable", "a grip pressure in an envelope file of the cable gripper", ("envelope", "e.toml",
         "--out", "env"), {"e.toml": ENVELOPE_FILE + "grip_pressure = 20000.0\n"}, expect="grip_pressure"),
    # --- studies ---
    Case("study_rules", "a study of 10^9 trials", ("study", "s.toml", "--out", "st", "--no-progress"),
         {"s.toml": _study('"finger.cut_angle_deg" = [40.0, 50.0]',
                           'grasp = { objects = ["block"], trials = 1000000000 }')}, expect="trials"),
    Case("study_rules", "a study varying a text field", ("study", "s.toml", "--out", "st", "--no-progress"),
         {"s.toml": _study('"servo.preset" = ["hobby_6v", "nope"]')}, expect="servo.preset"),
    Case("study_rules", "a study whose points cannot run", ("study", "s.toml", "--out", "st", "--no-progress"),
         {"s.toml": _study('"finger.pitch" = [0.004, 0.005]')}, expect="finger.pitch"),
    Case("study_rules", "a study of 10^6 points", ("study", "s.toml", "--out", "st", "--no-progress"),
         {"s.toml": _study("\n".join(f'"finger.{k}" = [{a}, {b}]' for k, a, b in [
             ("cut_angle_deg", 40, 50), ("pitch", 0.015, 0.017), ("width", 0.015, 0.017), ("height", 0.017, 0.019),
             ("bridge_thickness", 0.0018, 0.002)]) + "\n" + "\n".join(
             f'"layout.{k}" = [{a}, {b}]' for k, a, b in [("palm_radius", 0.039, 0.041)]) + "\n"
             + "\n".join(f'"lift.{k}" = [{", ".join(str(a * (1 + i / 100)) for i in range(10))}]' for k, a in [
                 ("stiffness", 4000), ("max_force", 60), ("damping_ratio", 1.0), ("home_height", 0.25)]),
             design="factorial")}, expect="points"),
    # --- the same thing spelled twice, a file named like a built-in ---
    Case("spelling_duplicates", "one mesh by two paths", (*BENCH, "--objects", "mesh:m.stl,mesh:./m.stl", "--out",
         "run"), {"m.stl": STL}, expect="m.stl"),
    Case("spelling_duplicates", "an object file named like a built-in", (*BENCH, "--objects", "o.toml", "--out",
         "run"), {"o.toml": _obj(name='"block"')}, expect="block"),
    Case("spelling_duplicates", "one object file by two paths", (*BENCH, "--objects", "o.toml,./o.toml", "--out",
         "run"), {"o.toml": OBJECT}, expect="o.toml"),
    # --- seeds beyond the command line's bound, by another door ---
    Case("seed_bounds", "an envelope file's seed of 2^40", ("envelope", "e.toml", "--out", "env"),
         {"e.toml": ENVELOPE_FILE + f"seed = {2 ** 40}\n"}, expect="seed"),
    Case("seed_bounds", "a study seed of -1", ("study", "s.toml", "--out", "st", "--no-progress"),
         {"s.toml": _study('"finger.cut_angle_deg" = [40.0]').replace('design =', "seed = -1\ndesign =")},
         expect="seed"),
    Case("seed_bounds", "run_trial with seed 2^40", api=_trial("'block', 2**40, 0"), expect="seed"),
    # --- the Python API: wrong types and values name the argument ---
    Case("api_arguments", "run_trial with index 1.5", api=_trial("'block', 0, 1.5"), expect="index"),
    Case("api_arguments", "run_trial with a negative index", api=_trial("'block', 0, -1"), expect="index"),
    Case("api_arguments", "run_trial with a negative seed", api=_trial("'block', -3, 0"), expect="seed"),
    Case("api_arguments", "run_trial with params of the wrong type", api=_trial("'block', 0, 0, params={'finger': 1}"),
         expect="params"),
    Case("api_arguments", "run_trial with an object of the wrong type", api=_trial("3.5, 0, 0"), expect="obj"),
    Case("api_arguments", "run_benchmark with a config of the wrong type", api="from gripper.bench.benchmark import "
         "run_benchmark\nrun_benchmark({'objects': ['block']}, 'run')", expect="cfg"),
    Case("api_arguments", "GraspEnv with params of the wrong type", api="from gripper.envs.grasp_env import "
         "SoftGripperGraspEnv\nSoftGripperGraspEnv(params=3)", expect="params"),
    Case("api_arguments", "GripperParams.load of a number", api="from gripper.core.params import GripperParams\n"
         "GripperParams.load(3)", expect="path"),
    # --- output that cannot be written ---
    Case("output_failure", "--version into a full device", ("--version",), stdout="/dev/full", expect="stdout"),
    Case("output_failure", "a design check's report into a full device", ("check", "--duration", "0.01"),
         stdout="/dev/full", expect="stdout"),
    Case("output_failure", "a parameter file onto a full disk", ("params", "--out", "p.toml"), fsize=64,
         expect="p.toml"),
    Case("output_failure", "a video onto a full disk", ("video", "--object", "block", "--out", "v.gif", "--width",
         "32", "--height", "32", "--fps", "5"), fsize=2048, expect="v.gif"),
    # --- signals: one line, exit 128 + the signal's number ---
    Case("signal", "SIGTERM during a two-worker bench", ("bench", "--objects", "block", "--trials", "40",
         "--workers", "2", "--no-progress", "--out", "run"), term_after=("run/trials.jsonl", 1),
         expect="terminated"),
]
KINDS = tuple(dict.fromkeys(c.kind for c in CASES))


def _bench_folder(folder: Path, seed: int) -> None:
    """A finished one-trial bench folder of ``seed`` (made once per campaign, copied per case)."""
    cache = _CACHE / f"bench-{seed}"  # this process's: a cache of another version would be another run
    with _MAKING:
        _make_bench_folder(cache, seed)
    shutil.copytree(cache, folder)


_MAKING = threading.Lock()
_CACHE = Path(tempfile.mkdtemp(prefix="gripper-campaign-"))
atexit.register(shutil.rmtree, _CACHE, ignore_errors=True)


def _make_bench_folder(cache: Path, seed: int) -> None:
    if not (cache / "summary.json").is_file():
        tmp = cache.with_name(cache.name + ".making")
        shutil.rmtree(tmp, ignore_errors=True)
        subprocess.run([*GRIPPER, *BENCH, "--seed", str(seed), "--out", str(tmp)], check=True, capture_output=True,
                       env=_env(), timeout=TIMEOUT)
        tmp.rename(cache)


def _env() -> dict[str, str]:
    return dict(os.environ, PYTHONPATH=str(ROOT), MUJOCO_GL="egl")


def _tree(folder: Path) -> dict[str, bytes | None]:
    out: dict[str, bytes | None] = {}
    for p in folder.rglob("*"):
        if p.is_symlink() or p.is_fifo():
            out[str(p.relative_to(folder))] = b"special"
        elif p.is_file():
            out[str(p.relative_to(folder))] = p.read_bytes()
        else:
            out[str(p.relative_to(folder))] = None
    return out


def _hold(folder: Path) -> subprocess.Popen:
    """Another process holding ``folder``'s run lock, as a running bench would."""
    folder.mkdir()
    code = ("import fcntl, sys, time\nf = open(sys.argv[1], 'a+')\nfcntl.flock(f, fcntl.LOCK_EX)\n"
            "f.write('4242'); f.flush(); print('held', flush=True); time.sleep(600)")
    holder = subprocess.Popen([sys.executable, "-c", code, str(folder / ".lock")], stdout=subprocess.PIPE, text=True)
    assert holder.stdout is not None and holder.stdout.readline().strip() == "held"
    return holder


def run_case(case: Case, timeout: float = TIMEOUT) -> tuple[str, str]:
    """(class, the one line or what went wrong) for ``case``."""
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        for name, content in case.files.items():
            path = folder / name
            if content == "FIFO":
                os.mkfifo(path)
            elif isinstance(content, str) and content.startswith("->"):
                path.symlink_to(content[2:])
            elif isinstance(content, str) and content.startswith("BENCH:"):
                _bench_folder(path, int(content[6:]))
            else:
                path.write_bytes(content if isinstance(content, bytes) else content.encode())
        if case.prepare is not None:
            case.prepare(folder)
        holder = _hold(folder / case.hold_lock) if case.hold_lock else None
        before = _tree(folder)
        argv = [str(ROOT / a) if a.startswith("gripper/data/") else a for a in case.argv]
        cmd = [sys.executable, "-c", case.api] if case.api else [*GRIPPER, *argv]

        def limits() -> None:
            if case.fsize is not None:
                signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a write past the limit fails with EFBIG
                resource.setrlimit(resource.RLIMIT_FSIZE, (case.fsize, case.fsize))

        stdout = open(case.stdout, "w") if case.stdout else subprocess.PIPE  # noqa: SIM115
        try:
            proc = subprocess.Popen(cmd, cwd=folder, stdout=stdout, stderr=subprocess.PIPE, text=True, env=_env(),
                                    stdin=subprocess.DEVNULL, preexec_fn=limits, start_new_session=True)
            try:
                if case.term_after is not None:
                    path, lines = folder / case.term_after[0], case.term_after[1]
                    deadline = time.monotonic() + timeout
                    while not (path.is_file() and path.read_text().count("\n") >= lines):
                        if proc.poll() is not None or time.monotonic() > deadline:
                            break
                        time.sleep(0.05)
                    proc.send_signal(signal.SIGTERM)
                out, err = proc.communicate(timeout=timeout)
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.communicate()
                return "hang", f"no end within {timeout:g} s"
        finally:
            if case.stdout:
                stdout.close()  # type: ignore[union-attr]
            if holder is not None:
                holder.kill()
                holder.wait()
        after = _tree(folder)
        lines = err.strip().splitlines()
        if "Traceback (most recent call last)" in err and not case.api:
            return "traceback", lines[-1] if lines else ""
        if case.api:
            last = lines[-1] if lines else ""
            if proc.returncode == 0:
                return "accepted", "no error"
            if last.startswith(("ValueError:", "TypeError:")) and case.expect in last:
                return "refused", last
            return "other", last
        if case.term_after is not None:
            # a signal: the finished records are kept (the folder grows), nothing else is said
            if proc.returncode == 128 + signal.SIGTERM and len(lines) == 1 and case.expect in lines[0]:
                return "refused", lines[0]
            return "other", f"exit {proc.returncode}, {len(lines)} lines: {lines[:4]}"
        if proc.returncode == 2:
            if len(lines) != 1:
                return "other", f"exit 2 with {len(lines)} lines: {lines[:3]}"
            if after != before:
                changed = sorted(set(after) ^ set(before) | {k for k in before if after.get(k) != before[k]})
                return "other", f"files changed: {changed[:4]}: {lines[0]}"
            if case.expect not in lines[0]:
                return "other", f"the line does not name {case.expect!r}: {lines[0]}"
            return "refused", lines[0]
        if proc.returncode == 0:
            return "accepted", ((out or "").strip().splitlines() or [""])[-1][:160]
        return "other", f"exit {proc.returncode}: {lines[-1] if lines else ''}"


def first_of_each_kind() -> list[Case]:
    return [next(c for c in CASES if c.kind == k) for k in KINDS]
