#!/usr/bin/python3
"""
Independent reference for Cook's membrane, nearly incompressible, with legacy
FEniCS (dolfin 2019.2, Debian 12 package ``python3-dolfin``).

What it computes
----------------
Plane-strain Cook's membrane: the quadrilateral with corners (0,0), (48,44),
(48,60), (0,44), obtained by mapping a structured N x N triangulation of the
unit square (``UnitSquareMesh(N, N, diagonal)``) with the bilinear map

    x(xi,eta) = (1-xi)(1-eta) P00 + xi(1-eta) P10 + (1-xi) eta P01 + xi eta P11,
    P00=(0,0), P10=(48,44), P01=(0,44), P11=(48,60).

  * x = 0 clamped (u = 0);
  * x = 48 loaded by a dead (reference-configuration) traction t = (0, 6.25)
    per unit length (edge length 16, total force 100), applied in equal load
    steps (default 10); each step solved by Newton's method (exact Jacobian from
    UFL, MUMPS LU; own loop, see newton(): dolfin's NonlinearVariationalSolver
    diverges / stagnates on the round-off floor for the plain P2 case);
  * compressible neo-Hookean with log J, plane strain (F is 2x2, out-of-plane
    stretch 1):
        Psi = mu/2 (tr(F^T F) - 2) - mu ln J + lambda/2 (ln J)^2,
        mu = 80.194, lambda = 400889.8  (nu = 0.4999).

Two discretisations are compared:
  * "TH":  Taylor-Hood P2 displacement / P1 continuous pressure, perturbed
           Lagrangian form: Psi_iso + p ln J - p^2/(2 lambda).  Stationarity in
           p gives p = lambda ln J, so it is equivalent to the energy above in
           the continuum, but does not lock.
  * "P2":  plain P2 displacement with the same energy (locks for nu -> 1/2).

Quantity of interest: u_y at the top-right corner (48, 60) (a mesh vertex).
A Richardson extrapolation from the last three Taylor-Hood values (mesh ratio 2)
gives an estimate of the continuum limit and the observed convergence order.

How to run (from the repository root; single process, no MPI):

    /usr/bin/python3 doc/peers/cook_membrane_fenics.py            # N = 8 16 32 64
    /usr/bin/python3 doc/peers/cook_membrane_fenics.py --N 8 16 32
    /usr/bin/python3 doc/peers/cook_membrane_fenics.py --diagonal right --skip-p2

It prints a table (N, number of unknowns, tip u_y for TH and P2) and the
extrapolated limit.  The first run spends some time JIT-compiling the forms;
the default run takes about 4 minutes on one core (N=64 P2 is the slowest part).

Defaults and notes
  * diagonal "crossed" (4 triangles per square, 4 N^2 cells); "right" is 2 N^2.
  * quadrature degree 6 (ln J is not polynomial).  TH tip values at N=16 agree
    to 10 digits between degrees 6 and 8, and to ~2e-7 between 4 and 6.
  * 10 vs 3 load steps give the same tip value to 10 digits (hyperelastic, path
    independent), so load stepping only matters for Newton robustness.
  * Newton stops at ||R|| <= 1e-11 ||R_0|| or ||du|| <= 1e-12 ||w||.
  * Convergence of the tip value is only ~O(h) (order 1.07 for N=16,32,64 and
    1.01 for N=32,64,128): the clamped corners, especially (0,44), carry a
    stress singularity, so Richardson with the observed order is an estimate;
    see doc/peers/cook_membrane_fenics.txt for the numbers.
"""

import argparse
import math
import time

import dolfin as df

df.set_log_level(df.LogLevel.WARNING)

MU = 80.194
LMBDA = 400889.8
TRACTION = (0.0, 6.25)
P00, P10, P01, P11 = (0.0, 0.0), (48.0, 44.0), (0.0, 44.0), (48.0, 60.0)
TIP = (48.0, 60.0)


def cook_mesh(n, diagonal):
    """Structured N x N mesh of the unit square mapped bilinearly onto Cook's membrane."""
    mesh = df.UnitSquareMesh(n, n, diagonal)
    xy = mesh.coordinates()
    xi, eta = xy[:, 0].copy(), xy[:, 1].copy()
    w00, w10 = (1 - xi) * (1 - eta), xi * (1 - eta)
    w01, w11 = (1 - xi) * eta, xi * eta
    for d in range(2):
        xy[:, d] = w00 * P00[d] + w10 * P10[d] + w01 * P01[d] + w11 * P11[d]
    return mesh


def boundary_markers(mesh):
    """1 = left (x=0), 2 = right (x=48)."""
    facets = df.MeshFunction("size_t", mesh, mesh.topology().dim() - 1, 0)
    df.CompiledSubDomain("on_boundary && near(x[0], 0.0, 1e-8)").mark(facets, 1)
    df.CompiledSubDomain("on_boundary && near(x[0], 48.0, 1e-8)").mark(facets, 2)
    return facets


def kinematics(u):
    F = df.Identity(2) + df.grad(u)
    C = F.T * F
    J = df.det(F)
    return F, C, J


def newton(w, Pi, R, K, bc, descent, rtol=1e-11, stol=1e-12, maxit=50, monitor=False):
    """Newton's method with an energy backtracking line search.

    The Newton step solves K du = -R (MUMPS LU, homogeneous Dirichlet bc on du).
    A step length alpha = 1, 1/2, 1/4, ... is accepted as soon as the energy Pi is
    finite (J > 0 at all quadrature points) and, if `descent` (pure displacement
    formulation, where Pi is minimised), does not increase (up to a round-off
    allowance).  For the mixed form Pi is a saddle function, so only finiteness
    is required.  Near convergence alpha = 1 is always accepted.
    Converged when ||R|| <= rtol ||R_0|| or, after a full step,
    ||du|| <= stol ||w|| (the residual of the plain displacement formulation
    stagnates at a round-off floor ~ lambda * eps, which is above rtol ||R_0||).
    """
    bc0 = df.DirichletBC(bc)
    bc0.homogenize()
    bc.apply(w.vector())
    du = df.Function(w.function_space())
    w_old = w.vector().copy()
    r0 = None
    for it in range(1, maxit + 1):
        A, b = df.assemble_system(K, -R, bc0)
        rnorm = b.norm("l2")
        if r0 is None:
            r0 = rnorm
        if rnorm <= rtol * r0:
            return it - 1
        solver = df.LUSolver(A, "mumps")
        solver.solve(du.vector(), b)
        e_old = df.assemble(Pi)
        w_old[:] = w.vector()
        alpha = 1.0
        while True:
            w.vector()[:] = w_old
            w.vector().axpy(alpha, du.vector())
            try:
                e_new = df.assemble(Pi)
            except RuntimeError:
                e_new = float("nan")
            if math.isfinite(e_new) and (not descent or
                                        e_new <= e_old + 1e-10 * abs(e_old) + 1e-12):
                break
            alpha *= 0.5
            if alpha < 1e-6:
                raise RuntimeError("line search failed")
        dnorm = alpha * du.vector().norm("l2")
        wnorm = w.vector().norm("l2")
        if monitor:
            print(f"    it {it:2d}: |R| = {rnorm:.3e}  alpha = {alpha:.4g}  "
                  f"|du|/|w| = {dnorm / max(wnorm, 1e-300):.3e}", flush=True)
        if alpha == 1.0 and dnorm <= stol * wnorm:
            return it
    raise RuntimeError("Newton did not converge in %d iterations" % maxit)


def solve_cook(n, formulation, diagonal="crossed", nsteps=10, qdeg=6, monitor=False):
    mesh = cook_mesh(n, diagonal)
    facets = boundary_markers(mesh)
    ds = df.Measure("ds", domain=mesh, subdomain_data=facets)
    dx = df.Measure("dx", domain=mesh, metadata={"quadrature_degree": qdeg})

    P2 = df.VectorElement("Lagrange", mesh.ufl_cell(), 2)
    if formulation == "TH":
        P1 = df.FiniteElement("Lagrange", mesh.ufl_cell(), 1)
        W = df.FunctionSpace(mesh, df.MixedElement([P2, P1]))
        w = df.Function(W)
        u, p = df.split(w)
        bc = df.DirichletBC(W.sub(0), df.Constant((0.0, 0.0)), facets, 1)
    elif formulation == "P2":
        W = df.FunctionSpace(mesh, P2)
        w = df.Function(W)
        u = w
        bc = df.DirichletBC(W, df.Constant((0.0, 0.0)), facets, 1)
    else:
        raise ValueError(formulation)

    load = df.Constant(0.0)
    t = df.Constant(TRACTION)
    mu, lmbda = df.Constant(MU), df.Constant(LMBDA)

    F, C, J = kinematics(u)
    lnJ = df.ln(J)
    psi = mu / 2 * (df.tr(C) - 2) - mu * lnJ
    if formulation == "TH":
        psi += p * lnJ - p ** 2 / (2 * lmbda)
    else:
        psi += lmbda / 2 * lnJ ** 2
    Pi = psi * dx - load * df.dot(t, u) * ds(2)

    R = df.derivative(Pi, w, df.TestFunction(W))
    K = df.derivative(R, w, df.TrialFunction(W))

    # Load stepping: nsteps equal increments; if Newton fails on an increment
    # (this happens only for the plain P2 formulation on fine meshes), restart
    # from the last converged state with the increment halved.  The energy is
    # path independent, so this does not change the converged solution.
    iters, cuts = 0, 0
    lam, dlam = 0.0, 1.0 / nsteps
    w_conv = w.vector().copy()
    while lam < 1.0 - 1e-14:
        target = min(1.0, lam + dlam)
        load.assign(target)
        try:
            iters += newton(w, Pi, R, K, bc, formulation == "P2", monitor=monitor)
        except RuntimeError:
            w.vector()[:] = w_conv
            dlam *= 0.5
            cuts += 1
            if dlam < 1e-4 / nsteps:
                raise
            continue
        lam = target
        w_conv[:] = w.vector()
    if formulation == "TH":
        uh = w.split(deepcopy=True)[0]
    else:
        uh = w
    uy = uh(df.Point(*TIP))[1]
    return W.dim(), uy, iters, cuts


def richardson(a, b, c, ratio=2.0):
    """Limit and observed order from three values on meshes refined by `ratio`."""
    d1, d2 = b - a, c - b
    if d1 == 0 or d2 == 0 or d1 / d2 <= 0:
        return float("nan"), float("nan")
    order = math.log(d1 / d2) / math.log(ratio)
    limit = c + d2 / (ratio ** order - 1)
    return limit, order


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    ap.add_argument("--N", type=int, nargs="+", default=[8, 16, 32, 64])
    ap.add_argument("--diagonal", default="crossed",
                    choices=["crossed", "right", "left", "right/left", "left/right"])
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument("--qdeg", type=int, default=6, help="quadrature degree")
    ap.add_argument("--skip-p2", action="store_true")
    args = ap.parse_args()

    rows = []
    for n in args.N:
        t0 = time.time()
        ndof_th, uy_th, it_th, cut_th = solve_cook(n, "TH", args.diagonal, args.steps, args.qdeg)
        t1 = time.time()
        if args.skip_p2:
            ndof_p2, uy_p2, it_p2, cut_p2 = 0, float("nan"), 0, 0
        else:
            ndof_p2, uy_p2, it_p2, cut_p2 = solve_cook(n, "P2", args.diagonal, args.steps, args.qdeg)
        t2 = time.time()
        rows.append((n, ndof_th, uy_th, ndof_p2, uy_p2))
        print(f"# N={n}: TH {t1 - t0:.1f}s ({it_th} Newton its, {cut_th} step cuts), "
              f"P2 {t2 - t1:.1f}s ({it_p2} Newton its, {cut_p2} step cuts)", flush=True)

    print()
    print("Cook's membrane, plane strain, neo-Hookean (log J), mu=%.5g, lambda=%.7g, "
          "dead traction (0, 6.25) on x=48, %d load steps" % (MU, LMBDA, args.steps))
    print("mesh: UnitSquareMesh(N, N, '%s') mapped bilinearly; quadrature degree %d; "
          "QoI: u_y at (48, 60)" % (args.diagonal, args.qdeg))
    print()
    print("%5s  %10s  %18s  %10s  %18s" % ("N", "dofs(TH)", "u_y TH (P2/P1)", "dofs(P2)", "u_y P2 (displ.)"))
    for n, d1, y1, d2, y2 in rows:
        print("%5d  %10d  %18.10g  %10d  %18.10g" % (n, d1, y1, d2, y2))
    if len(rows) >= 3:
        a, b, c = (r[2] for r in rows[-3:])
        ns = [r[0] for r in rows[-3:]]
        if ns[1] == 2 * ns[0] and ns[2] == 2 * ns[1]:
            limit, order = richardson(a, b, c)
            print()
            print("Richardson (TH, N=%d,%d,%d): limit u_y = %.10g, observed order = %.3f"
                  % (ns[0], ns[1], ns[2], limit, order))
        if not args.skip_p2:
            a, b, c = (r[4] for r in rows[-3:])
            limit, order = richardson(a, b, c)
            print("Richardson (P2, N=%d,%d,%d): limit u_y = %.10g, observed order = %.3f"
                  % (ns[0], ns[1], ns[2], limit, order))


if __name__ == "__main__":
    main()
