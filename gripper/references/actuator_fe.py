"""Paper 001's actuator inflated: a three-dimensional, large-deformation finite-element model in
FElupe, and its bending angle against pressure.

The model (mesh and materials: :mod:`gripper.references.actuator_mesh`,
:mod:`gripper.references.fibre_materials`):

- every cell but the neutral layer's is RTV 230 silicone, FElupe's Yeoh energy in the mixed
  u/p/J (Hu-Washizu) form with cell-constant pressure and volume ratio, nearly incompressible
  (bulk modulus ``BULK_RATIO`` times the shear modulus); the fibre layer's cells add the two
  tension-only fibre families; the neutral layer's cells are the fabric, a compressible solid
  with every strain component (:func:`fabric_material`), so it bends as a plate; silicone's
  near-incompressibility there would have stiffened the fabric's ν = 0.2 (the silicone's bulk
  modulus, 3·10⁴ μ, is of the fabric's modulus' order);
- half the actuator, with the mid-plane x = 0 a plane of symmetry (u_x = 0 there);
- the end z = 0 clamped (paper 001 §2.3 Step 3), the other free;
- gravity along the actuator, +z: it hangs from its clamp, as a gripper's finger does (assumed:
  the paper says gravity acts, not in which direction; hanging, the actuator bends only 1° at
  0 kPa, through the fabric's eccentric stiffness, so the curves start near 0° as the paper's
  Figs. 12-16 do);
- a follower pressure on every face of the duct (wall, flat side and both caps), ramped from 0,
  solved by Newton's method at each load step.

The bending angle (paper 001 Fig. 11; its drawing is lost, so defined here as a bending
actuator's is, e.g. Polygerinos et al. 2015): the angle through which the free end has turned
about the x axis, measured by the material line across the tip's face on the mid-plane
(bottom to top point), unwrapped past 180° over the load steps.

Example (the studies' mesh; about 8 s):
    >>> from gripper.references.actuator_fe import inflate
    >>> from gripper.references.actuator_mesh import MeshSize
    >>> from gripper.references.pneumatic_params import PneumaticActuator
    >>> r = inflate(PneumaticActuator(), [25e3], MeshSize.at_refinement(1))  # doctest: +SKIP
    >>> r.angles_deg.round(1)                                                # doctest: +SKIP
    array([ 1. , 16.9])
"""

from __future__ import annotations

import math
import os
import time
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from gripper.references.actuator_mesh import (
    FIBRE,
    NEUTRAL,
    ActuatorMesh,
    Geometry,
    MeshSize,
    actuator_mesh,
    winding_tangent,
)
from gripper.references.fibre_materials import fibre_elasticity, fibre_stress
from gripper.references.pneumatic_params import PneumaticActuator

GRAVITY = 9.81  # m/s², standard gravity
# the formulation's name, in the pneumatic calibration's design hash: a change of mesh family or
# material model makes the committed calibration stale (2: the isoparametric mesh with cells at
# most 10 mm long, the fabric a solid, the fibres tension-only)
REFERENCE_MODEL = "actuator_fe/2"
# -, the silicone's bulk modulus over its shear modulus: RTV silicones are nearly incompressible
# (ν ≈ 0.4995 at this ratio); the Yeoh tube's radius change at this ratio is 0.03 % from the
# incompressible closed form (gripper.references.yeoh_tube measured 0.17 % at 5000, 1/ratio scaling)
BULK_RATIO = 3e4
# -, Newton's tolerance on the residual forces relative to the reaction forces (FElupe's norm)
NEWTON_TOL = 1e-6
QUAD_ORDER = 2  # 3 x 3 x 3 Gauss points: the twenty-node cell's full integration (2 x 2 x 2 went singular)
PRESSURE_STEP = 25e3  # Pa, the largest load step
MAX_ITERATIONS = 30  # Newton iterations per step before a cutback (a converging 25 kPa step takes 12-30)
MAX_CUTBACKS = 6  # halvings of a failed step (down to 25 kPa / 64 = 0.4 kPa)


@dataclass(frozen=True)
class Inflation:
    """One pressure sweep: the pressures [Pa] and bending angles [deg] of the converged steps
    (a sweep that failed to converge stops early: ``failed_at`` is the pressure it failed at),
    and the deformed points [m] of each step when asked for."""

    pressures: np.ndarray
    angles_deg: np.ndarray
    mesh: ActuatorMesh
    failed_at: float | None = None
    wall_time_s: float = 0.0
    shapes: list[np.ndarray] = field(default_factory=list, repr=False)
    newton_iterations: int = 0

    def angle_at(self, pressure: float) -> float:
        """The bending angle [deg] at one of the sweep's pressures."""
        i = np.flatnonzero(np.isclose(self.pressures, pressure, rtol=0.0, atol=1.0))
        if not len(i):
            raise ValueError(f"pressure {pressure:g} Pa was not reached (converged up to "
                             f"{self.pressures.max(initial=0.0):g} Pa)")
        return float(self.angles_deg[i[0]])


def fibre_volume_fraction(actuator: PneumaticActuator) -> float:
    """φ of one fibre family in its layer: a thread of diameter d every pitch p, the layer d thick
    (π d² / 4 over d · p cos α, p cos α the spacing across the thread)."""
    d, alpha = actuator.fibre_diameter, math.radians(actuator.twist_angle_deg)
    return math.pi * d / (4.0 * actuator.fibre_pitch * math.cos(alpha))


def bending_angle(points: np.ndarray, line: tuple[int, int]) -> float:
    """The tip line's angle [rad] about x from its reference direction +y (positive: the tip
    turns towards -y, the neutral layer's side), in (-π, π]."""
    v = points[line[1]] - points[line[0]]
    return math.atan2(v[2], v[1])


def fabric_material(actuator: PneumaticActuator):
    """The fabric neutral layer as a solid: FElupe's large-strain linear-elastic material (a
    compressible neo-Hookean solid with the fabric's E and ν at small strain), with every strain
    component, so the layer has its transverse-shear and plate-bending stiffness
    E t³ / 12 (1 - ν²) (checked against a clamped strip's closed form in the tests)."""
    import felupe as fem

    return fem.LinearElasticLargeStrain(E=actuator.fabric_modulus, nu=actuator.fabric_poisson)


def build_model(m: ActuatorMesh, bulk_ratio: float = BULK_RATIO):
    """FElupe's items for the mesh: (field, solid bodies, pressure, gravity forces, boundaries)."""
    import felupe as fem

    a = m.actuator
    mesh = fem.Mesh(*m.quadratic(), "hexahedron20")
    quadrature = fem.GaussLegendre(order=QUAD_ORDER, dim=3)
    def make_region(msh):
        return fem.RegionQuadraticHexahedron(msh, quadrature=quadrature)
    region = make_region(mesh)
    field_ = fem.FieldContainer([fem.Field(region, dim=3)])

    def sub_field(mask):
        sub = fem.Mesh(mesh.points, mesh.cells[mask], "hexahedron20")
        return fem.FieldContainer([fem.Field(make_region(sub), dim=3)])

    neutral = m.material == NEUTRAL
    s_field = sub_field(~neutral) if neutral.any() else field_
    mu = a.yeoh_shear_modulus
    silicone = fem.SolidBodyNearlyIncompressible(
        fem.Hyperelastic(fem.yeoh, C10=a.yeoh_c10, C20=a.yeoh_c20, C30=a.yeoh_c30), s_field, bulk=bulk_ratio * mu)
    items: list = [silicone]
    fibre = m.material == FIBRE
    phi = fibre_volume_fraction(a)
    forces = []
    if fibre.any():
        alpha = math.radians(a.twist_angle_deg)
        f_field = sub_field(fibre)
        # the winding's direction at every quadrature point: it turns by up to 45° within a cell
        # round the top, where one direction per cell was 22° off at the cell's ends
        f_region = f_field[0].region
        shape_functions = f_region.h.reshape(*f_region.h.shape[:2], -1)[:, :, 0]  # (nodes, q): the same in every cell
        xq = np.einsum("cai,aq->iqc", f_region.mesh.points[f_region.mesh.cells], shape_functions)  # (3, q, cells)
        tangent = winding_tangent(Geometry(a), xq[0].ravel(), xq[1].ravel())
        h = np.zeros_like(xq)
        h[0], h[1] = tangent[:, 0].reshape(xq.shape[1:]), tangent[:, 1].reshape(xq.shape[1:])
        ez = np.array([0.0, 0.0, 1.0])[:, None, None]
        directions = [math.cos(alpha) * h + sign * math.sin(alpha) * ez for sign in (1.0, -1.0)]
        stiffness = np.full((1, int(fibre.sum())), phi * a.fibre_modulus)
        items.append(fem.SolidBody(fem.Material(fibre_stress, fibre_elasticity, directions=directions,
                                                stiffness=stiffness), f_field))
        forces.append(fem.SolidBodyForce(f_field, scale=2 * phi * (a.fibre_density - a.silicone_density)))
    if neutral.any():
        n_field = sub_field(neutral)
        items.append(fem.SolidBody(fabric_material(a), n_field))
        forces.append(fem.SolidBodyForce(n_field, scale=a.fabric_density))
    forces.append(fem.SolidBodyForce(s_field, scale=a.silicone_density))
    surface = fem.RegionQuadraticHexahedronBoundary(mesh, only_surface=True, mask=m.duct_surface_points(mesh.points))
    pressure = fem.SolidBodyPressure(fem.FieldContainer([fem.Field(surface, dim=3)]))
    x, _, z = mesh.points.T
    boundaries = {
        "clamp": fem.Boundary(field_[0], mask=np.isclose(z, 0.0)),
        "symmetry": fem.Boundary(field_[0], mask=np.isclose(x, 0.0), skip=(0, 1, 1)),
    }
    return field_, items, pressure, forces, boundaries


class PardisoSameSparsity:
    """MKL PARDISO (through pypardiso) that keeps its symbolic analysis (the fill-reducing
    ordering) while the matrix's sparsity pattern stays the same, as it does over a sweep's
    Newton iterations: each solve is then a numeric factorization and a solve (phases 23)
    instead of pypardiso.spsolve's analysis, factorization and solve (phases 13)."""

    def __init__(self) -> None:
        import pypardiso

        self._solver = pypardiso.PyPardisoSolver()
        self._pattern: tuple[np.ndarray, np.ndarray] | None = None

    def __call__(self, A, b: np.ndarray) -> np.ndarray:
        A = A.tocsr()
        A.sort_indices()
        b = np.asfortranarray(b, dtype=float)
        s = self._solver
        s._check_A(A)  # noqa: SLF001 - pypardiso's own checks (pinned <0.5)
        if (self._pattern is None or not np.array_equal(self._pattern[0], A.indptr)
                or not np.array_equal(self._pattern[1], A.indices)):
            s.set_phase(11)
            s._call_pardiso(A, b)  # noqa: SLF001
            self._pattern = (A.indptr.copy(), A.indices.copy())
        s.set_phase(23)
        return s._call_pardiso(A, b)  # noqa: SLF001

    def release(self) -> None:
        """Free MKL's memory for this solver (each sweep has its own; a study runs many)."""
        if self._pattern is not None:
            self._solver.free_memory(everything=True)
            self._pattern = None


def linear_solver():
    """The sparse direct solver: Intel MKL PARDISO through pypardiso when installed (FElupe's
    recommended solver; 20-40 times faster than SuperLU on these quadratic hexahedra, measured
    0.49 s against 0.012-0.24 s on 8821 unknowns), keeping its ordering between solves of one
    pattern (:class:`PardisoSameSparsity`), else SciPy's SuperLU. One MKL thread, so a result
    does not depend on how many threads or worker processes run."""
    os.environ.setdefault("MKL_NUM_THREADS", "1")
    try:
        import pypardiso  # noqa: F401
    except ImportError:  # e.g. no MKL build for this platform
        from scipy.sparse.linalg import spsolve

        return spsolve
    return PardisoSameSparsity()


def inflate(actuator: PneumaticActuator, pressures: Sequence[float] | np.ndarray, size: MeshSize | None = None, *,
            keep_shapes: bool = False, largest_step: float = PRESSURE_STEP,
            bulk_ratio: float = BULK_RATIO, gravity: Sequence[float] = (0.0, 0.0, GRAVITY)) -> Inflation:
    """Inflate the actuator through ``pressures`` [Pa] (increasing) and return the bending angle
    at each, after gravity at 0 Pa (``gravity`` [m/s²] in the mesh's frame: by default along the
    actuator, +z, hanging from its clamp; the pneumatic finger's calibration also lays it
    sideways, :mod:`gripper.references.actuator_bending`).

    Load steps of at most ``largest_step``, each solved by Newton's method from the last
    converged state. A step that does not converge is restored and halved (a cutback), down to
    ``largest_step / 2**MAX_CUTBACKS``; past that the sweep ends, and the result holds the
    pressures reached and ``failed_at`` (a limit point: the duct balloons, or the model went
    unstable). Nothing unconverged is ever returned as a result."""
    import felupe as fem

    t0 = time.perf_counter()
    m = actuator_mesh(actuator, size or MeshSize())
    field_, items, pressure, forces, boundaries = build_model(m, bulk_ratio)
    everything = [*items, pressure, *forces]
    dof0, dof1 = fem.dof.partition(field_, boundaries)
    ext0 = fem.dof.apply(field_, boundaries, dof0)
    solver = linear_solver()
    points = field_[0].region.mesh.points
    line = m.tip_line()
    for f in forces:
        f.update(np.asarray(gravity, dtype=float))
    targets = np.unique(np.r_[0.0, np.asarray(pressures, dtype=float)])
    reached: list[float] = []
    angles: list[float] = []
    shapes: list[np.ndarray] = []
    failed = None
    now, increment = 0.0, largest_step

    iterations = [0]

    def solve(p: float) -> bool:
        pressure.update(p)
        saved = field_[0].values.copy(), [(it, it.checkpoint()) for it in items]
        try:
            with np.errstate(all="raise"):
                res = fem.newtonraphson(x0=field_, items=everything, dof0=dof0, dof1=dof1, ext0=ext0,
                                        solver=solver, tol=NEWTON_TOL, maxiter=MAX_ITERATIONS, verbose=0,
                                        plugins=[fem.LinesearchPlugin(residual=False)])
        except (fem.NewtonConvergenceError, ArithmeticError, np.linalg.LinAlgError):
            field_[0].values[:] = saved[0]
            for it, checkpoint in saved[1]:
                it.restore(checkpoint)
            return False
        field_.link(res.x)
        iterations[0] += res.iterations
        return True

    for target in targets:
        while failed is None and (now < target or not reached):
            trial = min(target, now + increment)
            if solve(trial):
                now, increment = trial, min(largest_step, 2.0 * increment)
                if trial < target:
                    continue
            elif increment > largest_step / 2 ** MAX_CUTBACKS:
                increment /= 2.0
                continue
            else:
                failed = trial
                break
            deformed = points + field_[0].values
            reached.append(target)
            angles.append(bending_angle(deformed, line))
            if keep_shapes:
                shapes.append(deformed.copy())
            # the angle is unwrapped between recorded pressures: steps of a sweep stay well under 180°
        if failed is not None:
            break
    release = getattr(solver, "release", None)
    if release is not None:
        release()
    unwrapped = np.degrees(np.unwrap(np.asarray(angles))) if angles else np.zeros(0)
    return Inflation(pressures=np.asarray(reached), angles_deg=unwrapped, mesh=m, failed_at=failed,
                     wall_time_s=time.perf_counter() - t0, shapes=shapes, newton_iterations=iterations[0])
