#include "core/closure/deconvolver.hpp"
#include "strategies/deconvolution/deconvolvers.hpp"
#include "strategies/register_builtin.hpp"

namespace closurelab {

void register_deconvolvers(Registry& r) {
  r.deconvolvers.add({"landweber", "Landweber series of order n, x_n = sum_{k<=n} (I - A)^k b, (4.3)/(4.9); square A, or any A with lift = interpolation",
                      landweber_series_schema()},
                     make_landweber_series);
  r.deconvolvers.add({"landweber_relaxed", "relaxed Landweber x_{k+1} = x_k + omega A'(b - A x_k), any A",
                      landweber_relaxed_schema()},
                     make_landweber_relaxed);
  r.deconvolvers.add({"tikhonov", "Tikhonov (4.7): (A + alpha C)x = b or min ||Ax - b||^2 + alpha ||Lx||^2, C = I or L'L",
                      tikhonov_schema()},
                     make_tikhonov);
  r.deconvolvers.add({"tsvd", "truncated SVD by index or threshold; Kronecker SVD on tensor meshes", tsvd_schema()},
                     make_tsvd);
  r.deconvolvers.add({"cg", "conjugate gradients on a symmetric positive definite A (refuses otherwise)", cg_schema()},
                     make_cg);
  r.deconvolvers.add({"cgls", "conjugate gradients on the normal equations (any A)", cgls_schema()}, make_cgls);
}

}  // namespace closurelab
