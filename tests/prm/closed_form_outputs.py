#!/usr/bin/env python3
"""Writes the expected outputs of the homogeneous-deformation tests from
closed-form solutions, independently of tissuefem. Run from tests/prm/.

Each test deforms a unit cube (2 x 2 x 2 Q1 cells, 81 unknowns)
homogeneously, in two quasistatic steps to t = 1; the summary holds the
reaction force on one face at t = 0 and t = 1 and the final elastic energy
(Psi(F) times the unit volume)."""
import math


def lame(E, nu):
    return E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))


def fmt(x):
    # tissuefem prints with 8 significant digits (std::setprecision(8)).
    return "%.8g" % x


def write(name, boundary, reaction, energy, cells=8):
    lines = ["cells %d unknowns 81" % cells,
             "t = 0 boundary %d reaction = 0 0 0" % boundary,
             "t = 1 boundary %d reaction = %s" % (boundary, " ".join(fmt(r) for r in reaction)),
             "final elastic energy " + fmt(energy)]
    with open(name + ".output", "w") as f:
        f.write("\n".join(lines) + "\n")


def stvk_energy(lam, mu, E, kappa=0.0, a_index=None):
    tr = sum(E[i][i] for i in range(3))
    W = mu * sum(E[i][j] ** 2 for i in range(3) for j in range(3)) + 0.5 * lam * tr ** 2
    if a_index is not None:
        W += kappa * E[a_index][a_index] ** 2
    return W


def diag(*d):
    return [[d[i] if i == j else 0.0 for j in range(3)] for i in range(3)]


# St Venant-Kirchhoff, uniaxial stretch 1.2 with free lateral faces:
# S = lambda tr(E) I + 2 mu E, E = diag(a, b, b), S_yy = 0 gives
# b = -lambda a / (2 (lambda + mu)); P_xx = 1.2 S_xx.
lam, mu = lame(1000, 0.3)
stretch = 1.2
a = (stretch ** 2 - 1) / 2
b = -lam * a / (2 * (lam + mu))
S_xx = lam * (a + 2 * b) + 2 * mu * a
write("uniaxial_stretch_stvk", 1, [stretch * S_xx, 0, 0],
      stvk_energy(lam, mu, diag(a, b, b)))

# neo-Hookean (log J), uniaxial stretch 1.2: F = diag(1.2, s, s),
# P = mu F + (lambda ln J - mu) F^{-T}; solve P_yy = mu s + (lambda ln J -
# mu)/s = 0 for s by bisection, then P_xx = 1.2 mu + (lambda ln J - mu)/1.2.
def p_yy(s):
    J = stretch * s * s
    return mu * s + (lam * math.log(J) - mu) / s
lo, hi = 0.5, 1.0
for _ in range(200):
    mid = 0.5 * (lo + hi)
    if p_yy(lo) * p_yy(mid) <= 0:
        hi = mid
    else:
        lo = mid
s = 0.5 * (lo + hi)
J = stretch * s * s
P_xx = mu * stretch + (lam * math.log(J) - mu) / stretch
I1 = stretch ** 2 + 2 * s * s
W = 0.5 * mu * (I1 - 3) - mu * math.log(J) + 0.5 * lam * math.log(J) ** 2
write("uniaxial_stretch_neo_hookean", 1, [P_xx, 0, 0], W)
# The same stretch on P1 tetrahedra (2 x 2 x 2 cubes, 5 tetrahedra each)
# with the nodal dilatation: homogeneous, so Fbar = F.
write("uniaxial_stretch_nodal_dilatation", 1, [P_xx, 0, 0], W, cells=40)
# And with one pressure per vertex: homogeneous, so the pressure solving
# A p = b is lambda log J at every vertex (solid/nodal_pressure.h).
for name in ("uniaxial_stretch_nodal_pressure",
             "uniaxial_stretch_nodal_pressure.mpirun=2"):
    write(name, 1, [P_xx, 0, 0], W, cells=40)

# Simple shear F = I + g e_x (x) e_y, g = 0.3; reaction on y = 1 is P e_y.
g = 0.3
# St Venant-Kirchhoff: E = [[0, g/2, 0], [g/2, g^2/2, 0], [0, 0, 0]],
# S = lambda tr(E) I + 2 mu E, P = F S.
E = [[0, g / 2, 0], [g / 2, g * g / 2, 0], [0, 0, 0]]
trE = g * g / 2
S = [[lam * trE * (i == j) + 2 * mu * E[i][j] for j in range(3)] for i in range(3)]
F = [[1, g, 0], [0, 1, 0], [0, 0, 1]]
P = [[sum(F[i][k] * S[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
write("simple_shear_stvk", 3, [P[0][1], P[1][1], P[2][1]], stvk_energy(lam, mu, E))
# neo-Hookean: J = 1, so P = mu (F - F^{-T}) and P e_y = (mu g, 0, 0);
# Psi = mu/2 (tr F^T F - 3) = mu g^2 / 2.
write("simple_shear_neo_hookean", 3, [mu * g, 0, 0], 0.5 * mu * g * g)

# Transversely isotropic St Venant-Kirchhoff (Jeffrey eq 24), the muscle:
# (lambda, mu) from E = 20 kPa, nu = 0.4 across; kappa = Delta lambda / 2 +
# Delta mu from E^L = 150 kPa, nu^L = 0.4 along. S = lambda tr(E) I + 2 mu E
# + 2 kappa (a.E a) a (x) a. Stretch 1.01 in x; lateral E entries from
# S_yy = S_zz = 0 (linear in them), then P_xx = 1.01 S_xx.
lam, mu = lame(20000, 0.4)
lamL, muL = lame(150000, 0.4)
kappa = 0.5 * (lamL - lam) + (muL - mu)
stretch = 1.01
a = (stretch ** 2 - 1) / 2
# Fibre along x: S_yy = S_zz = 0 gives b = -lambda a / (2 (lambda + mu)).
b = -lam * a / (2 * (lam + mu))
S_xx = lam * (a + 2 * b) + 2 * mu * a + 2 * kappa * a
write("muscle_stretch_along", 1, [stretch * S_xx, 0, 0],
      stvk_energy(lam, mu, diag(a, b, b), kappa, 0))
# The same on 40 tetrahedra with the edge-length formulation.
write("muscle_stretch_along_edge_length", 1, [stretch * S_xx, 0, 0],
      stvk_energy(lam, mu, diag(a, b, b), kappa, 0), cells=40)
along = stretch * S_xx
# Fibre along y: S_yy = lambda (a + by + bz) + 2 (mu + kappa) by = 0,
#                S_zz = lambda (a + by + bz) + 2 mu bz = 0.
m11, m12, r1 = lam + 2 * (mu + kappa), lam, -lam * a
m21, m22, r2 = lam, lam + 2 * mu, -lam * a
det = m11 * m22 - m12 * m21
by = (r1 * m22 - m12 * r2) / det
bz = (m11 * r2 - m21 * r1) / det
S_xx = lam * (a + by + bz) + 2 * mu * a
write("muscle_stretch_across", 1, [stretch * S_xx, 0, 0],
      stvk_energy(lam, mu, diag(a, by, bz), kappa, 1))
print("stiffness ratio along/across the fibre at 1 % stretch:", along / (stretch * S_xx))


def tool_pull_bar_1d():
    # u(x, t) = 0.1 t x while held (uniform strain 0.1 t, sigma = E eps,
    # E = 1, L = 1): probe x = 0.5 at 0.05 t, the tissue pulls on the tool
    # with -0.1 t; released at t = 0.5, the free bar is at rest from then on.
    lines = ["cells 4 unknowns 5"]
    for t in (0, 0.25, 0.5, 0.75, 1):
        held = t <= 0.5
        lines.append("t = %s probe 0 u = %s" % (fmt(t), fmt(0.05 * t if held else 0)))
        lines.append("t = %s tool force = %s" % (fmt(t), fmt(-0.1 * t if held and t > 0 else 0)))
    lines.append("final elastic energy 0")
    with open("tool_pull_bar_1d.output", "w") as f:
        f.write("\n".join(lines) + "\n")


tool_pull_bar_1d()


def gravity_ramp_bar_1d(name="gravity_ramp_bar_1d",
                        factor=lambda t: min(2 * t, 1)):
    # -E u'' = rho g lambda on (0, 1), u(0) = 0, E u'(1) = 0, E = 1,
    # rho g = -0.1, lambda(t) = min(2 t, 1) (or the default of a quasistatic
    # run, t / End time = t): u = -0.1 lambda (x - x^2/2).
    # Linear elements reproduce u at the nodes (1D); their energy is that of
    # the nodal interpolant, sum over cells of E/2 (du)^2 / h.
    def u(x, lam):
        return -0.1 * lam * (x - x * x / 2)
    lines = ["cells 4 unknowns 5"]
    for t in (0, 0.25, 0.5, 0.75, 1):
        lam = factor(t)
        lines.append("t = %s probe 0 u = %s" % (fmt(t), fmt(u(0.5, lam) + 0.0)))
        lines.append("t = %s probe 1 u = %s" % (fmt(t), fmt(u(1, lam) + 0.0)))
        lines.append("t = %s boundary 0 reaction = %s" % (fmt(t), fmt(0.1 * lam)))
    nodes = [0, 0.25, 0.5, 0.75, 1]
    energy = sum(0.5 * (u(b, 1) - u(a, 1)) ** 2 / (b - a)
                 for a, b in zip(nodes, nodes[1:]))
    lines.append("final elastic energy " + fmt(energy))
    with open(name + ".output", "w") as f:
        f.write("\n".join(lines) + "\n")


gravity_ramp_bar_1d()
gravity_ramp_bar_1d("gravity_default_ramp_bar_1d", lambda t: t)


def contact_floor_bar_1d():
    # The bar of gravity_ramp_bar_1d standing on a penalty floor instead of
    # its clamp: the floor carries the weight 0.1 t (load factor t) with the
    # penetration 0.1 t / k, k = factor E / h = 100 * 1 / 0.25 = 400; the
    # bar above is the clamped bar's u shifted by the foot's -0.1 t / k
    # (the nodal values of linear elements stay exact in 1D, the spring at
    # x = 0 being a boundary term).
    k = 100 * 1 / 0.25

    def u(x, t):
        return -0.1 * t / k - 0.1 * t * (x - x * x / 2)
    lines = ["cells 4 unknowns 5"]
    for t in (0, 0.5, 1):
        lines.append("t = %s obstacle floor force = %s" % (fmt(t), fmt(0.1 * t)))
        lines.append("t = %s obstacle floor penetration = %s" % (fmt(t), fmt(0.1 * t / k)))
        # The foot is a point (unit area weight): its pressure is the force.
        lines.append("t = %s obstacle floor pressure range = %s %s" % (fmt(t), fmt(0.1 * t), fmt(0.1 * t)))
        for p, x in enumerate((0, 0.5, 1)):
            lines.append("t = %s probe %d u = %s" % (fmt(t), p, fmt(u(x, t) + 0.0)))
    nodes = [0, 0.25, 0.5, 0.75, 1]
    energy = sum(0.5 * (u(b, 1) - u(a, 1)) ** 2 / (b - a)
                 for a, b in zip(nodes, nodes[1:]))
    lines.append("final elastic energy " + fmt(energy))
    with open("contact_floor_bar_1d.output", "w") as f:
        f.write("\n".join(lines) + "\n")


contact_floor_bar_1d()


def contact_floor_block_2d(name="contact_floor_block_2d", times=(0, 0.5, 1),
                           weights=(0, 0.5, 1), variants=(".mpirun=2",),
                           floors=("floor",)):
    # Uniaxial stress under the block's weight (nu = 0, frictionless floor,
    # roller on x = 0): each column is the 1D bar of contact_floor_bar_1d
    # with H = 0.5, rho g = 0.1 and k = 100 E / h, h = 0.25 sqrt 2 (the
    # cells' diameter); the floor carries the weight 0.1 * 0.5 * 1 * t.
    # The energy is that of the nodal interpolant (two cells per column).
    # With n identical floors (the same plane) their penalties add: each
    # carries 1/n of the weight, the penetration is 1/n of one floor's.
    k = 100 / (0.25 * math.sqrt(2))
    n = len(floors)

    def u(y, t):
        return -0.05 * t / (n * k) - 0.1 * t * (0.5 * y - y * y / 2)
    lines = ["cells 8 unknowns 30"]
    for t, w in zip(times, weights):
        for floor in floors:
            lines.append("t = %s obstacle %s force = 0 %s" % (fmt(t), floor, fmt(0.05 * w / n)))
            lines.append("t = %s obstacle %s penetration = %s" % (fmt(t), floor, fmt(0.05 * w / (n * k))))
            # Uniform over the unit width: the weight.
            lines.append("t = %s obstacle %s pressure range = %s %s" % (fmt(t), floor, fmt(0.05 * w / n), fmt(0.05 * w / n)))
        for p, y in enumerate((0, 0.25, 0.5)):
            lines.append("t = %s probe %d u = 0 %s" % (fmt(t), p, fmt(u(y, w) + 0.0)))
    nodes = [0, 0.25, 0.5]
    energy = sum(0.5 * (u(b, 1) - u(a, 1)) ** 2 / (b - a)
                 for a, b in zip(nodes, nodes[1:]))
    lines.append("final elastic energy " + fmt(energy))
    for n in (name,) + tuple(name + v for v in variants):
        with open(n + ".output", "w") as f:
            f.write("\n".join(lines) + "\n")


contact_floor_block_2d()
# Released under its full weight at t = 0; at rest at t = 30 (the steps of
# linearly implicit Euler damp the motion).
contact_floor_block_2d("contact_floor_block_lie_2d", (0, 30), (0, 1), ())
# Any number of obstacles: four floors in the slots 2, 5, 9 and 12, beyond
# the four slots always declared.
contact_floor_block_2d("contact_many_obstacles_2d", variants=(),
                       floors=("floor 2", "floor 5", "floor 9", "floor 12"))


def contact_patch(name, dim, cells, unknowns, probes, names=None, tool=False):
    # A rigid flat face pushed by 0.05 t into a block of height H = 0.5 on
    # rollers, frictionless, linear elastic (E = 1, nu = 0.3): homogeneous
    # uniaxial stress, eps = -0.1 t along the last axis, the other stresses
    # zero (and plane strain in 2D: E' = E / (1 - nu^2), nu' = nu / (1 -
    # nu)); the augmented Lagrangian leaves no gap, so the pressure is E'
    # 0.1 t, uniform, on a unit area or width.
    nu = 0.3
    E1, nu1 = (1 / (1 - nu * nu), nu / (1 - nu)) if dim == 2 else (1.0, nu)
    zero = " ".join(["0"] * dim)
    lines = ["cells %d unknowns %d" % (cells, unknowns)]
    for t in (0, 0.5, 1):
        p = E1 * 0.1 * t
        force = ["0"] * (dim - 1) + [fmt(-p + 0.0)]
        lines.append("t = %s obstacle press force = %s" % (fmt(t), " ".join(force)))
        lines.append("t = %s obstacle press penetration = 0" % fmt(t))
        lines.append("t = %s obstacle press pressure range = %s %s" % (fmt(t), fmt(p), fmt(p)))
        for i, X in enumerate(probes):
            u = [nu1 * 0.1 * t * x for x in X[:-1]] + [-0.1 * t * X[-1]]
            lines.append("t = %s probe %d u = %s" % (fmt(t), i, " ".join(fmt(c + 0.0) for c in u)))
        if tool:
            # The tissue pushes the press back: minus its force on the tissue.
            back = ["0"] * (dim - 1) + [fmt(p)]
            lines.append("t = %s tool force = %s" % (fmt(t), " ".join(back)))
    # Psi V = 1/2 sigma eps V with V = 0.5 (unit cross-section, H = 0.5).
    energy = 0.5 * E1 * 0.1 * 0.1 * 0.5
    lines.append("final elastic energy " + fmt(energy))
    for n in names or (name,):
        with open(n + ".output", "w") as f:
            f.write("\n".join(lines) + "\n")


contact_patch("contact_patch_2d", 2, 8, 30, [(1, 0.5), (0.5, 0.25), (0.25, 0.5)])
contact_patch("contact_patch_recorded_2d", 2, 8, 30, [(1, 0.5), (0.5, 0.25), (0.25, 0.5)])
contact_patch("contact_tool_patch_2d", 2, 8, 30, [(1, 0.5), (0.5, 0.25), (0.25, 0.5)],
              tool=True)
contact_patch("contact_patch_3d", 3, 20, 54,
              [(1, 1, 0.5), (0.5, 0.5, 0.25), (0.3, 0.7, 0.5)],
              ("contact_patch_3d", "contact_patch_3d.mpirun=2"))
# Every element the solid has: Q2 (9 x 5 nodes), the mean dilatation (Q1),
# the nodal dilatation (P1, whose pressures are not counted among the
# displacement unknowns), P2 (18 vertices and 53 edges: 20 tetrahedra with
# 56 faces, 32 of them the 16 boundary squares split, and Euler's V - E + F
# - T = 1).
contact_patch("contact_patch_q2_2d", 2, 8, 2 * 9 * 5,
              [(1, 0.5), (0.5, 0.25), (0.25, 0.5)])
contact_patch("contact_patch_mean_dilatation_2d", 2, 8, 30,
              [(1, 0.5), (0.5, 0.25), (0.25, 0.5)])
contact_patch("contact_patch_nodal_dilatation_3d", 3, 20, 54,
              [(1, 1, 0.5), (0.5, 0.5, 0.25), (0.3, 0.7, 0.5)],
              ("contact_patch_nodal_dilatation_3d",
               "contact_patch_nodal_dilatation_3d.mpirun=2"))
contact_patch("contact_patch_p2_3d", 3, 20, 3 * (18 + 53),
              [(1, 1, 0.5), (0.5, 0.5, 0.25), (0.3, 0.7, 0.5)])
contact_patch("contact_patch_surface_3d", 3, 20, 54,
              [(1, 1, 0.5), (0.5, 0.5, 0.25), (0.3, 0.7, 0.5)],
              ("contact_patch_surface_3d", "contact_patch_surface_3d.mpirun=2"))
