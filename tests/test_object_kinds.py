"""Object kinds are components: one module each behind ``ObjectKind``, a registry, and no code
outside ``gripper/objects/`` that asks an object which kind it is. A kind defined here, in the
test file alone, builds, runs a grasp trial through the normal code and is read from an object
file (the guide it follows: docs/architecture.md, "Add an object kind")."""

from __future__ import annotations

import math
import re
from pathlib import Path

import mujoco
import pytest

from gripper.core.ranges import Range
from gripper.objects.files import load_object_file
from gripper.objects.grasp_object import GraspObject
from gripper.objects.kinds import Criterion, ObjectKind, object_kind, register_object_kind, unregister_object_kind
from gripper.objects.kinds.rigid import RigidKind
from gripper.objects.scene_objects import Placement, add_object

ROOT = Path(__file__).resolve().parents[1]

# A peak contact force limit of its own: a capsule of brittle glass, broken above 12 N (its own
# criterion, so that the trial's damage goes through the kind and not the built-in table).
BREAK = Criterion("peak total contact force before it cracks [N]", Range(0.0, 100.0, "N", "a glass ampoule"))


class UprightCapsule(RigidKind):
    """An upright capsule (``size``: radius, radius, half-height including the caps)."""

    name = "test_capsule"
    yaw_symmetric = True
    criteria = {"crack_force": BREAK}
    own_criterion = "crack_force"

    def add_geom(self, spec, body, obj):
        r, _, hz = obj.size
        return body.add_geom(name="object_geom", type=mujoco.mjtGeom.mjGEOM_CAPSULE, size=[r, hz - r, 0])

    def volume(self, size):
        r, _, hz = size
        return math.pi * r ** 2 * 2 * (hz - r) + 4 / 3 * math.pi * r ** 3

    def check(self, obj, where):
        if obj.size[2] <= obj.size[0]:
            raise ValueError(f"{where}.size: a capsule's half-height must exceed its radius, got {list(obj.size)}")


@pytest.fixture
def capsule_kind():
    register_object_kind(UprightCapsule())
    try:
        yield
    finally:
        unregister_object_kind("test_capsule")  # the other tests see the shipped kinds only


def _capsule(**changes) -> GraspObject:
    fields = dict(name="ampoule", kind="test_capsule", size=(0.015, 0.015, 0.035), mass=0.04, friction=0.8,
                  yaw_symmetric=True, close_command=3.0, damage="crack_force", damage_limit=12.0)
    return GraspObject(**{**fields, **changes}).validate()


def test_a_new_kind_builds_and_is_validated(capsule_kind):
    obj = _capsule()
    assert obj.object_kind.name == "test_capsule" and not obj.is_flex
    assert obj.damage_measure.startswith("peak total contact force before it cracks")
    assert obj.is_damaged(12.5) and not obj.is_damaged(11.5)
    spec = mujoco.MjSpec()
    add_object(spec, obj, Placement())
    m = spec.compile()
    assert m.geom("object_geom").type == mujoco.mjtGeom.mjGEOM_CAPSULE
    assert m.body("object").mass[0] == pytest.approx(0.04)
    with pytest.raises(ValueError, match=r"object\.ampoule\.size: a capsule's half-height"):
        _capsule(size=(0.015, 0.015, 0.012))
    with pytest.raises(ValueError, match=r"object\.ampoule\.damage: a test_capsule allows crack_force"):
        _capsule(damage="contact_force")
    with pytest.raises(ValueError, match=r"object\.ampoule\.damage_limit"):
        _capsule(damage_limit=500.0)


def test_a_new_kind_is_read_from_an_object_file(tmp_path, capsule_kind):
    path = tmp_path / "ampoule.toml"
    path.write_text('[object]\nname = "ampoule"\nkind = "test_capsule"\nsize = [0.015, 0.015, 0.035]\n'
                    'density = 2500.0\nfriction = 0.8\n[damage]\nlimit = 12.0\n')
    obj = load_object_file(path)
    assert obj.damage == "crack_force" and obj.yaw_symmetric  # the kind's own defaults
    assert obj.mass == pytest.approx(2500.0 * UprightCapsule().volume(obj.size))


def test_an_unregistered_kind_is_refused_with_the_registered_ones():
    with pytest.raises(ValueError, match=r"object\.ampoule\.kind: must be one of rigid_box, .*zipper_bag, got "
                                         r"'test_capsule'"):
        _capsule()


def test_a_new_kind_runs_a_grasp_trial(capsule_kind):
    from gripper.experiments.protocol import GraspProtocol
    from gripper.experiments.trial import run_trial

    proto = GraspProtocol()
    rec = run_trial(_capsule(), seed=0, index=0, protocol=proto)
    assert rec.status == "ok", rec.get("error")
    # found by the palm camera, squeezed by every finger and lifted; its damage is its own
    # criterion's measure, the peak total contact force, against its own 12 N limit, and a
    # cracked ampoule is not a success however well it was held
    assert rec.depth_estimate is not None and min(rec.peak_finger_force_N) > 0.0
    assert rec.lift_height_m >= proto.success_height
    assert rec.damage_measure == pytest.approx(rec.peak_total_force_N) and rec.damage_limit == 12.0
    assert rec.damaged == (rec.peak_total_force_N > 12.0)
    assert rec.success == (not rec.damaged)


def test_every_kind_declares_what_the_trial_asks():
    for name in ("rigid_box", "rigid_cylinder", "rigid_sphere", "mesh", "balloon", "paper_box", "bag", "zipper_bag"):
        kind = object_kind(name)
        assert isinstance(kind, ObjectKind) and kind.criteria
        assert kind.own_criterion is None or kind.own_criterion in kind.criteria
        assert kind.deformable == (kind.default_mesh_points != (0, 0, 0))


# What asking an object's kind looks like: a comparison of an object's kind, a kind name that
# no library object is called, or a list of kinds kept by hand.
KIND_TESTS = re.compile(r"""(?<![\w])(?:[\w.]*\.)?obj(?:ect)?\.kind\b\s*(==|!=|\bin\b|\bnot\s+in\b)"""
                        r"""|["'](rigid_box|rigid_cylinder|rigid_sphere|zipper_bag)["']"""
                        r"""|\b(STRAIN_DAMAGE|RIGID|DEFORMABLE|FLEX)_KINDS\b""")


def test_no_code_outside_the_objects_asks_for_the_kind():
    """Only gripper/objects/ may test an object's kind; everything else asks the kind."""
    found = []
    for path in sorted((ROOT / "gripper").rglob("*.py")):
        rel = path.relative_to(ROOT).as_posix()
        if rel.startswith("gripper/objects/"):
            continue
        for n, line in enumerate(path.read_text().splitlines(), 1):
            if KIND_TESTS.search(line):
                found.append(f"{rel}:{n}: {line.strip()}")
    assert not found, "\n".join(found)


def test_the_grep_sees_a_kind_test():
    """The pattern above finds the forms of kind test the code used before the registry."""
    for line in ('if obj.kind == "paper_box":', "if s.obj.kind in STRAIN_DAMAGE_KINDS:",
                 'if self.probe.obj.kind not in X:', "kinds = ('rigid_box', 'mesh')"):
        assert KIND_TESTS.search(line), line


def test_a_kind_that_declares_what_the_objects_lack_is_refused_at_registration():
    class Porous(UprightCapsule):
        name = "test_porous"
        material_fields = ("porosity",)

    class Unsure(UprightCapsule):
        name = "test_unsure"
        own_criterion = "bruise_energy"

    with pytest.raises(ValueError, match="material fields porosity unknown; allowed: youngs_modulus"):
        register_object_kind(Porous())
    with pytest.raises(ValueError, match="own_criterion 'bruise_energy' is not one of its criteria"):
        register_object_kind(Unsure())
    with pytest.raises(ValueError, match="object.ampoule.kind: must be one of"):
        _capsule(kind="test_porous")  # neither was registered
