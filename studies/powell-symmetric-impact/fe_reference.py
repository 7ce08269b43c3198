"""Finite-element reference of Powell's symmetric impact [Powell2012, ch. 4 §4.1] with DOLFINx (Debian python3-dolfinx
0.5; `bash scripts/install-deps.sh --fe`): plane-strain elastodynamics of the block [0, L] x [0, H] (the SPH body:
each particle carries a dx x dx cell), bilinear quadrilaterals (Q1), lumped (row-sum) mass, explicit central
differences (velocity Verlet: the undamped leap-frog), dt = cfl h_e / c_P.

Models:
  linear  small-strain linear elasticity, sigma = lambda tr(eps) I + 2 mu eps (Powell: "a linear elastic material
          model"); the stiffness matrix is assembled once, a step is one sparse product
  svk     Saint Venant-Kirchhoff (total Lagrangian, P = F S, S = lambda tr(E) I + 2 mu E): the same constants with the
          geometric nonlinearity that the rate forms carry; the internal force is assembled every step

Initial velocity: v_y = -v0 above the mid-plane, +v0 below, 0 on it (the mesh nodes on y = H/2).
Measures, as the SPH study records them: the global kinetic energy 1/2 sum M_i |v_i|^2; at a point A (any point of
the block: the SPH particle A's initial position), the speed |v(A)| and the pressure p(A) (linear: -K div u; svk:
K (1/J - 1), the rate form's K (rho/rho0 - 1)) of the lumped L2 projection of p to the nodes, interpolated in the
cell that holds A. Snapshots: x = X + u(X) and p at given material points X (the particles' initial positions).

Usage from plot.py: fe_run(n, v0, t_end, points_a, snap_points, snap_times, model, cfl, collocated_dx).
"""
import time

import numpy as np

E, NU, RHO = 2.1, 0.3, 7.8
MU = E / (2 * (1 + NU))
LAM = E * NU / ((1 + NU) * (1 - 2 * NU))
K = LAM + 2 * MU / 3
C_P = np.sqrt((LAM + 2 * MU) / RHO)


def _dolfinx():
    try:
        from mpi4py import MPI
        import dolfinx
        import dolfinx.fem.petsc  # noqa: F401
        import ufl
    except ImportError as e:
        raise SystemExit("fe_reference: DOLFINx is not installed (bash scripts/install-deps.sh --fe): " + str(e))
    return MPI, dolfinx, ufl


class _PointEval:
    """Evaluates a CG1 function (scalar or vector) at fixed points: the cell of each point found once."""

    def __init__(self, dolfinx, msh, points):
        from dolfinx import geometry
        pts = np.zeros((len(points), 3))
        pts[:, :2] = points
        tree = geometry.BoundingBoxTree(msh, msh.topology.dim)
        cand = geometry.compute_collisions(tree, pts)
        cells = geometry.compute_colliding_cells(msh, cand, pts)
        self.cells = np.array([cells.links(i)[0] for i in range(len(pts))], dtype=np.int32)
        self.pts = pts

    def __call__(self, f):
        return np.asarray(f.eval(self.pts, self.cells)).reshape(len(self.pts), -1)


def fe_run(n, v0, t_end, points_a, snap_points=None, snap_times=(), model="linear", cfl=0.5, collocated_dx=None,
           length=1.0, height=1.0, record_dt=None):
    """One run on an n x n mesh. points_a: list of (x, y); returns dict with t, kinetic_energy, pressure (per point
    of points_a, len(t) rows), speed (likewise), snapshots {t_wanted: (t, x (m x 2), p (m))}, dofs, steps, dt,
    seconds. collocated_dx: Powell's mesh instead, nodes at the particles, [dx/2, L - dx/2]^2 with n elements."""
    MPI, dolfinx, ufl = _dolfinx()
    from dolfinx import fem, mesh
    import dolfinx.fem.petsc as fpetsc
    import scipy.sparse as sp
    t0 = time.time()
    lo = np.array([0.0, 0.0]) if collocated_dx is None else np.array([collocated_dx / 2] * 2)
    hi = np.array([length, height]) - lo
    msh = mesh.create_rectangle(MPI.COMM_SELF, [lo, hi], [n, n], mesh.CellType.quadrilateral)
    V = fem.VectorFunctionSpace(msh, ("CG", 1))
    Q = fem.FunctionSpace(msh, ("CG", 1))
    v_, q_ = ufl.TestFunction(V), ufl.TestFunction(Q)
    u = fem.Function(V)
    ones = fem.Constant(msh, np.array([1.0, 1.0]))
    mass = fpetsc.assemble_vector(fem.form(RHO * ufl.inner(ones, v_) * ufl.dx)).array.copy()  # row sums: lumped
    qmass = fpetsc.assemble_vector(fem.form(q_ * ufl.dx)).array.copy()
    eps = lambda w: ufl.sym(ufl.grad(w))  # noqa: E731
    Id = ufl.Identity(2)
    if model == "linear":
        w = ufl.TrialFunction(V)
        A = fpetsc.assemble_matrix(fem.form(ufl.inner(LAM * ufl.tr(eps(w)) * Id + 2 * MU * eps(w), eps(v_)) * ufl.dx))
        A.assemble()
        Kmat = sp.csr_matrix(A.getValuesCSR()[::-1], shape=A.getSize())
        force = lambda x: Kmat @ x  # noqa: E731
        p_form = fem.form(-K * ufl.div(u) * q_ * ufl.dx)
    elif model == "svk":
        F = Id + ufl.grad(u)
        Eg = 0.5 * (F.T * F - Id)
        P = F * (LAM * ufl.tr(Eg) * Id + 2 * MU * Eg)
        f_form = fem.form(ufl.inner(P, ufl.grad(v_)) * ufl.dx)
        fvec = fpetsc.create_vector(f_form)

        def force(x):
            u.x.array[:] = x
            with fvec.localForm() as loc:
                loc.set(0)
            fpetsc.assemble_vector(fvec, f_form)
            return fvec.array.copy()
        p_form = fem.form(K * (1 / ufl.det(F) - 1) * q_ * ufl.dx)
    else:
        raise ValueError(f"fe_run: unknown model '{model}' (linear, svk)")
    p_fun = fem.Function(Q)
    vel = fem.Function(V)
    X = V.tabulate_dof_coordinates()[:, :2]  # one row per node (blocked space: 2 dofs per row)
    v = np.zeros(2 * len(X))
    mid = 0.5 * (lo[1] + hi[1])
    tol = 1e-9 * height
    v[1::2] = np.where(X[:, 1] > mid + tol, -v0, np.where(X[:, 1] < mid - tol, v0, 0.0))
    x = np.zeros_like(v)
    h_e = (hi[0] - lo[0]) / n
    steps = int(np.ceil(t_end / (cfl * h_e / C_P)))
    dt = t_end / steps
    a = -force(x) / mass
    ev_a = _PointEval(dolfinx, msh, np.asarray(points_a))
    ev_s = _PointEval(dolfinx, msh, np.asarray(snap_points)) if snap_points is not None else None
    every = 1 if record_dt is None else max(1, int(round(record_dt / dt)))
    out = {"t": [], "kinetic_energy": [], "pressure": [], "speed": [], "snapshots": {}}
    pending = sorted(snap_times)

    def pressure_nodes():
        u.x.array[:] = x
        p_fun.x.array[:] = fpetsc.assemble_vector(p_form).array / qmass

    def record(k):
        t = k * dt
        out["t"].append(t)
        out["kinetic_energy"].append(0.5 * float(np.dot(mass, v * v)))
        pressure_nodes()
        vel.x.array[:] = v
        out["pressure"].append(ev_a(p_fun)[:, 0].copy())
        out["speed"].append(np.linalg.norm(ev_a(vel), axis=1))
        while pending and t >= pending[0] - 0.5 * dt:
            u.x.array[:] = x
            disp = ev_s(u)
            out["snapshots"][pending.pop(0)] = (t, np.asarray(snap_points) + disp, ev_s(p_fun)[:, 0].copy())

    record(0)
    for k in range(1, steps + 1):  # velocity Verlet: v^n synchronised at every record
        v += 0.5 * dt * a
        x += dt * v
        a = -force(x) / mass
        v += 0.5 * dt * a
        if k % every == 0 or k == steps:
            record(k)
    for key in ("t", "kinetic_energy"):
        out[key] = np.asarray(out[key])
    out["pressure"], out["speed"] = np.asarray(out["pressure"]), np.asarray(out["speed"])
    out.update(dofs=len(v), steps=steps, dt=dt, seconds=time.time() - t0, h_e=h_e)
    return out
