"""A latex balloon: a flexcomp ellipsoid on a trilinear cage (the air in it resists volume
change far more than shape change), damaged when its membrane's edge strain passes the limit."""

from __future__ import annotations

from gripper.objects.kinds.base import OBJECT_BODY, object_friction
from gripper.objects.kinds.flex import FilmKind, flex_contact

# Balloon mesh: flexcomp ellipsoid with mesh_points surface points per axis (5: 99 vertices) on a
# trilinear 2 × 2 × 2 cell grid (81 dofs): enough for local dents under each finger; 5 points is
# where its convergence check put it (docs/performance.md, "Mesh resolution").
BALLOON_CELLS = 2
# Rayleigh damping time of the balloon's elasticity [s]: latex and air damp the wobble within
# a few periods; 2 ms damps the 2 × 2 × 2 mode set without slowing the squeeze.
BALLOON_DAMPING = 0.002


class Balloon(FilmKind):
    name = "balloon"
    material_fields = ("youngs_modulus",)
    default_mesh_points = (5, 5, 5)
    yaw_symmetric = True
    history_dependent = True  # an interpolated flex (gripper.sim.canonical)

    def build(self, spec, obj, place, pos, quat, *, rigid_contact):
        r = obj.size[0]
        pts = obj.mesh_points
        flex = spec.worldbody.make_flex(
            OBJECT_BODY, type="ellipsoid", dim=3, dof="trilinear", count=list(pts),
            cellcount=[BALLOON_CELLS] * 3, spacing=[2.0 * r / (n - 1) for n in pts], radius=0.0008,
            mass=obj.mass * place.mass_scale, inertiabox=0.002, pos=pos)
        flex.young = obj.youngs_modulus
        # air in a closed balloon resists volume change far more than shape change
        flex.poisson = 0.45
        flex.damping = BALLOON_DAMPING
        flex.rgba = [0.85, 0.15, 0.2, 1.0]
        flex_contact(flex, object_friction(obj, place))
