#pragma once
// The reference permeability of a periodic square array of circular cylinders in Stokes flow (scene
// "cylinder-lattice", core/scenes/cylinder_lattice_scene.cpp), two independent ways:
//  - the low-concentration series of Hasimoto (1959), extended by Sangani & Acrivos (1982, Int. J. Multiphase
//    Flow 8, 193, eq. for the square array):  F/(mu U) = 4 pi / (-1/2 ln c - 0.738 + c - 0.887 c^2 + 2.038 c^3);
//  - our own Stokes solve of the cell by boundary collocation (below), valid at every c up to close packing.
// F is the drag per unit length on one cylinder when a mean pressure gradient G drives the flow, F = G L^2
// (the gradient acts on the whole cell), U the superficial velocity (the flux per unit width, the mean velocity
// over the whole cell with the solid counting zero), c = pi a^2 / L^2 the solid fraction. The Darcy permeability
// is then k = mu U / G, k / L^2 = 1 / (F / (mu U)); a body force g per unit mass on the fluid alone is the same
// as G = rho g (the pressure's periodic part absorbs the difference), so k = mu <u> / (rho g).
namespace closurelab {

// Hasimoto / Sangani–Acrivos series for F/(mu U) at solid fraction c (0 < c; accurate to ~0.1 % at c = 0.1,
// 12 % low at c = 0.3).
double square_array_drag_series(double c);

struct SquareArrayStokesResult {
  double drag = 0.0;               // F / (mu U)
  double permeability = 0.0;       // k / L^2 = 1 / drag
  double boundary_residual = 0.0;  // max residual of the cell-boundary conditions, relative to the flux
  int modes = 0;
};

// Boundary collocation (the method of Sangani & Acrivos's eigenfunction expansions, in the unit cell): the stream
// function psi = sum over odd n of f_n(r) sin(n theta), each f_n a combination of the biharmonic solutions
// r^n, r^-n, r^(n+2), r^(2-n) (n = 1: r, 1/r, r^3, r ln r) that vanishes with its derivative on r = a (no slip,
// exactly), with the symmetry conditions of the cell on its boundary imposed in the least-squares sense at
// collocation points of the quarter cell's outer edges: on y = L/2, psi = Q/2 and vorticity 0 (v = 0, du/dy = 0);
// on x = L/2, d psi/dx = 0 and d(vorticity)/dx = 0 (v = 0; u and the vorticity even about the line). The
// coefficient of r ln r sin(theta) is F / (4 pi mu) (the Stokeslet); U = Q / L.
// `a_over_l` in (0, 1/2); `modes` odd harmonics n = 1, 3, ..., 2 modes - 1.
SquareArrayStokesResult square_array_stokes(double a_over_l, int modes = 24);

}  // namespace closurelab
