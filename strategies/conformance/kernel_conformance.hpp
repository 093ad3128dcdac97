#pragma once
// The averaging-kernel conformance checks (DESIGN.md §2, §7 rung 1) as a library without GoogleTest, run by
// tests/conformance/test_strategy_conformance.cpp on every registered kernel and by a user's project on its own
// (as for deconvolvers, strategies/conformance/deconvolver_conformance.hpp shows how). The kernel is built as
// the runner builds it: {"name": NAME, "eta": η} with every other parameter at its default, for two η.
//
// The checks (each by name), every integral by GSL adaptive quadrature:
//   window_is_even_nonnegative_and_supported: name() and eta() as asked; φ even, non-negative and finite; φ
//     below 1e-15 of its peak beyond support_radius(), which is finite;
//   normalization_is_one: ∫ φ = 1 (2.6);
//   fourier_symbol_matches_quadrature: factor_symbol(ξ) = ∫ φ(t) cos(2πξt) dt, symbol(0) = 1, and the 2D
//     symbol is the product of the factors';
//   bond_integral_matches_quadrature_and_short_bond_limit: (A.1) against ∫₀¹ ψ(s(x − q_k) + (1 − s)(x − q_j)) ds
//     near, across and far from the window; symmetric in the bond's ends; → ψ(x − q) as |q_k − q_j| → 0.
#include <string>
#include <vector>

#include "core/base/registry.hpp"
#include "strategies/conformance/conformance_report.hpp"

namespace closurelab {

// The names of every check, in the order they run.
const std::vector<std::string>& kernel_conformance_checks();

// Runs every check (or only `check`) on the kernel registered as `name`. An unknown name or check is a
// ConfigError; an exception escaping a check is a failure.
ConformanceReport run_kernel_conformance(const Registry& registry, const std::string& name, const std::string& check = "");

}  // namespace closurelab
