"""The hostile-input campaign (tests/hostile_inputs.py): the first case of every kind in the
default suite, the rest as slow tests; ``scripts/bad_input_campaign.py`` runs them all and prints
the totals."""

from __future__ import annotations

import pytest
from hostile_inputs import CASES, first_of_each_kind, run_case

FIRST = first_of_each_kind()


def _id(case) -> str:
    return f"{case.kind}: {case.name}"


@pytest.mark.parametrize("case", FIRST, ids=_id)
def test_each_kind_of_hostile_input_is_refused_in_one_line(case):
    kind, text = run_case(case)
    assert kind == "refused", f"{kind}: {text}"


@pytest.mark.slow
@pytest.mark.parametrize("case", [c for c in CASES if c not in FIRST], ids=_id)
def test_every_hostile_input_is_refused_in_one_line(case):
    kind, text = run_case(case)
    assert kind == "refused", f"{kind}: {text}"
