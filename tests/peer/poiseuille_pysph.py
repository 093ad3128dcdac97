"""An independent PySPH model of closurelab's `poiseuille-uniform` (and `layered-two-phase`) scene (DESIGN.md par. 5), written from the
paper and the scene's definition, not from closurelab's code paths: a peer for the direct SPH engine.

Run under the Debian interpreter (python3-pysph): /usr/bin/python3 tests/peer/poiseuille_pysph.py --ny 48 --tf 0.6

The model, term by term (closurelab's conventions: model units rho = mu = g = L_y = 1, periodic in x):
  - lattice: particle (i, j) at ((i + 1/2) eps', (j + 1/2) eps'), eps' = L_y / n_y, n_x columns; rows with
    y < 3 eta' or y > L_y - 3 eta' are wall particles held at zero velocity (5.3), the rest fluid;
  - smoothing function: PySPH's QuinticSpline (support 3h), h = eps';
  - number density by summation, n_i = sum_j w(|q_i - q_j|) over fluid and wall neighbours (itself included);
    the walls do not move, so their wall-wall part is summed once before the run and kept ("nfix", with numpy:
    the strip is 3 supports wide at least, so the images at -L_x, 0, +L_x are all), and each step adds the fluid
    part;
  - equation of state P = c^2 (m n - rho0) + P_b with P_b = rho0 c^2, i.e. P = c^2 rho; c = 10 x the analytic
    peak velocity rho g (l2 - l1)^2 / (8 mu);
  - the pair force (5.1) with Morris's viscous term and mu_ij = mu_i + mu_j:
      f_ij = -(P_i/n_i^2 + P_j/n_j^2) grad_i w + (mu_i + mu_j) (v_i - v_j) (q_ij . grad_i w) / (n_i n_j |q_ij|^2),
    a_i = sum_j f_ij / m + g e_x for the fluid;
  - kick-drift-kick (velocity Verlet) with the second force evaluation at the predicted velocity
    v + dt a(t): v_half = v + dt/2 a; x += dt v_half; v_pred = v_half + dt/2 a; a_new = a(x, v_pred);
    v = v_half + dt/2 a_new;
  - dt = kappa min(eps'/(c + max|v|), rho eps'^2 / (mu beta)) with kappa = 0.25: the viscous limit 0.25 eps'^2
    for these walls (beta = 1); the final step is shortened to land on tf (PySPH's solver does it);
  - the particle mass m = rho0 / n*, n* the number density of the perfect infinite lattice.

--wall-model ghost_velocity swaps in Morris's ghost velocities (in a fluid-wall pair the wall particle carries
-(d_wall/d_fluid) v_fluid, so the pair's relative velocity is beta v_fluid, beta = min(beta_max, 1 + d_wall/d_fluid),
distances to the wall surfaces y = l1, l2) and the
viscous time step divided by beta_max' = min(beta_max, 1 + 3h/(eps'/2)), as closurelab does.

--scene layered-two-phase builds closurelab's two-phase layered channel instead (core/scenes/layered_scene.cpp
defaults; --ny fluid rows between walls of lround(3 eta'/eps') rows outside the channel, --case case1..3 scaled
from the paper's 192 rows): phase 1 (mu = 100) in layers, phase 0 (mu = 200) elsewhere and in the walls; van der
Waals (7.1), P = n k_B T / (1 - c_1 n) - c_2 n^2 with c_1 n0 = 1/2, c_2 n0 = k_B T, k_B T = m c^2 / (1/(1 - 1/2)^2 - 2),
an unlike pair adding 2 (1 - k*) c_2 (k* = 1/2) to P_i/n_i^2 + P_j/n_j^2; mu_ij = mu_i + mu_j (arithmetic);
c = 10 x the peak of the piecewise-parabolic steady solution.

--scene cylinder-lattice builds closurelab's cylinder lattice (core/scenes/cylinder_lattice_scene.cpp defaults;
--ny is n, the cell's n x n lattice, L = 1, --radius-over-length a/L): periodic in x and y (PySPH's DomainManager),
the lattice particles within a of the cell's centre solid at zero velocity with their solid-solid density part
summed once ("nfix", images in x and y) like the channel's walls, and taking part in the fluid's pair forces with
their pressure; g = 0.01 on the fluid; P = c^2 (m n - rho0) + 0.002 rho0 c^2, c from the scene's rule
(CylinderLatticeScene).

Each particle carries `lattice`, its index j n_x + i, so a comparison can pair particles whatever order PySPH
keeps them in. The solver writes PySPH's own output files (HDF5 with h5py, else npz) into the output folder.
"""

import math

import numpy as np

from pysph.base.kernels import QuinticSpline
from pysph.base.nnps import DomainManager
from pysph.base.utils import get_particle_array
from pysph.solver.application import Application
from pysph.solver.solver import Solver
from pysph.sph.equation import Equation, Group
from pysph.sph.integrator import Integrator
from pysph.sph.integrator_step import IntegratorStep


# ----------------------------------------------------------------------------------------------------------------
# Equations


class NumberDensity(Equation):
    """n_i = n_fixed_i + sum_j w_ij (fluid: n_fixed = 0 and the sum over fluid and walls, itself included;
    walls: n_fixed their wall-wall part, the sum over the fluid)."""

    def initialize(self, d_idx, d_n, d_nfix):
        d_n[d_idx] = d_nfix[d_idx]

    def loop(self, d_idx, d_n, WIJ):
        d_n[d_idx] += WIJ


class WeaklyCompressiblePressure(Equation):
    """P = c^2 (m n - rho0) + P_b; stores P/n^2 and rho = m n."""

    def __init__(self, dest, sources, c0, rho0, pb):
        self.c2 = c0 * c0
        self.rho0 = rho0
        self.pb = pb
        super(WeaklyCompressiblePressure, self).__init__(dest, sources)

    def initialize(self, d_idx, d_n, d_m, d_rho, d_p, d_pn2):
        d_rho[d_idx] = d_m[d_idx] * d_n[d_idx]
        d_p[d_idx] = self.c2 * (d_rho[d_idx] - self.rho0) + self.pb
        d_pn2[d_idx] = d_p[d_idx] / (d_n[d_idx] * d_n[d_idx])


class VanDerWaalsPressure(Equation):
    """(7.1) for like pairs, P = n k_B T / (1 - c_1 n) - c_2 n^2; stores P/n^2 and rho = m n. (An unlike pair adds
    (1 - k*) c_2 to each P/n^2: PairForce51's `unlike`.)"""

    def __init__(self, dest, sources, kt, c1, c2):
        self.kt = kt
        self.c1 = c1
        self.c2 = c2
        super(VanDerWaalsPressure, self).__init__(dest, sources)

    def initialize(self, d_idx, d_n, d_m, d_rho, d_p, d_pn2):
        n = d_n[d_idx]
        d_rho[d_idx] = d_m[d_idx] * n
        d_p[d_idx] = n * self.kt / (1.0 - self.c1 * n) - self.c2 * n * n
        d_pn2[d_idx] = d_p[d_idx] / (n * n)


class PairForce51(Equation):
    """The pair force (5.1) with Morris's viscosity, mu_ij = mu_i + mu_j; a = sum f / m + g e_x.

    ghost = 1: Morris's ghost velocity for fluid-wall pairs (the sources that are walls carry `is_wall` = 1).
    Two phases (the layered scene): a pair of unlike phases adds `unlike` = 2 (1 - k*) c_2 to P_i/n_i^2 + P_j/n_j^2
    ((7.1) with k_ij = k*); mu_ij stays mu_i + mu_j."""

    def __init__(self, dest, sources, gx, ghost, beta_max, wall_lo, wall_hi, dx, unlike=0.0):
        self.gx = gx
        self.unlike = unlike
        self.ghost = ghost
        self.beta_max = beta_max
        self.wall_lo = wall_lo
        self.wall_hi = wall_hi
        self.dmin = 1e-3 * dx
        super(PairForce51, self).__init__(dest, sources)

    def initialize(self, d_idx, d_fx, d_fy):
        d_fx[d_idx] = 0.0
        d_fy[d_idx] = 0.0

    def loop(self, d_idx, s_idx, d_pn2, s_pn2, d_n, s_n, d_mu, s_mu, d_u, d_v, d_y, s_y, s_is_wall, d_phase,
             s_phase, d_fx, d_fy, DWIJ, XIJ, VIJ, R2IJ):
        if R2IJ > 1e-300:
            psum = d_pn2[d_idx] + s_pn2[s_idx]
            if d_phase[d_idx] != s_phase[s_idx]:
                psum += self.unlike
            visc = (d_mu[d_idx] + s_mu[s_idx]) / (d_n[d_idx] * s_n[s_idx])
            F = (DWIJ[0] * XIJ[0] + DWIJ[1] * XIJ[1]) / R2IJ
            vx = VIJ[0]
            vy = VIJ[1]
            if self.ghost > 0 and s_is_wall[s_idx] > 0:
                # the wall particle moves with -(d_wall/d_fluid) v_fluid: v_i - v_ghost = beta v_i
                if s_y[s_idx] < self.wall_lo:
                    dw = self.wall_lo - s_y[s_idx]
                    df = max(d_y[d_idx] - self.wall_lo, self.dmin)
                else:
                    dw = s_y[s_idx] - self.wall_hi
                    df = max(self.wall_hi - d_y[d_idx], self.dmin)
                beta = min(self.beta_max, 1.0 + dw / df)
                vx = beta * d_u[d_idx]
                vy = beta * d_v[d_idx]
            d_fx[d_idx] += -psum * DWIJ[0] + visc * F * vx
            d_fy[d_idx] += -psum * DWIJ[1] + visc * F * vy

    def post_loop(self, d_idx, d_m, d_fx, d_fy, d_au, d_av):
        d_au[d_idx] = d_fx[d_idx] / d_m[d_idx] + self.gx
        d_av[d_idx] = d_fy[d_idx] / d_m[d_idx]


# ----------------------------------------------------------------------------------------------------------------
# Kick-drift-kick


class KickDriftKickStep(IntegratorStep):
    def stage1(self, d_idx, d_x, d_y, d_u, d_v, d_au, d_av, d_uh, d_vh, dt):
        d_uh[d_idx] = d_u[d_idx] + 0.5 * dt * d_au[d_idx]
        d_vh[d_idx] = d_v[d_idx] + 0.5 * dt * d_av[d_idx]
        d_x[d_idx] = d_x[d_idx] + dt * d_uh[d_idx]
        d_y[d_idx] = d_y[d_idx] + dt * d_vh[d_idx]
        # the predicted velocity for the viscous force of the second evaluation
        d_u[d_idx] = d_uh[d_idx] + 0.5 * dt * d_au[d_idx]
        d_v[d_idx] = d_vh[d_idx] + 0.5 * dt * d_av[d_idx]

    def stage2(self, d_idx, d_u, d_v, d_au, d_av, d_uh, d_vh, dt):
        d_u[d_idx] = d_uh[d_idx] + 0.5 * dt * d_au[d_idx]
        d_v[d_idx] = d_vh[d_idx] + 0.5 * dt * d_av[d_idx]


class KickDriftKickIntegrator(Integrator):
    def one_timestep(self, t, dt):
        self.stage1()
        self.update_domain()
        self.do_post_stage(dt, 1)
        self.compute_accelerations()
        self.stage2()
        self.update_domain()
        self.do_post_stage(dt, 2)


# ----------------------------------------------------------------------------------------------------------------
# The scene


def quintic_w(r, h):
    """The 2D quintic spline (support 3h), for the lattice sum of the particle mass."""
    q = r / h
    s = 0.0
    if q < 3.0:
        s += (3.0 - q) ** 5
    if q < 2.0:
        s -= 6.0 * (2.0 - q) ** 5
    if q < 1.0:
        s += 15.0 * (1.0 - q) ** 5
    return 7.0 / (478.0 * math.pi * h * h) * s


def wall_wall_density(x, y, lx, h, ly=None):
    """sum_j w(|q_i - q_j|) over the given particles and their images shifted by -lx, 0, +lx (periodic in x) and,
    given ly, by -ly, 0, +ly too (periodic in y)."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    n = np.zeros_like(x)
    yshifts = (0.0,) if ly is None else (-ly, 0.0, ly)
    for shift in (-lx, 0.0, lx):
        for yshift in yshifts:
            for a in range(len(x)):
                q = np.hypot(x[a] - (x + shift), y[a] - (y + yshift)) / h
                s = np.where(q < 3.0, (3.0 - q) ** 5, 0.0) - np.where(q < 2.0, 6.0 * (2.0 - q) ** 5, 0.0) \
                    + np.where(q < 1.0, 15.0 * (1.0 - q) ** 5, 0.0)
                n[a] += 7.0 / (478.0 * math.pi * h * h) * np.sum(s)
    return n


class ChannelScene(object):
    """poiseuille-uniform's parameters (closurelab core/scenes/scenes.cpp defaults)."""

    def __init__(self, ny, nx, eta_over_ly=1.0 / 16.0, ly=1.0, rho=1.0, mu=1.0, g=1.0, sound_speed_factor=10.0,
                 background_pressure_factor=1.0, wall_model="zero_velocity", ghost_beta_max=1.0e6):
        self.ny, self.nx = ny, nx
        self.dx = ly / ny
        self.h = self.dx
        self.lx, self.ly = nx * self.dx, ly
        self.eta = eta_over_ly * ly
        self.wall_lo, self.wall_hi = 3.0 * self.eta, ly - 3.0 * self.eta
        self.rho0, self.mu, self.g = rho, mu, g
        self.wall_model, self.ghost_beta_max = wall_model, ghost_beta_max
        # The analytic peak (5.15) at the channel's centre, and the sound speed from it.
        l1, l2 = self.wall_lo, self.wall_hi
        y = 0.5 * (l1 + l2)
        self.peak = -rho * g / (2.0 * mu) * (y * y - (l1 + l2) * y + l1 * l2)
        self.c0 = sound_speed_factor * self.peak
        self.pb = background_pressure_factor * rho * self.c0 * self.c0
        # m = rho0 / n*, n* = sum of w over the perfect lattice.
        reach = int(math.ceil(3.0 * self.h / self.dx)) + 1
        n_star = sum(quintic_w(self.dx * math.hypot(a, b), self.h)
                     for a in range(-reach, reach + 1) for b in range(-reach, reach + 1))
        self.mass = rho / n_star
        beta = 1.0
        if wall_model == "ghost_velocity":
            beta = min(ghost_beta_max, 1.0 + 3.0 * self.h / (0.5 * self.dx))
        self.viscous_stiffening = beta

    def time_step(self, kappa=0.25, max_speed=0.0):
        return kappa * min(self.dx / (self.c0 + max_speed),
                           self.rho0 * self.dx * self.dx / (self.mu * self.viscous_stiffening))

    def is_wall(self, y):
        return y < self.wall_lo or y > self.wall_hi

    def is_solid(self, x, y):
        return self.is_wall(y)


class LayeredScene(ChannelScene):
    """layered-two-phase (closurelab core/scenes/layered_scene.cpp defaults): n_y fluid rows across the channel
    L = 1, walls of lround(3 eta'/eps') rows outside it; less-viscous layers (phase 1, mu 100) in the more viscous
    fluid (phase 0, mu 200; the walls too) at the paper's rows of the 192-row lattice scaled by n_y/192; van der
    Waals (7.1) with phi = 1/2, a = 1, k* = 1/2, c = 10 x the analytic peak of the piecewise parabolas."""

    layouts = {"case1": ([30, 45, 90, 140, 152], 9), "case2": ([25, 70, 115, 160], 9), "case3": ([30, 120], 27)}

    def __init__(self, ny, nx, case="case1", eta_over_l=1.0 / 16.0, l=1.0, rho=1.0, mu_viscous=200.0,
                 mu_less_viscous=100.0, g=1.0, sound_speed_factor=10.0, phi=0.5, a=1.0, k_star=0.5):
        self.nx = nx
        self.dx = l / ny
        self.h = self.dx
        self.eta = eta_over_l * l
        wall_rows = int(round_half_away(3.0 * self.eta / self.dx))
        self.fluid_rows = ny
        self.ny = ny + 2 * wall_rows
        self.lx, self.ly = nx * self.dx, self.ny * self.dx
        self.wall_lo = wall_rows * self.dx
        self.wall_hi = self.wall_lo + l
        self.rho0, self.g = rho, g
        self.wall_model, self.ghost_beta_max, self.viscous_stiffening = "zero_velocity", 1.0e6, 1.0
        starts, width = self.layouts[case]
        scale = float(ny) / 192.0
        self.row_phase = [0] * ny
        for st in starts:
            for k in range(int(round_half_away(width * scale))):
                self.row_phase[int(round_half_away(st * scale)) + k] = 1
        self.phase_mu = [mu_viscous, mu_less_viscous]
        self.mu = max(self.phase_mu)  # the viscous time step's
        # The analytic peak: v(y) = int_l1^y (tau_1 - rho g (s - l1)) / mu(s) ds, tau_1 from v(l2) = 0; the peak
        # where the shear stress vanishes, y* = l1 + tau_1 / (rho g).
        bounds = [self.wall_lo]
        mus = [self.phase_mu[self.row_phase[0]]]
        for r in range(1, ny):
            if self.row_phase[r] != self.row_phase[r - 1]:
                bounds.append(self.wall_lo + r * self.dx)
                mus.append(self.phase_mu[self.row_phase[r]])
        bounds.append(self.wall_hi)
        l1 = self.wall_lo
        compliance = sum((bounds[k + 1] - bounds[k]) / mus[k] for k in range(len(mus)))
        moment = sum((bounds[k + 1] - bounds[k]) * (bounds[k] + bounds[k + 1] - 2.0 * l1) / (2.0 * mus[k])
                     for k in range(len(mus)))
        tau1 = rho * g * moment / compliance
        ystar = l1 + tau1 / (rho * g)
        v = 0.0
        for k in range(len(mus)):
            a0, b0 = bounds[k], min(bounds[k + 1], ystar)
            if b0 <= a0:
                break
            v += (tau1 * (b0 - a0) - 0.5 * rho * g * (b0 - a0) * (a0 + b0 - 2.0 * l1)) / mus[k]
        self.peak = abs(v)
        self.c0 = sound_speed_factor * self.peak
        reach = int(math.ceil(3.0 * self.h / self.dx)) + 1
        n_star = sum(quintic_w(self.dx * math.hypot(i, j), self.h)
                     for i in range(-reach, reach + 1) for j in range(-reach, reach + 1))
        self.mass = rho / n_star
        n0 = rho / self.mass
        d = 1.0 - phi
        self.kt = self.mass * self.c0 * self.c0 / (1.0 / (d * d) - 2.0 * a)
        self.c1 = phi / n0
        self.c2 = a * self.kt / n0
        self.unlike = 2.0 * (1.0 - k_star) * self.c2

    def phase(self, y):
        r = math.floor((y - self.wall_lo) / self.dx)
        return self.row_phase[r] if 0 <= r < self.fluid_rows else 0


class CylinderLatticeScene(ChannelScene):
    """cylinder-lattice (closurelab core/scenes/cylinder_lattice_scene.cpp defaults): a square cell of side L,
    periodic in x and y, the n x n lattice of spacing eps' = L / n; the lattice particles closer than
    a = radius_over_length L to the centre (L/2, L/2) are solid, at zero velocity; the fluid is driven by g e_x.
    P = c^2 (m n - rho0) + P_b with P_b = 0.002 rho0 c^2; c = 10 V with
    V^2 = max(U^2, nu U / L, g L, nu^2 / L^2) (Morris, Fox & Zhu 1997), U = 1.5 <u> L / (L - 2a) the gap-velocity
    estimate from the Darcy permeability of the square array, <u> = k g / nu. The permeability is only needed for
    U, and at the scene's defaults (g = 0.01, nu = 1) nu^2 / L^2 = 1 exceeds the other three terms by 100 x and more,
    so here k is Hasimoto's (1959) dilute series k / L^2 = (-ln c - 1.476 + 2 c - 1.774 c^2) / (8 pi)
    (c = pi a^2 / L^2; within a few % of Sangani & Acrivos at c <= 0.3); the scene refuses parameters under which
    the U terms come within a factor 10 of the largest, where the estimate's error could change c."""

    def __init__(self, n, radius_over_length=0.2, l=1.0, rho=1.0, mu=1.0, g=0.01, sound_speed_factor=10.0,
                 background_pressure_factor=0.002):
        self.nx = self.ny = n
        self.dx = l / n
        self.h = self.dx
        self.lx = self.ly = l
        self.a = radius_over_length * l
        self.rho0, self.mu, self.g = rho, mu, g
        self.wall_model, self.ghost_beta_max, self.viscous_stiffening = "zero_velocity", 1.0e6, 1.0
        self.wall_lo, self.wall_hi = -1.0, 2.0 * l  # no walls (PairForce51's ghost terms are off)
        nu = mu / rho
        c = math.pi * radius_over_length ** 2
        k = l * l * (-math.log(c) - 1.476 + 2.0 * c - 1.774 * c * c) / (8.0 * math.pi)
        u_gap = 1.5 * (k * g / nu) * l / (l - 2.0 * self.a)
        v2_flow = max(u_gap * u_gap, nu * u_gap / l)
        v2 = max(g * l, nu * nu / (l * l))
        if v2_flow * 10.0 > v2:
            raise SystemExit("cylinder-lattice: the sound speed depends on the gap velocity here (V^2 terms %g vs %g); "
                             "this model's permeability estimate is not precise enough for it" % (v2_flow, v2))
        self.peak = u_gap
        self.c0 = sound_speed_factor * math.sqrt(v2)
        self.pb = background_pressure_factor * rho * self.c0 * self.c0
        reach = int(math.ceil(3.0 * self.h / self.dx)) + 1
        n_star = sum(quintic_w(self.dx * math.hypot(i, j), self.h)
                     for i in range(-reach, reach + 1) for j in range(-reach, reach + 1))
        self.mass = rho / n_star

    def is_wall(self, y):
        return False

    def is_solid(self, x, y):
        cx = cy = 0.5 * self.lx
        return (x - cx) * (x - cx) + (y - cy) * (y - cy) < self.a * self.a


def round_half_away(x):
    """C's lround."""
    return math.floor(x + 0.5) if x >= 0 else -math.floor(-x + 0.5)


class PoiseuillePeer(Application):
    def add_user_options(self, group):
        group.add_argument("--ny", type=int, default=48, help="particle rows across L_y")
        group.add_argument("--nx", type=int, default=12, help="particle columns of the periodic strip")
        group.add_argument("--wall-model", default="zero_velocity", choices=["zero_velocity", "ghost_velocity"])
        group.add_argument("--ghost-beta-max", type=float, default=1.0e6)
        group.add_argument("--scene", default="poiseuille-uniform",
                           choices=["poiseuille-uniform", "layered-two-phase", "cylinder-lattice"],
                           help="layered-two-phase: --ny fluid rows, walls outside, zero-velocity walls only; "
                                "cylinder-lattice: --ny is n (the cell's n x n lattice), --nx ignored")
        group.add_argument("--case", default="case1", choices=["case1", "case2", "case3"])
        group.add_argument("--radius-over-length", type=float, default=0.2, help="cylinder-lattice: a / L")

    def consume_user_options(self):
        o = self.options
        if o.scene == "layered-two-phase":
            self.scene = LayeredScene(o.ny, o.nx, case=o.case)
        elif o.scene == "cylinder-lattice":
            self.scene = CylinderLatticeScene(o.ny, radius_over_length=o.radius_over_length)
        else:
            self.scene = ChannelScene(o.ny, o.nx, wall_model=o.wall_model, ghost_beta_max=o.ghost_beta_max)

    def create_domain(self):
        if isinstance(self.scene, CylinderLatticeScene):
            return DomainManager(xmin=0.0, xmax=self.scene.lx, ymin=0.0, ymax=self.scene.ly, periodic_in_x=True,
                                 periodic_in_y=True)
        return DomainManager(xmin=0.0, xmax=self.scene.lx, periodic_in_x=True)

    def create_particles(self):
        s = self.scene
        fx, fy, fl, wx, wy, wl = [], [], [], [], [], []
        for j in range(s.ny):
            y = (j + 0.5) * s.dx
            for i in range(s.nx):
                x = (i + 0.5) * s.dx
                if s.is_solid(x, y):
                    wx.append(x), wy.append(y), wl.append(j * s.nx + i)
                else:
                    fx.append(x), fy.append(y), fl.append(j * s.nx + i)
        props = ["n", "nfix", "p", "pn2", "mu", "fx", "fy", "uh", "vh", "is_wall"]
        layered = isinstance(s, LayeredScene)
        arrays = []
        for name, x, y, lat, wall in (("fluid", fx, fy, fl, 0.0), ("solid", wx, wy, wl, 1.0)):
            x = np.array(x)
            pa = get_particle_array(name=name, x=x, y=np.array(y), m=np.full_like(x, s.mass),
                                    h=np.full_like(x, s.h), rho=np.full_like(x, s.rho0))
            for prop in props:
                pa.add_property(prop)
            pa.add_property("lattice", type="int", data=np.array(lat, dtype=np.int32))
            phase = [s.phase(yy) for yy in y] if layered else [0] * len(y)
            pa.add_property("phase", type="int", data=np.array(phase, dtype=np.int32))
            pa.mu[:] = [s.phase_mu[k] for k in phase] if layered else s.mu
            pa.is_wall[:] = wall
            pa.set_output_arrays(["x", "y", "u", "v", "m", "rho", "p", "n", "h", "phase", "lattice", "pid", "gid", "tag"])
            arrays.append(pa)
        fluid, solid = arrays
        # The walls' fixed wall-wall density, once (walls do not move): the quintic spline summed over the wall
        # particles and their periodic images in x, itself included.
        solid.nfix[:] = wall_wall_density(solid.x, solid.y, s.lx, s.h,
                                          ly=s.ly if isinstance(s, CylinderLatticeScene) else None)
        return [fluid, solid]

    def create_equations(self):
        s = self.scene
        ghost = 1 if s.wall_model == "ghost_velocity" else 0
        # Densities and pressures also on the periodic images (real=False): PySPH copies an image's properties
        # from its particle when it places the images, before this step's density exists.
        if isinstance(s, LayeredScene):
            eos = [VanDerWaalsPressure(dest=d, sources=None, kt=s.kt, c1=s.c1, c2=s.c2) for d in ("fluid", "solid")]
            unlike = s.unlike
        else:
            eos = [WeaklyCompressiblePressure(dest=d, sources=None, c0=s.c0, rho0=s.rho0, pb=s.pb)
                   for d in ("fluid", "solid")]
            unlike = 0.0
        return [
            Group(equations=[NumberDensity(dest="fluid", sources=["fluid", "solid"]),
                             NumberDensity(dest="solid", sources=["fluid"])], real=False),
            Group(equations=eos, real=False),
            Group(equations=[PairForce51(dest="fluid", sources=["fluid", "solid"], gx=s.g, ghost=ghost,
                                         beta_max=s.ghost_beta_max, wall_lo=s.wall_lo, wall_hi=s.wall_hi, dx=s.dx,
                                         unlike=unlike)]),
        ]

    def create_solver(self):
        s = self.scene
        # The viscous limit holds throughout (c = 10 x the peak), so dt is fixed; checked at the end.
        dt = s.time_step()
        return Solver(kernel=QuinticSpline(dim=2), dim=2, integrator=KickDriftKickIntegrator(fluid=KickDriftKickStep()),
                      dt=dt, tf=0.6, adaptive_timestep=False, pfreq=10**9)

    def post_process(self, info_fname):
        s = self.scene
        fluid = self.particles[0]
        vmax = float(np.max(np.hypot(fluid.u, fluid.v)))
        if s.time_step(max_speed=vmax) != s.time_step():
            raise SystemExit("poiseuille_pysph: the time step left the viscous limit (max|v| = %g)" % vmax)


if __name__ == "__main__":
    app = PoiseuillePeer()
    app.run()
    app.post_process(app.info_filename)
