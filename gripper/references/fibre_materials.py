"""The actuator's two reinforcements as strain energies for FElupe, added to the silicone's Yeoh
energy in the cells that hold them (:mod:`gripper.references.actuator_mesh`).

- **The helical fibre**, smeared over its layer: two families of fibre (the winding crosses
  itself, right- and left-handed, paper 001 §2.4.2 case 5) along a± = cos α h ± sin α e_z, h the
  winding's path around the cross-section and α the twist angle. Each family stores
  W = φ E_f (I₄ − 1)² / 8 per unit volume (the fibre's Saint Venant-Kirchhoff energy
  E_f ε_GL² / 2, ε_GL = (I₄ − 1)/2, I₄ = a·C·a), in tension and in compression
  (``TENSION_ONLY_FLOOR``: a tension-only switch at I₄ = 1 made Newton's method chatter between
  the two branches and fail within the first 25 kPa; the fibre runs nearly in the hoop
  direction, which the pressure keeps stretched). φ is the fibre's volume fraction in its layer,
  one thread of diameter d per family every pitch p: φ = π d / (4 p cos α).
- **The fabric neutral layer** as a membrane: the plane-stress Saint Venant-Kirchhoff energy of
  its in-plane Green-Lagrange strains (across x and along z; E, ν), without the transverse shear
  that would lock the thin eight-node cells in bending, so the layer keeps its own bending
  stiffness E t³/12 (linear strain through one cell) and its inextensibility.

For each the stress is P = F S (S the second Piola-Kirchhoff stress) and the tangent
A_iJkL = δ_ik S_JL + F_iM C_MJNL F_kN with C = ∂S/∂E; for a fibre family, C = φ E_f a⊗a⊗a⊗a.
The tests check both against finite differences of the energy.

Example:
    >>> import numpy as np
    >>> from gripper.references.fibre_materials import fibre_stress
    >>> F = np.diag([1.0, 1.1, 1.0])[:, :, None, None]          # 10 % stretch along y
    >>> a = np.array([0.0, 1.0, 0.0])[:, None, None]             # a fibre along y
    >>> P, _ = fibre_stress([F, None], directions=[a], stiffness=np.ones((1, 1)))
    >>> round(float(P[1, 1, 0, 0]), 4)   # F S = 1.1 * (1.21 - 1) / 2
    0.1155
"""

from __future__ import annotations

import numpy as np

EYE = np.eye(3)
TENSION_ONLY_FLOOR = 0.0  # I₄ below which a family carries nothing (0: never; 1.0 would be tension only)


def _fibre_terms(F: np.ndarray, directions, stiffness: np.ndarray):
    """Per family: (F a, stretched mask × stiffness, S contribution)."""
    out = []
    for a in directions:
        fa = np.einsum("iJ...,J...->i...", F, a)
        i4 = np.einsum("i...,i...->...", fa, fa)
        k = stiffness * (i4 > TENSION_ONLY_FLOOR)
        out.append((a, fa, k, 0.5 * k * (i4 - 1.0)))
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


def membrane_tensor(modulus: float, poisson: float, axes=(0, 2)) -> np.ndarray:
    """The plane-stress elasticity C_IJKL [Pa] acting on the Green-Lagrange strain's components
    in the plane of ``axes`` (default x and z); zero on the others."""
    lam = modulus * poisson / (1.0 - poisson ** 2)
    mu = modulus / (2.0 * (1.0 + poisson))
    mask = np.zeros(3)
    mask[list(axes)] = 1.0
    d = np.diag(mask)
    return (lam * np.einsum("IJ,KL->IJKL", d, d)
            + mu * (np.einsum("IK,JL->IJKL", d, d) + np.einsum("IL,JK->IJKL", d, d)))


def _membrane_pk2(F: np.ndarray, tensor: np.ndarray) -> np.ndarray:
    """S = C:E, E = (FᵀF - 1)/2 the Green-Lagrange strain."""
    E = 0.5 * (np.einsum("kI...,kJ...->IJ...", F, F) - EYE.reshape(3, 3, *([1] * (F.ndim - 2))))
    return np.einsum("IJKL,KL...->IJ...", tensor, E)


def membrane_stress(x, tensor):
    """[P, state]: first Piola-Kirchhoff stress [Pa] of the membrane energy ½ E:C:E."""
    F, state = x[0], x[-1]
    return [np.einsum("iK...,KJ...->iJ...", F, _membrane_pk2(F, tensor)), state]


def membrane_elasticity(x, tensor):
    """[A]: ∂P/∂F of :func:`membrane_stress`."""
    F = x[0]
    S = _membrane_pk2(F, tensor)
    FC = np.einsum("iM...,MJNL->iJNL...", F, tensor)
    return [np.einsum("ik,JL...->iJkL...", EYE, S) + np.einsum("iJNL...,kN...->iJkL...", FC, F)]
