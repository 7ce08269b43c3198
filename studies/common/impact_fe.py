"""Finite-element reference of Powell's impact problems [Powell2012, ch. 4 §4] with DOLFINx (Debian python3-dolfinx
0.5; `bash scripts/install-deps.sh --fe`): plane-strain elastodynamics of the rectangle [x0, x1] x [y0, y1] (the SPH
body: each particle carries a dx x dx cell), bilinear quadrilaterals (Q1), lumped (row-sum) mass, explicit central
differences (velocity Verlet: the undamped leap-frog), dt = cfl h_e / c_P with h_e the smaller element side.

Models:
  linear  small-strain linear elasticity, sigma = lambda tr(eps) I + 2 mu eps (Powell: "a linear elastic material
          model"); the stiffness matrix is assembled once, a step is one sparse product
  svk     Saint Venant-Kirchhoff (total Lagrangian, P = F S, S = lambda tr(E) I + 2 mu E): the same constants with the
          geometric nonlinearity that the rate forms carry; the internal force is assembled every step

Initial velocity: velocity(X) of the problem at every node; a node on a discontinuity of it (the symmetric impact's
mid-plane, the bar's impact plane, the edges of the beam's loaded section) takes the mean of the values around it.
Clamps: nodes with x <= x0 + clamp or x >= x1 - clamp keep zero displacement (the beam's fixed layers).
Measures, as the SPH studies record them: the global kinetic energy 1/2 sum M_i |v_i|^2; at points (any points of the
body: the SPH particles' initial positions), the speed |v|, the pressure p (linear: -K div u; svk: K (1/J - 1), the
rate form's K (rho/rho0 - 1)) of the lumped L2 projection of p to the nodes, and the displacement u, each interpolated
in the cell that holds the point; the body's length (max - min x of the deformed nodes); the smallest cell-mean
det F (j_min: <= 0 when an element has inverted). Snapshots: x = X + u(X) and p at given material points X.
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
        raise SystemExit("impact_fe: DOLFINx is not installed (bash scripts/install-deps.sh --fe): " + str(e))
    return MPI, dolfinx, ufl


class _PointEval:
    """Evaluates a CG1 function (scalar or vector) at fixed points: the cell of each point found once."""

    def __init__(self, msh, points):
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


def nodal_velocity(velocity, X, eps):
    """velocity(X) (n x 2 -> n x 2) at the nodes; where the four values at X + (+-eps, +-eps) differ (a node on a
    discontinuity), their mean."""
    vals = [velocity(X + np.array([sx, sy]) * eps) for sx in (-1, 1) for sy in (-1, 1)]
    out = vals[0].copy()
    differ = np.any([np.any(vals[0] != w, axis=1) for w in vals[1:]], axis=0)
    out[differ] = 0.25 * (vals[0][differ] + vals[1][differ] + vals[2][differ] + vals[3][differ])
    return out


def fe_run(nx, ny, t_end, velocity, points, lo, hi, snap_points=None, snap_times=(), model="linear", cfl=0.5,
           clamp=None, record_dt=None):
    """One run on an nx x ny mesh of the rectangle lo .. hi. velocity: X (n x 2) -> initial velocity (n x 2);
    points: list of (x, y). Returns a dict with t, kinetic_energy, length, pressure and speed (len(t) x
    len(points)), displacement (len(t) x len(points) x 2), snapshots {t_wanted: (t, x (m x 2), p (m))}, dofs, steps, dt, seconds,
    h_e."""
    MPI, dolfinx, ufl = _dolfinx()
    from dolfinx import fem, mesh
    import dolfinx.fem.petsc as fpetsc
    import scipy.sparse as sp
    t0 = time.time()
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    msh = mesh.create_rectangle(MPI.COMM_SELF, [lo, hi], [nx, ny], mesh.CellType.quadrilateral)
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
    # The smallest cell-mean Jacobian det(I + grad u): <= 0 where an element has inverted (the model has left its
    # range: linear elasticity has no such limit, but its strains are then not small).
    D = fem.FunctionSpace(msh, ("DG", 0))
    d_ = ufl.TestFunction(D)
    j_form = fem.form(ufl.det(Id + ufl.grad(u)) * d_ * ufl.dx)
    area = fpetsc.assemble_vector(fem.form(d_ * ufl.dx)).array.copy()
    X = V.tabulate_dof_coordinates()[:, :2]  # one row per node (blocked space: 2 dofs per row)
    h_e = min((hi[0] - lo[0]) / nx, (hi[1] - lo[1]) / ny)
    v = nodal_velocity(velocity, X, 1e-6 * h_e).reshape(-1)
    free = np.ones(len(v), dtype=bool)
    if clamp is not None:
        tol = 1e-9 * h_e
        fixed = (X[:, 0] <= lo[0] + clamp + tol) | (X[:, 0] >= hi[0] - clamp - tol)
        free = np.repeat(~fixed, 2)
        v[~free] = 0
    x = np.zeros_like(v)
    steps = int(np.ceil(t_end / (cfl * h_e / C_P)))
    dt = t_end / steps

    def accel(x):
        a = -force(x) / mass
        a[~free] = 0
        return a

    a = accel(x)
    ev_a = _PointEval(msh, np.asarray(points))
    ev_s = _PointEval(msh, np.asarray(snap_points)) if snap_points is not None else None
    every = 1 if record_dt is None else max(1, int(round(record_dt / dt)))
    out = {"t": [], "kinetic_energy": [], "pressure": [], "speed": [], "displacement": [], "length": [],
           "j_min": [], "snapshots": {}}
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
        out["displacement"].append(ev_a(u).copy())  # u holds x (pressure_nodes)
        xs = X[:, 0] + x[0::2]
        out["length"].append(float(xs.max() - xs.min()))
        out["j_min"].append(float(np.min(fpetsc.assemble_vector(j_form).array / area)))
        while pending and t >= pending[0] - 0.5 * dt:
            disp = ev_s(u)
            out["snapshots"][pending.pop(0)] = (t, np.asarray(snap_points) + disp, ev_s(p_fun)[:, 0].copy())

    record(0)
    for k in range(1, steps + 1):  # velocity Verlet: v^n synchronised at every record
        v += 0.5 * dt * a
        x += dt * v
        a = accel(x)
        v += 0.5 * dt * a
        if k % every == 0 or k == steps:
            record(k)
    for key in ("t", "kinetic_energy", "pressure", "speed", "displacement", "length", "j_min"):
        out[key] = np.asarray(out[key])
    out.update(dofs=len(v), steps=steps, dt=dt, seconds=time.time() - t0, h_e=h_e)
    return out
