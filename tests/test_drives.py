"""The drive as a component: a third drive, defined here and nowhere in the package, builds a
gripper and runs a grasp trial through the same code as the cable and pneumatic grippers; and
nothing outside the drive folders asks which drive it has."""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import mujoco
import numpy as np
import pytest

from gripper.core.params import Actuation, GripperParams
from gripper.drives import Drive, drive_for, register_drive, unregister_drive
from gripper.parts.names import FingerNames, finger_name

ROOT = Path(__file__).parents[1]

# A rigid two-link finger with a position-servoed knuckle: the simplest drive a user might add.
LINK = (0.05, 0.016, 0.018)  # length, width, height of each link [m]
KP, KV, TORQUE = 2.0, 0.02, 1.0  # knuckle servo: N·m/rad, N·m·s/rad, N·m
TRAVEL = 1.2  # rad


@dataclass(frozen=True)
class KnuckleReading:
    effort: np.ndarray  # knuckle torque [N·m]

    def to_dict(self) -> dict:
        return {"torque_Nm": self.effort.tolist()}


class KnuckleSensor:
    def __init__(self, m, adr):
        self.adr = adr

    def read(self, row, rng=None) -> KnuckleReading:
        return KnuckleReading(effort=np.asarray(row)[..., self.adr])


class KnuckleDrive(Drive):
    kind = "knuckle"
    model_name = "knuckle_gripper"
    peak_effort_record = "peak_torque_Nm"  # its own key in the record's drive entry
    command_record = "close_command_rad"
    effort_label = "knuckle torque [N·m]"

    n_segments = 2
    finger_length = 2 * LINK[0]
    finger_height = LINK[2]
    finger_width = LINK[1]

    def names(self, k: int) -> FingerNames:
        return FingerNames(finger_name(k), 2, first_hinge=2, actuator="motor")

    def _box(self) -> np.ndarray:
        length, w, h = LINK
        return np.array([[x, y, z] for x in (0, length) for y in (-w / 2, w / 2) for z in (0, h)], dtype=float)

    def add_meshes(self, spec):
        spec.add_mesh(name="link", uservert=self._box().ravel().tolist())

    def add_finger(self, spec, parent, k, pos, quat, defaults, pads):
        names = self.names(k)
        body = parent.add_body(name=names.mount, pos=list(pos), quat=list(quat))
        for j in (1, 2):
            seg = body.add_body(name=f"{names.prefix}_seg{j}", pos=[LINK[0] if j == 2 else 0.0, 0, 0])
            if j == 2:
                spec.add_exclude(bodyname1=body.name, bodyname2=seg.name)
                seg.add_joint(defaults["hinge"], name=names.hinges[0], range=[-0.2, TRAVEL + 0.3], damping=[0.01, 0, 0])
            collision = seg.add_geom(defaults["collision"], name=f"{names.prefix}_seg{j}_collision",
                                     type=mujoco.mjtGeom.mjGEOM_MESH, meshname="link")
            host = seg if pads is None else pads(seg, j, "link", collision, self._box(), LINK[0] * LINK[1])
            host.add_site(defaults["pad"], name=names.pads[j - 1], pos=[LINK[0] / 2, 0, LINK[2]],
                          size=[LINK[0] / 2, LINK[1] / 2, 0.0025])
            body = seg
        act = spec.add_actuator(name=names.drive, target=names.hinges[0], trntype=mujoco.mjtTrn.mjTRN_JOINT)
        act.set_to_position(kp=KP, kv=KV)
        act.ctrllimited = act.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
        act.ctrlrange, act.forcerange = [0.0, TRAVEL], [-TORQUE, TORQUE]
        spec.add_sensor(name=f"{names.drive}_torque", type=mujoco.mjtSensor.mjSENS_ACTUATORFRC,
                        objname=names.drive, objtype=mujoco.mjtObj.mjOBJ_ACTUATOR)
        for pad in names.pads:
            spec.add_sensor(name=pad, type=mujoco.mjtSensor.mjSENS_TOUCH, objname=pad,
                            objtype=mujoco.mjtObj.mjOBJ_SITE)
        return names

    contact_modulus = 1e6  # a stiffer silicone skin [Pa]
    pad_depth = 0.003

    def pad_kinds(self):
        return ("link",)

    def pad_vertices(self, kind):
        return self._box()

    def element_vertices(self, j):
        return self._box()

    def element_kind(self, j):
        return "link"

    def face_area(self, j):
        return LINK[0] * LINK[1]

    def effort_sensors(self, m):
        adr = np.array([m.sensor_adr[m.sensor(f"{self.actuator_name(k)}_torque").id]
                        for k in range(self.params.layout.n_fingers)])
        return adr, np.ones(len(adr))

    def sensor(self, m, rng=None, sensing=None):
        return KnuckleSensor(m, self.effort_sensors(m)[0])

    def command_rate(self, protocol):
        return 2.0

    def reach_commands(self):
        return np.linspace(0.0, TRAVEL, 13)

    def open_loop_rate(self, protocol):
        return 1.0  # rad/s


@pytest.fixture(scope="module")
def knuckle():
    register_drive("knuckle", KnuckleDrive)
    try:
        yield GripperParams(actuation=Actuation(kind="knuckle")).validate()
    finally:
        unregister_drive("knuckle")  # the other tests see the shipped drives only


def test_a_third_drive_builds_a_gripper(knuckle):
    from gripper.model.builders import build_gripper_spec

    assert isinstance(drive_for(knuckle), KnuckleDrive)
    m = build_gripper_spec(knuckle).compile()
    assert m.nu == 4 + 3 + 1  # a knuckle per finger, the lift stage and the wrist
    assert [m.actuator(k).name for k in range(4)] == [f"f{k}_motor" for k in range(4)]
    # the shared parts: the pads (their slide joints and springs) and the lift
    assert sum(m.joint(j).name.endswith("_padslide") for j in range(m.njnt)) == 8
    assert m.body("f2_seg2").id > 0 and m.opt.timestep > 0


def test_a_third_drive_runs_a_grasp_trial(knuckle):
    from gripper.experiments.protocol import GraspProtocol
    from gripper.experiments.trial import run_trial

    proto = GraspProtocol(policy="per_object", grasp="envelope")
    rec = run_trial("cylinder", seed=0, index=0, params=knuckle, protocol=proto)
    assert rec.status == "ok", rec.get("error")
    # the palm camera found the cylinder, the knuckles closed on it to the cylinder's closing
    # command clipped to their travel, every finger pressed it, and it was lifted and held
    assert rec.depth_estimate is not None and rec.grasp == "envelope"
    assert rec.drive["close_command_rad"] == pytest.approx(TRAVEL)
    assert min(rec.peak_finger_force_N) > 0.0
    assert rec.success and rec.lift_height_m >= proto.success_height
    # the drive's own entry: its kind, its peak knuckle torque (at most the servo's limit), and
    # its sensor's readings; nothing of a cable
    assert rec.drive["kind"] == "knuckle" and 0.0 < rec.drive["peak_torque_Nm"] <= TORQUE + 1e-9
    assert len(rec.drive["at_grasp"]["torque_Nm"]) == 4
    assert not any("cable" in key for key in rec.to_dict())


def test_a_third_drive_is_refused_where_it_cannot_run(knuckle):
    from gripper.experiments.protocol import GraspProtocol

    with pytest.raises(ValueError, match="^protocol.policy: the knuckle gripper"):
        drive_for(knuckle).check_set_point(GraspProtocol())
    with pytest.raises(ValueError, match="^actuation.kind: must be one of cable, pneumatic, knuckle"):
        GripperParams(actuation=Actuation(kind="vacuum")).validate()


# What asking a drive's kind looks like: a comparison with a drive's name, the pneumatic flag of
# earlier versions, or an isinstance test on a drive's own classes.
KIND_TESTS = re.compile(r"""actuation\.kind\s*[!=]=|kind\s*[!=]=\s*["'](cable|pneumatic)["']|pneumatic_fingers"""
                        r"""|isinstance\([^)]*(Pressure|Servo|Grip)(Controller|Sensor|Reading)""")


def test_no_code_outside_the_drives_asks_for_the_drive():
    """Only the drive folders and the command line's option parsing may test the drive's kind."""
    allowed = ("gripper/drives/", "gripper/cli/options.py", "gripper/cli/commands/pullout.py")
    found = []
    for path in sorted((ROOT / "gripper").rglob("*.py")):
        rel = path.relative_to(ROOT).as_posix()
        if rel.startswith(allowed):
            continue
        for n, line in enumerate(path.read_text().splitlines(), 1):
            if KIND_TESTS.search(line):
                found.append(f"{rel}:{n}: {line.strip()}")
    assert not found, "\n".join(found)


@pytest.mark.parametrize("kind", ["cable", "pneumatic"])
def test_each_drive_reports_its_set_points_quantity(kind):
    """A drive's sensor reading carries ``effort`` in the set-point's unit, and its effort
    sensors read the same quantity, noiseless: the cable's tension, the chamber's pressure."""
    from gripper.sim.scene import grasp_scene_spec, trial_params

    p = GripperParams(actuation=Actuation(kind=kind)).validate()
    drive = drive_for(p)
    m = grasp_scene_spec(trial_params(p)).compile()
    d = mujoco.MjData(m)
    act = drive.actuator_ids(m)
    d.ctrl[act] = 0.6 * m.actuator_ctrlrange[act, 1]
    mujoco.mj_step(m, d, 500)  # 1 s: the fingers curl, the cables tighten, the chambers fill
    adr, divisor = drive.effort_sensors(m)
    true = d.sensordata[adr] / divisor
    assert np.all(true > 0)
    reading = drive.sensor(m, np.random.default_rng(0)).read(d.sensordata)
    # within the hardware's noise and quantisation: 4 sigma of the load cell's 0.05 N, 5 sigma of
    # the pressure monitor's 1 kPa (gripper.drives.*.sensing)
    np.testing.assert_allclose(reading.effort, true, rtol=0.05, atol=0.2 if kind == "cable" else 5e3)
