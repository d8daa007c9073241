"""Small, long and low everyday parts the default object set does not have, built as meshes here
(trimesh) and grasped as user meshes are (:func:`gripper.objects.mesh_objects.mesh_object`): a
22 mm die, an AA cell lying on the table and a 130 mm pen lying on the table.

Each part's dimensions and mass carry their source in :data:`PARTS`; the meshes are written to a
folder the caller gives (nothing is committed or downloaded), so a run rebuilds them.

Example:
    >>> import tempfile
    >>> from gripper.objects.everyday_parts import everyday_part
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     die = everyday_part("die", tmp)
    >>> [round(2e3 * h, 1) for h in die.size]           # mm
    [22.0, 22.0, 22.0]
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from gripper.objects.grasp_object import GraspObject


@dataclass(frozen=True)
class PartSpec:
    """One everyday part: its shape's dimensions [m], its mass [kg], and where they come from."""

    shape: str
    dimensions: tuple[float, ...]
    mass: float
    source: str


PARTS = {
    # a cube with rounded edges (a casino-style die's 22 mm class; the pips' 1 mm recesses are left
    # out: contact meets the convex hull)
    "die": PartSpec("rounded_cube", (0.022, 0.002), 0.0125,
                    "the issue's 22 mm die; edge radius 2 mm assumed; mass: 22 mm cube of acrylic, "
                    "1180 kg/m³ (assumed material)"),
    # an AA (LR6) cell lying on its side: a cylinder 14.5 mm across and 50.5 mm long
    "aa_cell": PartSpec("lying_cylinder", (0.0145, 0.0505), 0.023,
                        "IEC 60086-2 LR6: 14.5 mm diameter, 50.5 mm long; mass 23 g, a typical alkaline "
                        "AA's datasheet value"),
    # a ballpoint pen lying on the table: a hexagonal barrel 8 mm across its flats, 115 mm long,
    # and a 15 mm cone to a 2 mm tip (130 mm over all)
    "pen": PartSpec("pen", (0.008, 0.115, 0.015, 0.002), 0.006,
                    "the issue's 130 mm pen; an 8 mm hexagonal barrel and 6 g, a disposable "
                    "ballpoint's class (assumed)"),
}
# Silicone on the parts' plastic or printed label: the library's 0.6 (assumed, as for the block).
PART_FRICTION = 0.6
# The largest contact force a part takes before counting as damaged [N]: the block's limit.
PART_FORCE_LIMIT = 200.0


def part_mesh(spec: PartSpec):
    """The part's watertight, convex trimesh (metres), its base at z = 0."""
    import trimesh

    if spec.shape == "rounded_cube":
        side, r = spec.dimensions
        corner = 0.5 * side - r
        ball = trimesh.creation.icosphere(subdivisions=2, radius=r).vertices
        pts = [ball + np.array([sx, sy, sz]) * corner for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
        mesh = trimesh.convex.convex_hull(np.vstack(pts))
    elif spec.shape == "lying_cylinder":
        diameter, length = spec.dimensions
        mesh = trimesh.creation.cylinder(radius=0.5 * diameter, height=length, sections=48)
        mesh.apply_transform(trimesh.transformations.rotation_matrix(0.5 * math.pi, [0, 1, 0]))
    elif spec.shape == "pen":
        flats, barrel, cone, tip = spec.dimensions
        corner = flats / math.sqrt(3.0)  # a hexagon's corner radius from its width across flats
        phi = np.arange(6) * math.pi / 3
        hexagon = np.column_stack([corner * np.cos(phi), corner * np.sin(phi)])
        ring = np.column_stack([np.zeros(8), 0.5 * tip * np.cos(np.arange(8) * math.pi / 4),
                                0.5 * tip * np.sin(np.arange(8) * math.pi / 4)])
        pts = [np.column_stack([np.full(6, x), hexagon]) for x in (0.0, barrel)]
        pts.append(ring + np.array([barrel + cone, 0.0, 0.0]))
        # corners at 0°, 60°, ... from +y: the edge from 60° to 120° is a flat, so the pen lies on one
        mesh = trimesh.convex.convex_hull(np.vstack(pts))
    else:
        raise ValueError(f"part shape: {spec.shape!r} is not one of rounded_cube, lying_cylinder, pen")
    mesh.apply_translation(-mesh.bounds.mean(axis=0))
    mesh.apply_translation([0.0, 0.0, -mesh.bounds[0, 2]])
    return mesh


def everyday_part(name: str, folder: str | Path) -> GraspObject:
    """The part ``name`` (:data:`PARTS`) as a grasp object, its mesh written to ``folder``.

    Raises:
        ValueError: an unknown name, listing the known ones.
    """
    from gripper.objects.mesh_objects import mesh_object

    if name not in PARTS:
        raise ValueError(f"part: unknown part {name!r}; allowed: {', '.join(PARTS)}")
    spec = PARTS[name]
    path = Path(folder) / f"{name}.stl"
    part_mesh(spec).export(path)
    return mesh_object(path, mass=spec.mass, friction=PART_FRICTION, name=name,
                       damage="contact_force", damage_limit=PART_FORCE_LIMIT,
                       reasons=(("size", spec.source), ("mass", spec.source)))


__all__ = ["PARTS", "PART_FORCE_LIMIT", "PART_FRICTION", "PartSpec", "everyday_part", "part_mesh"]
