#pragma once
// Factories and parameter schemas of the built-in deconvolvers (registered in register_deconvolvers.cpp).
// Each factory takes the resolved JSON of its schema.
#include <memory>

#include "core/closure/deconvolver.hpp"
#include "core/base/params.hpp"

namespace closurelab {

ParamSchema landweber_series_schema();
std::unique_ptr<Deconvolver> make_landweber_series(const json& p);    // (4.3)/(4.9)
ParamSchema landweber_relaxed_schema();
std::unique_ptr<Deconvolver> make_landweber_relaxed(const json& p);   // x_{k+1} = x_k + ω Aᵀ(b − A x_k)
ParamSchema tikhonov_schema();
std::unique_ptr<Deconvolver> make_tikhonov(const json& p);            // (4.7) and its least-squares form
ParamSchema tsvd_schema();
std::unique_ptr<Deconvolver> make_tsvd(const json& p);                // truncated SVD (§4.2)
ParamSchema cg_schema();
std::unique_ptr<Deconvolver> make_cg(const json& p);                  // CG on symmetric positive definite A
ParamSchema cgls_schema();
std::unique_ptr<Deconvolver> make_cgls(const json& p);                // CG on the normal equations

}  // namespace closurelab
