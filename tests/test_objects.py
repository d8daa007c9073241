"""Object library, user meshes and the Wilson interval."""

import math

import pytest
import trimesh

from gripper.bench.benchmark import wilson_interval
from gripper.core.params import GripperParams
from gripper.drives import drive_for
from gripper.objects.library import DEFAULT_OBJECTS, get_object, mesh_object
from gripper.objects.scene_objects import Placement


def test_library_fits_the_aperture_with_placement_noise():
    # the open fingers' faces stand open_radius from the axis at their tips; trials offset objects by 10 mm
    from gripper.experiments.approach import open_radius
    from gripper.objects.library import library

    aperture = open_radius(GripperParams())
    for obj in library().values():
        obj.validate()
        assert obj.half_width + 0.010 < aperture, obj.name
        assert obj.height < GripperParams().finger.length, obj.name


def test_default_objects_are_the_five_named():
    assert set(DEFAULT_OBJECTS) == {"balloon", "block", "cylinder", "paper_box", "bag"}


def test_unknown_object_is_refused_naming_the_allowed():
    with pytest.raises(ValueError, match="unknown object 'sphere'.*balloon"):
        get_object("sphere")


def test_mesh_mass_from_density_and_volume(tmp_path):
    path = tmp_path / "part.stl"
    trimesh.creation.box(extents=(0.03, 0.03, 0.05)).export(path)
    obj = mesh_object(path)
    assert math.isclose(obj.mass, 620.0 * 0.03 * 0.03 * 0.05, rel_tol=1e-6)
    assert obj.size == pytest.approx((0.015, 0.015, 0.025))
    assert mesh_object(path, mass=0.1).mass == 0.1
    assert get_object(f"mesh:{path}").kind == "mesh"


def test_open_mesh_is_refused(tmp_path):
    path = tmp_path / "sheet.stl"
    trimesh.Trimesh(vertices=[[0, 0, 0], [0.02, 0, 0], [0, 0.02, 0], [0.02, 0.02, 0.001]],
                    faces=[[0, 1, 2], [1, 3, 2]]).export(path)
    with pytest.raises(ValueError, match="not watertight"):
        mesh_object(path)


def test_unreadable_mesh_is_refused(tmp_path):
    path = tmp_path / "junk.stl"
    path.write_bytes(b"\x00\x01not a mesh")
    with pytest.raises(ValueError, match="mesh"):
        mesh_object(path)
    with pytest.raises(ValueError, match="No such file"):
        mesh_object(tmp_path / "missing.obj")


def test_wilson_interval_known_values():
    # Wilson 95 % interval for 8/10: 0.4902-0.9433 (Newcombe 1998, Table I method 3 style)
    lo, hi = wilson_interval(8, 10)
    assert lo == pytest.approx(0.4902, abs=1e-4) and hi == pytest.approx(0.9433, abs=1e-4)
    lo, hi = wilson_interval(50, 50)
    assert hi == pytest.approx(1.0) and lo == pytest.approx(0.9287, abs=1e-4)


def test_paper_box_shell_is_closed_and_compiles():
    from gripper.objects.kinds.flex import box_shell
    from gripper.sim.scene import build_grasp_scene
    obj = get_object("paper_box")
    mesh = box_shell(obj.size, obj.mesh_points)
    assert mesh.is_watertight and mesh.volume == pytest.approx(8 * obj.size[0] * obj.size[1] * obj.size[2])
    m = build_grasp_scene(GripperParams(), obj, Placement())
    assert m.nflex == 1 and m.flex_vertnum[0] == len(mesh.vertices)
    # a closed grid surface of nx x ny x nz points: 2 (nx ny + ny nz + nz nx) - 4 (nx + ny + nz) + 8 vertices
    nx, ny, nz = obj.mesh_points
    assert len(mesh.vertices) == 2 * (nx * ny + ny * nz + nz * nx) - 4 * (nx + ny + nz) + 8


@pytest.mark.parametrize("name", ["paper_box", "bag", "bag_pack", "balloon"])
def test_the_mesh_resolution_reaches_the_flex(name):
    import dataclasses

    from gripper.sim.scene import build_grasp_scene
    obj = get_object(name)
    counts = {}
    for pts in (obj.mesh_points, (6, 6, 7)):
        m = build_grasp_scene(GripperParams(), dataclasses.replace(obj, mesh_points=pts), Placement())
        counts[pts] = int(m.flex_vertnum[0])
    assert counts[(6, 6, 7)] > counts[obj.mesh_points]


def test_the_zipper_bag_is_built_from_its_sources():
    """The default bag's numbers follow from its cited sources (gripper/data/objects/bag.toml):
    the film mass from the 38 x 64 mm flat size, the 42.5 µm gauge and LDPE's density, and the
    filled size from the flat sheet going round the 16 mm thickness; the scene holds the film
    flex and both bricks, loose, and the probe counts both as the object."""
    from gripper.sim.probes import ObjectProbe
    from gripper.sim.scene import build_grasp_scene

    obj = get_object("bag")
    assert obj.kind == "zipper_bag" and obj.contents_count == 2
    film = obj.mass - obj.contents_count * obj.contents_mass
    assert film == pytest.approx(2 * 0.038 * 0.064 * obj.thickness * 920.0, rel=0.02)
    thick = 2 * obj.size[2]
    assert 2 * obj.size[0] == pytest.approx(0.064 - thick, abs=1e-3)
    assert 2 * obj.size[1] == pytest.approx(0.038 - thick, abs=1e-3)
    m = build_grasp_scene(GripperParams(), obj, Placement(yaw=0.7))
    bricks = [b for b in range(m.nbody) if m.body(b).name.startswith("object_contents_")]
    assert len(bricks) == 2 and all(m.body_jntnum[b] == 1 for b in bricks)
    assert sum(m.body_mass[b] for b in bricks) == pytest.approx(2 * obj.contents_mass)
    probe = ObjectProbe(m, obj, 4, drive_for(GripperParams()))
    assert probe.object_geom[[m.body_geomadr[b] for b in bricks]].all() and probe.flex >= 0
