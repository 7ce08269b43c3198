"""sphstab: is this SPH formulation stable, and why? The C++ library's front doors from Python.

The compiled module ``_sphstab`` holds every computation; this file only adapts arguments and results to NumPy and
SciPy (no second copy of the library's logic). Errors are Python exceptions carrying the library's one-line message,
the same text the CLI prints after ``sphstab: error:`` (ValueError for bad input, RuntimeError otherwise,
``MemoryLimitError`` for a refused size).

Quick start (after ``bash scripts/test.sh``, with ``PYTHONPATH=build/python``)::

    import sphstab
    cases = sphstab.critical_tension(n=30, kernels=["cubic", "quintic"], h=[1.0, 1.2, 1.5])
    ops = sphstab.operators(sphstab.lattice("square", 10, support_radius=2.6), "cubic", 1.3)
    ops["G_x"]                      # scipy.sparse.csr_matrix, sharing the library's storage
"""
import os as _os

# The program's OpenMP wait policy (core/threads.hpp, set_program_wait_policy): libgomp reads it once, when it is
# loaded, so it is set here, before the compiled module (and NumPy) load it, unless the environment chose one. Without
# it a waiting thread spins ~3 ms and, beside another process, stalls its descheduled partner. It has no effect if
# libgomp was loaded earlier in this interpreter. Equal to _sphstab.program_wait_policy (tests/test_threads.py).
if "OMP_WAIT_POLICY" not in _os.environ and "GOMP_SPINCOUNT" not in _os.environ:
    _os.environ["OMP_WAIT_POLICY"] = "passive"

import numpy as _np  # noqa: E402
import scipy.sparse as _sparse  # noqa: E402

from ._sphstab import (  # noqa: F401, E402  (re-exported)
    CriticalStrainCase,
    CriticalTensionCase,
    Kernel,
    MemoryLimitError,
    NeighbourList,
    ParticleSet1D,
    ParticleSet2D,
    ParticleSet3D,
    RateFormOptions,
    RateFormTimeStep,
    RunResult,
    Scene2D,
    StabilityVerdict,
    StateStability,
    detection_floor,
    fourier_symbol_1d,
    gms_plate_scene,
    gms_rings_scene,
    gms_slab_scene,
    kernel_names,
    lattice,
    material_from_youngs,
    max_memory,
    neighbours,
    powell_impact_scene,
    read_particle_state,
    run,
    set_fixed_threads,
    set_max_memory,
    set_threads,
    threads,
    wait_policy,
)
from . import _sphstab

__all__ = [
    "CriticalStrainCase", "critical_strain", "elastic_linearisation", "max_memory", "set_max_memory",
    "set_threads", "set_fixed_threads", "threads", "wait_policy", "rate_form_jacobian",
    "rate_form_dispersion",
    "critical_tension", "CriticalTensionCase", "detection_floor", "fourier_symbol_1d", "gms_plate_scene",
    "gms_rings_scene", "gms_slab_scene", "Kernel", "kernel_names", "lattice", "material_from_youngs", "MemoryLimitError",
    "NeighbourList", "neighbours", "operators", "ParticleSet1D", "ParticleSet2D", "ParticleSet3D", "powell_impact_scene",
    "RateFormOptions", "RateFormTimeStep", "read_particle_state", "run", "RunResult", "Scene2D", "StabilityVerdict",
    "state_stability", "StateStability", "table", "write_modes_vtk",
]


def _csr(parts):
    """scipy.sparse.csr_matrix over the library's own arrays (no copy: data, indices and indptr are views of the
    C++ matrix, kept alive by the arrays)."""
    data, indices, indptr, shape = parts
    return _sparse.csr_matrix((data, indices, indptr), shape=shape, copy=False)


def operators(particles, kernel="cubic", h=1.3, hessian=False, correction="none", counting="actual",
              polish_free=False):
    """The SPH operator matrices of ``particles`` (a ParticleSet1D/2D/3D) for ``kernel`` and smoothing length ``h``,
    as ``sphstab operators`` writes them: a dict of scipy.sparse.csr_matrix named W, G_x (G_y, G_z), the corrected
    gradient G_<correction>_x ... (correction other than "none") and H_xx, H_xy, ... (hessian=True). Row-major with
    the neighbour-list pattern; W_ij = W(|x_i - x_j|, h) V_j, G^a_ij = dW/dx_i^a V_j. No copy is made."""
    return {name: _csr(parts) for name, parts in
            _sphstab._operators(particles, kernel, float(h), bool(hessian), correction, counting,
                                bool(polish_free)).items()}


def _list(value):
    return [value] if isinstance(value, (str, int, float)) else list(value)


def critical_tension(n=30, kernels=("cubic",), h=(1.3,), forms=("conservative",), periodic=False,
                     compression=False, method="both", backend="auto", correction="none", corrected="auto"):
    """The critical tension T_crit of the 1D pre-stressed bar (Powell (3.40): the smallest T > 0 at which
    A(T) = K - n T L stops being positive definite) for every kernel x h/dx x momentum form, in that order (form
    fastest): the cases `sphstab tcrit` prints, each a CriticalTensionCase with tcrit, status and reason. ``h`` is
    h/dx (dx = 1). ``table(cases)`` turns them into NumPy columns."""
    return _sphstab._critical_tension(int(n), _list(kernels), [float(x) for x in _list(h)], _list(forms),
                                      bool(periodic), bool(compression), method, backend, correction, corrected)


def critical_strain(lattice="square", n=16, kernels=("cubic",), h=(1.3,), forms=("conservative",), periodic=False,
                    lam=1.2115384615384615, mu=0.80769230769230769, prestrain="isotropic", compression=False,
                    route="auto", method="both", backend="auto", criterion="auto", dim=None):
    """The critical pre-strain e_crit of a 2D lattice (square, hex, face-centred) or a 3D cubic one under an isotropic
    or uniaxial pre-strain, for every kernel x h/dx x form, each case through the critical-load front door
    (critical_load_problem.hpp: route auto | assembled | matrix-free | symbol, its memory estimate and fallbacks), as
    `sphstab tcrit --dim 2|3` computes it; with the infinite-lattice limit in 2D. Lame lambda (``lam``) and mu default
    to E = 2.1, nu = 0.3 in plane strain. Returns CriticalStrainCase objects (``table`` makes columns)."""
    if dim is None:
        dim = 3 if lattice == "cubic" else 2
    return _sphstab._critical_strain(int(dim), lattice, int(n), bool(periodic), _list(kernels),
                                     [float(x) for x in _list(h)], _list(forms), float(lam), float(mu), prestrain,
                                     bool(compression), route, method, backend, criterion)


def elastic_linearisation(dim=1, n=30, kernel="cubic", h=1.3, form="conservative", lattice="square",
                          lam=1.2115384615384615, mu=0.80769230769230769, prestrain="isotropic"):
    """(A0, A1) of A(load) = A0 + load A1 for the lattice `sphstab jacobian elastic` exports, as
    scipy.sparse.csr_matrix (no copy): 1D, a line of n free particles with fixed layers under pre-tension T (Powell
    (3.40), load T); 2D, an n x n lattice under a pre-strain e (load e). The critical load is the smallest load at
    which A stops being positive definite."""
    a0, a1 = _sphstab._elastic_linearisation(int(dim), int(n), kernel, float(h), form, lattice, float(lam), float(mu),
                                              prestrain)
    return _csr(a0), _csr(a1)


def table(cases):
    """Columns of a list of result objects: {field: numpy array} for every public property."""
    if not cases:
        return {}
    names = [k for k in dir(cases[0]) if not k.startswith("_")]
    return {k: _np.array([getattr(c, k) for c in cases]) for k in names}


def _matrix(a, rows, cols, name, dtype=float):
    if a is None:
        return _np.zeros((0, 0))
    a = _np.asarray(a, dtype=dtype)
    if a.ndim == 1 and cols == 1:
        a = a.reshape(-1, 1)
    if a.ndim == 1 and rows == 1:
        a = a.reshape(1, -1)
    if a.ndim != 2:
        raise ValueError(f"state: {name} must be a 2-D array (got {a.ndim} dimensions)")
    return a


def _state_arrays(x, density, mass, v, deviator, fixed):
    x = _np.asarray(x, dtype=float)
    x = _matrix(x.reshape(-1, 1) if x.ndim == 1 else x, None, None, "x")
    dim = x.shape[1]
    density = _np.asarray(density, dtype=float).reshape(-1)
    mass = _np.asarray(mass, dtype=float).reshape(-1)
    v = _matrix(v, None, dim, "v") if v is not None and _np.size(v) else _np.zeros((0, 0))
    stress_cols = 1 if dim == 1 else 3
    deviator = (_matrix(deviator, None, stress_cols, "deviator") if deviator is not None and _np.size(deviator)
                else _np.zeros((0, 0)))
    fixed = [] if fixed is None else [bool(f) for f in _np.asarray(fixed).reshape(-1)]
    return x, dim, density, mass, v, deviator, fixed


def write_modes_vtk(path, result, x, density, mass, h, v=None, deviator=None, fixed=None, spacing=0.0):
    """Writes the state with the modes of its StateStability ``result`` to a VTK PolyData file for ParaView: point
    data velocity, density, mass, fixed, semi_discrete_mode and map_mode (velocity shapes, 0 on fixed particles)."""
    x, dim, density, mass, v, deviator, fixed = _state_arrays(x, density, mass, v, deviator, fixed)
    _sphstab._write_state_modes_vtp(str(path), x, density, mass, float(h), v, deviator, fixed, float(spacing), result)


def _material(youngs, poisson, rho0, bulk_modulus, shear_modulus):
    if rho0 is None:
        raise ValueError("state: rho0 (the reference density of the equation of state) is required")
    if youngs is not None or poisson is not None:
        if youngs is None or poisson is None or bulk_modulus is not None or shear_modulus is not None:
            raise ValueError("state: give youngs and poisson, or bulk_modulus and shear_modulus")
        return material_from_youngs(youngs, poisson, rho0)
    if bulk_modulus is None or shear_modulus is None:
        raise ValueError("state: give youngs and poisson, or bulk_modulus and shear_modulus")
    return float(rho0), float(bulk_modulus), float(shear_modulus)


def rate_form_jacobian(x, density, mass, h, v=None, deviator=None, fixed=None, spacing=0.0, kernel="cubic",
                       youngs=None, poisson=None, rho0=None, bulk_modulus=None, shear_modulus=None, scheme=None):
    """J = dF/dy of the rate-form scheme built at a state given as arrays (the arguments of state_stability), by
    coloured complex step as `sphstab jacobian rate-form` computes it. Returns (J as scipy.sparse.csr_matrix, y the
    state vector, offsets: N x 4 int array of each particle's x, v, rho and S offsets in y, -1 where it has none)."""
    x, dim, density, mass, v, deviator, fixed = _state_arrays(x, density, mass, v, deviator, fixed)
    rho0, bulk_modulus, shear_modulus = _material(youngs, poisson, rho0, bulk_modulus, shear_modulus)
    j, y, offsets = _sphstab._rate_form_jacobian(x, density, mass, float(h), v, deviator, fixed, float(spacing), kernel,
                                                 rho0, bulk_modulus, shear_modulus,
                                                 scheme if scheme is not None else RateFormOptions())
    return _csr(j), y, offsets


def rate_form_dispersion(k, lattice="square", n=12, kernel="cubic", h=1.3, dx=0.01, xi=1.0, youngs=None,
                         poisson=None, rho0=None, bulk_modulus=None, shear_modulus=None, scheme=None):
    """The dispersion of the whole rate-form scheme (every term of ``scheme``) on a periodic lattice (line, square,
    hex, face-centred; n per side, spacing dx, h = ``h`` x dx) at volume strain xi, from its exact Bloch symbol
    (spectral/rate_form_symbol.hpp), at the wavevectors ``k`` (K x dim, 1/length; any real k). Returns a dict:
    growth_rate (K), omega2 (K x dim, the acoustic branches), eigenvalues (K x s, all of Jhat(k))."""
    rho0, bulk_modulus, shear_modulus = _material(youngs, poisson, rho0, bulk_modulus, shear_modulus)
    k = _np.asarray(k, dtype=float)
    if k.ndim == 1:
        k = k.reshape(-1, 1) if lattice == "line" else k.reshape(1, -1)
    return _sphstab._rate_form_dispersion(lattice, int(n), kernel, float(h), float(dx), float(xi), rho0,
                                          bulk_modulus, shear_modulus,
                                          scheme if scheme is not None else RateFormOptions(), k)


def state_stability(x, density, mass, h, v=None, deviator=None, fixed=None, spacing=0.0, kernel="cubic",
                    youngs=None, poisson=None, rho0=None, bulk_modulus=None, shear_modulus=None, scheme=None,
                    integrator="pc", leapfrog_xsph=0.0, dt=None, t_end=None, energy_ratio=100.0, floor=None,
                    lattice=None):
    """Is this particle state linearly unstable, and which mode will grow?

    The rate-form scheme (continuity, equation of state, Jaumann rate, and the terms of ``scheme``, a RateFormOptions)
    is built AT the state given as arrays, N particles: ``x`` (N x dim, dim 1 or 2), ``density`` (N), ``mass`` (N),
    smoothing length ``h``, optional velocities ``v`` (N x dim), deviatoric stress ``deviator`` (N x 1 in 1D, N x 3 in
    2D: S_xx, S_yy, S_xy), ``fixed`` flags (N) and the initial spacing ``spacing`` (artificial stress, 2D
    wavevectors). Material: ``youngs``, ``poisson`` and ``rho0``, or ``rho0``, ``bulk_modulus`` and
    ``shear_modulus``. The verdict is for a run with ``integrator`` ("pc", "pc1", "leapfrog") at step ``dt``; its
    detection floor is ``floor`` or detection_floor(t_end, energy_ratio).

    Returns a StateStability: ``verdict`` (letter S/U/I/B, semi_discrete_growth, map_growth, floor, ...),
    ``semi_discrete_mode`` and ``map_mode`` (shape over the free particles, the particle where it peaks, its
    wavevector), ``time_step`` (leap-frog and predictor-corrector limits, at rest) and ``acceleration_max`` (how far
    the state is from an equilibrium).
    """
    x, dim, density, mass, v, deviator, fixed = _state_arrays(x, density, mass, v, deviator, fixed)
    rho0, bulk_modulus, shear_modulus = _material(youngs, poisson, rho0, bulk_modulus, shear_modulus)
    if dt is None:
        raise ValueError("state: dt (the step of the run the verdict is for) is required")
    if floor is None:
        if t_end is None:
            raise ValueError("state: give the detection floor, or t_end (and energy_ratio) to compute it")
        floor = detection_floor(t_end, energy_ratio)
    return _sphstab._state_stability(dim, x, density, mass, float(h), v, deviator, fixed, float(spacing), kernel,
                                     float(rho0), float(bulk_modulus), float(shear_modulus),
                                     scheme if scheme is not None else RateFormOptions(), integrator,
                                     float(leapfrog_xsph), float(dt), float(floor), lattice or "")
