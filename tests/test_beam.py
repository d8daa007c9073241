import numpy as np
import pytest

from gripper.parts.beam import chain_tip_position, elastica_tip_force, elastica_tip_moment

L, EI = 0.1, 1.0e-3


def test_elastica_reference_values():
    # pure moment M·L/EI = π: a half circle, tip at (0, 2L/π)
    assert np.allclose(elastica_tip_moment(np.pi, L), [0, 2 * L / np.pi], atol=1e-12)
    # tip load F·L²/EI = 10: Bisshopp & Drucker (1945): vertical deflection 0.8106 L
    assert elastica_tip_force(10.0, L)[1] / L == pytest.approx(0.8106, abs=5e-4)


@pytest.mark.parametrize(("kind", "load"), [("moment", 0.5), ("moment", 1.5), ("moment", np.pi),
                                            ("force", 1.0), ("force", 5.0), ("force", 10.0)])
def test_chain_of_ten_matches_elastica(kind, load):
    exact = (elastica_tip_moment if kind == "moment" else elastica_tip_force)(load, L)
    tip = chain_tip_position(kind, load, n=10, length=L, ei=EI)
    assert np.linalg.norm(tip - exact) <= 0.01 * L


@pytest.mark.parametrize(("kind", "load"), [("moment", np.pi), ("force", 10.0)])
def test_error_shrinks_with_n(kind, load):
    exact = (elastica_tip_moment if kind == "moment" else elastica_tip_force)(load, L)
    errs = [np.linalg.norm(chain_tip_position(kind, load, n=n, length=L, ei=EI) - exact)
            for n in (5, 10, 20)]
    assert errs[0] > errs[1] > errs[2]
    # midpoint rule: second order, halving h quarters the error (allow 3x)
    assert errs[1] / errs[2] > 3.0
