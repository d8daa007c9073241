"""Which bridge makes paper 000's spring consistent with its silicone: a root-find on the
converged continuum reference.

Paper 000 gives the silicone (E 0.44 MPa, ν 0.48, Table 2), the cut angle (45°), the hole
(Ø 6 mm) and a torsion spring of "1.9e-3 N·m/deg" (Table 2), but no outer dimensions (its
figures are lost). The spring of a bridge of thickness t follows from the body: at a small
tension T the straight cable loads the finger by its knot alone, so every bridge carries the
moment ``T·lever`` (lever: the cable's height above the hinge axis) and a chain of equal springs
bends by ``n·T·lever/K``. Hence the body's equivalent hinge stiffness

    K_eq(t) = n_hinges · lever / (d bending / dT),

with the compliance from the mesh-converged reference
(:func:`gripper.references.convergence.mesh_convergence`, Richardson-extrapolated).
:func:`bridge_for_stiffness` solves ``K_eq(t) = K`` by a secant iteration on log K against
log t (a power law, so two or three steps suffice). A reading of K that needs a bridge the
finger cannot hold (thicker than the room left under the 6 mm hole) is evidence against that
reading.

Example:
    >>> from gripper.calibration.consistency import bridge_for_stiffness
    >>> bridge_for_stiffness(1.9e-3)["bridge_thickness_m"]       # doctest: +SKIP
"""

from __future__ import annotations

import math

from gripper.core.params import GripperParams
from gripper.references.convergence import mesh_convergence


def equivalent_stiffness(params: GripperParams | None = None, on_progress=None) -> dict:
    """The converged body's equivalent hinge stiffness K_eq [N·m/rad] (module docstring)."""
    p = (params or GripperParams()).validate()
    g = p.finger
    conv = mesh_convergence(p, on_progress=on_progress)
    compliance = math.radians(conv.richardson.extrapolated)  # rad/N
    lever = g.hole_height - g.hinge_z
    return {"bridge_thickness_m": g.bridge_thickness,
            "stiffness_Nm_per_rad": g.n_hinges * lever / compliance,
            "compliance_deg_per_N": conv.richardson.extrapolated,
            "gci_fine": conv.richardson.gci_fine, "order": conv.richardson.order}


# Thinnest silicone wall between the bridge's top and the cable channel that can be moulded
# [m]. Assumed 1 mm: the moulds of paper 000's body are 3D-printed (a core for the channel).
MIN_WALL_UNDER_CHANNEL = 1.0e-3


def max_bridge_thickness(params: GripperParams) -> float:
    """Thickest bridge the finger holds under its cable channel [m]: the channel's floor less
    ``MIN_WALL_UNDER_CHANNEL``."""
    from gripper.references.finger_mesh import channel_side

    g = params.finger
    return g.hole_height - 0.5 * channel_side(g) - MIN_WALL_UNDER_CHANNEL


def bridge_for_stiffness(target: float, params: GripperParams | None = None, *,
                         rtol: float = 0.01, max_iter: int = 6, on_progress=None,
                         known: list[dict] | None = None) -> dict:
    """Bridge thickness [m] at which the converged body's K_eq equals ``target`` [N·m/rad].

    Args:
        known: evaluations already made (``equivalent_stiffness`` results), reused.

    Returns:
        dict with ``bridge_thickness_m`` (None when the target lies beyond the thickest bridge
        the finger holds), ``stiffness_Nm_per_rad`` there, ``evaluations`` and ``feasible``.
    """
    p = (params or GripperParams()).validate()
    say = on_progress or (lambda msg: None)
    pts = list(known or [])
    t_max = max_bridge_thickness(p)

    def evaluate(t: float) -> dict:
        q = p.replace(finger=p.finger.replace(bridge_thickness=t))
        r = equivalent_stiffness(q)
        say(f"bridge {t * 1e3:.3f} mm: K_eq {r['stiffness_Nm_per_rad']:.4g} N·m/rad")
        pts.append(r)
        return r

    if not pts:
        evaluate(p.finger.bridge_thickness)
    if len(pts) < 2:
        t0, k0 = pts[0]["bridge_thickness_m"], pts[0]["stiffness_Nm_per_rad"]
        evaluate(min(t_max, t0 * (target / k0) ** (1 / 2.5)))  # start from K ~ t^2.5
    for _ in range(max_iter):
        best = min(pts, key=lambda r: abs(math.log(r["stiffness_Nm_per_rad"] / target)))
        if abs(best["stiffness_Nm_per_rad"] / target - 1) <= rtol:
            return {**best, "evaluations": pts, "feasible": True}
        a, b = sorted(pts, key=lambda r: abs(math.log(r["stiffness_Nm_per_rad"] / target)))[:2]
        la, lb = math.log(a["bridge_thickness_m"]), math.log(b["bridge_thickness_m"])
        ka, kb = math.log(a["stiffness_Nm_per_rad"]), math.log(b["stiffness_Nm_per_rad"])
        t = math.exp(la + (math.log(target) - ka) * (lb - la) / (kb - ka))
        if t > t_max:
            at_max = evaluate(t_max) if all(abs(r["bridge_thickness_m"] - t_max) > 1e-9
                                            for r in pts) else None
            k_max = max(r["stiffness_Nm_per_rad"] for r in pts)
            if k_max < target:
                return {"bridge_thickness_m": None, "stiffness_Nm_per_rad": k_max,
                        "needed_extrapolated_m": t, "evaluations": pts, "feasible": False,
                        "thickest_m": t_max, "at_thickest": at_max}
            continue
        evaluate(t)
    raise RuntimeError(f"bridge_for_stiffness: no convergence to {target:g} N·m/rad")


__all__ = ["bridge_for_stiffness", "equivalent_stiffness", "max_bridge_thickness"]
