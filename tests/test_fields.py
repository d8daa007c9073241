"""Field metadata is the one home of each parameter's unit, range and source, and it is what
validation, the model README's table and the command line's help read."""

from __future__ import annotations

import dataclasses
import math
import re

import pytest

from gripper.core.fields import field_specs
from gripper.core.params import _SECTIONS, GripperParams, parameter_help, parameter_rows
from gripper.experiments.protocol import BendingConfig, GraspProtocol, TrialNoise
from gripper.objects.scene_objects import Placement
from gripper.sim.model_files import parameter_table, shipped_grippers

CLASSES = [(name, cls) for name, cls in _SECTIONS.items()] + [("protocol", GraspProtocol), ("noise", TrialNoise),
                                                           ("bend", BendingConfig), ("placement", Placement)]


def _outside(spec):
    """Values just outside each bound of ``spec`` (none for unbounded or non-numeric fields)."""
    out = []
    if spec.kind in ("number", "integer", "numbers"):
        def step(bound):
            return 1 if spec.kind == "integer" else 1e-6 * max(1, abs(bound))

        if spec.lo is not None:
            out.append(spec.lo if spec.lo_open else spec.lo - step(spec.lo))
        if spec.hi is not None:
            out.append(spec.hi if spec.hi_open else spec.hi + step(spec.hi))
    return out


@pytest.mark.parametrize(("section", "cls"), CLASSES, ids=[c[0] for c in CLASSES])
def test_every_field_declares_unit_and_source(section, cls):
    specs = field_specs(cls)
    assert set(specs) == {f.name for f in dataclasses.fields(cls)}, "a field without metadata"
    for name, spec in specs.items():
        assert spec.unit, f"{section}.{name}: no unit"
        assert spec.source, f"{section}.{name}: no source"


@pytest.mark.parametrize(("section", "cls"), CLASSES, ids=[c[0] for c in CLASSES])
def test_replace_refuses_every_value_outside_its_declared_range(section, cls):
    base = cls()
    for name, spec in field_specs(cls).items():
        for bad in _outside(spec):
            value = (bad,) if spec.kind == "numbers" else bad
            allowed = re.escape(spec.allowed())
            with pytest.raises(ValueError, match=rf"^{section}\.{name}(\[0\])?: must be {allowed}( \(.*\))?, got"):
                base.replace(**{name: value})
        if spec.kind in ("number", "numbers"):
            with pytest.raises(ValueError, match=rf"^{section}\.{name}"):
                base.replace(**{name: (math.nan,) if spec.kind == "numbers" else math.nan})


def test_the_defaults_are_inside_their_declared_ranges():
    GripperParams().validate()
    GraspProtocol().validate()
    TrialNoise().validate()


def test_table_and_help_are_read_from_the_metadata():
    """Each shipped gripper's model README lists its drive's sections; together they list all."""
    rows = parameter_rows()
    tables = "\n".join(parameter_table(p) for p in shipped_grippers().values())
    help_text = parameter_help()
    for section, name, _value, spec in rows:
        line = next(r for r in tables.splitlines() if r.startswith(f"| {section} | {name} |"))
        assert f"| {spec.unit} | {spec.allowed()} | {spec.source} |" in line
        assert f"{section}.{name} = " in help_text
    assert len(rows) == sum(len(field_specs(c)) for c in _SECTIONS.values())
