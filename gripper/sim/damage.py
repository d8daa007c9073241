"""Damage measures of grasped objects: each object's kind measures its own
(``ObjectKind.damage_measure``: peak edge strain, permanent dent, peak contact force, ...)."""

from __future__ import annotations

from gripper.sim.probes import ObjectProbe


def damage_measure(m, d, obj, probe: ObjectProbe, *, peak_strain: float, peak_force: float) -> float:
    """The object's damage measure at the trial's end, as its kind defines it (peak edge strain
    of a film, permanent dent of a card box after spring-back from the state in ``d``, else the
    peak total contact force [N])."""
    return obj.object_kind.damage_measure(m, d, obj, probe, peak_strain=peak_strain, peak_force=peak_force)


def running_damage_measure(m, d, obj, probe: ObjectProbe, *, peak_strain: float, total_force: float) -> float:
    """The damage measure where it must be read at every step (the environment), as the
    object's kind defines it (a card box counts any crease, stricter than its dent)."""
    return obj.object_kind.running_damage(m, d, obj, probe, peak_strain=peak_strain, total_force=total_force)
