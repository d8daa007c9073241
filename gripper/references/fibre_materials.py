"""The actuator's fibre reinforcement as a strain energy for FElupe, added to the silicone's Yeoh
energy in the cells that hold it (:mod:`gripper.references.actuator_mesh`).

- **The helical fibre**, smeared over its layer: two families of fibre (the winding crosses
  itself, right- and left-handed, paper 001 §2.4.2 case 5) along a± = cos α h ± sin α e_z, h the
  winding's path around the cross-section and α the twist angle. Each family stores
  W = φ E_f (I₄ − 1)² / 8 per unit volume (the fibre's Saint Venant-Kirchhoff energy
  E_f ε_GL² / 2, ε_GL = (I₄ − 1)/2, I₄ = a·C·a) while it is stretched (I₄ > 1) and nothing while
  it is shortened (``TENSION_ONLY_FLOOR``): a wound thread carries tension only. Measured on
  the model that kept compression: at 250 kPa a third of the fibre layer's quadrature points
  were shortened, down to ε = -0.5 % on the duct's sides, where a 0.5 mm thread in silicone
  buckles at about (E_silicone / E_fibre)^(2/3) ≈ 7e-4 (a fibre on an elastic foundation);
  tension only bends the default design 3 % further at 250 kPa. φ is the fibre's volume
  fraction in its layer, one thread of diameter d per family every pitch p:
  φ = π d / (4 p cos α).

The fabric neutral layer is a solid of its own (:func:`gripper.references.actuator_fe.fabric_material`),
not an energy added here.

The stress is P = F S (S the second Piola-Kirchhoff stress) and the tangent
A_iJkL = δ_ik S_JL + F_iM C_MJNL F_kN with C = ∂S/∂E = φ E_f a⊗a⊗a⊗a for a stretched family.
The tests check both against finite differences of the energy.

Example:
    >>> import numpy as np
    >>> from gripper.references.fibre_materials import fibre_stress
    >>> F = np.diag([1.0, 1.1, 1.0])[:, :, None, None]          # 10 % stretch along y
    >>> a = np.array([0.0, 1.0, 0.0])[:, None, None]             # a fibre along y
    >>> P, _ = fibre_stress([F, None], directions=[a], stiffness=np.ones((1, 1)))
    >>> round(float(P[1, 1, 0, 0]), 4)   # F S = 1.1 * (1.21 - 1 - δ/2) / 2, δ the toe band
    0.1152
"""

from __future__ import annotations

import numpy as np

EYE = np.eye(3)
TENSION_ONLY_FLOOR = 1.0  # I₄ at or below which a family carries nothing: tension only
# -, the width in I₄ (δ) over which a family's stiffness rises from nothing to φ E_f as it is
# stretched past the floor: a wound thread's toe region, its crimp taken up over the first
# ε_GL = δ/2 = 0.05 % of strain (assumed: the thread's datasheet curve is not among the sources).
# With it the fibre's stress has a continuous tangent; the bare switch (δ = 0) made Newton's method
# alternate between the branches: measured 199 iterations to 50 kPa against 91 with the band, the
# bend at 25 kPa 0.6 % larger (studies' mesh)
TENSION_ONLY_BAND = 1e-3


def ramp(x: np.ndarray, band: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The tension-only ramp g(x) of the stretch measure x = I₄ - 1 and its slope g'(x): 0 for
    x ≤ 0, x²/2δ within the band 0 < x < δ, x - δ/2 past it (δ = ``band``, by default
    ``TENSION_ONLY_BAND``; δ = 0: max(x, 0))."""
    band = TENSION_ONLY_BAND if band is None else band
    if band <= 0:
        on = (x > 0).astype(float)
        return x * on, on
    inside = (x > 0) & (x < band)
    g = np.where(x >= band, x - 0.5 * band, np.where(inside, 0.5 * x * x / band, 0.0))
    slope = np.where(x >= band, 1.0, np.where(inside, x / band, 0.0))
    return g, slope


def _fibre_terms(F: np.ndarray, directions, stiffness: np.ndarray):
    """Per family: (a, F a, tangent stiffness k g', S's coefficient k g / 2)."""
    out = []
    for a in directions:
        fa = np.einsum("iJ...,J...->i...", F, a)
        i4 = np.einsum("i...,i...->...", fa, fa)
        g, slope = ramp(i4 - TENSION_ONLY_FLOOR)
        out.append((a, fa, stiffness * slope, 0.5 * stiffness * g))
    return out


def fibre_stress(x, directions, stiffness):
    """[P, state]: first Piola-Kirchhoff stress [Pa] of the tension-only fibre families.

    ``directions``: unit reference directions, each (3, q or 1, cells); ``stiffness``: φ E_f
    [Pa] per cell (q or 1, cells)."""
    F, state = x[0], x[-1]
    S = np.zeros_like(F)
    for a, _, _, s in _fibre_terms(F, directions, stiffness):
        S += s * np.einsum("I...,J...->IJ...", a, a)
    return [np.einsum("iK...,KJ...->iJ...", F, S), state]


def fibre_elasticity(x, directions, stiffness):
    """[A]: ∂P/∂F of :func:`fibre_stress`."""
    F = x[0]
    terms = _fibre_terms(F, directions, stiffness)
    S = np.zeros_like(F)
    for a, _, _, s in terms:
        S += s * np.einsum("I...,J...->IJ...", a, a)
    A = np.einsum("ik,JL...->iJkL...", EYE, S)
    for a, fa, k, _ in terms:
        A = A + k * np.einsum("i...,J...,k...,L...->iJkL...", fa, a, fa, a)
    return [A]
