#pragma once
// The version of the direct SPH engine's results: part of every reference-store key
// (experiments/kinds/reference_store.hpp), so a stored direct run is reused only by the engine that would
// compute the same particles. Bump it in the commit that changes what the direct SPH computes (the pair
// force, the equation of state, the walls, the integrator, the time step, the steady-state test, the scenes'
// lattices or parameters); a change of speed alone keeps it.
namespace closurelab {

inline constexpr int sph_engine_version = 1;

}  // namespace closurelab
