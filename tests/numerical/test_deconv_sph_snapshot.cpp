// Real data for the deconvolution suite: the Gaussian averages of a direct-SPH velocity snapshot,
// deconvolved back to the particle rows. The averages (2.9) of an x-invariant snapshot are exactly the
// coarse–fine operator applied to the row velocities (plus the lattice ripple), so the strategies must
// recover the rows far better than the zero-order closure (the averages themselves) does.
#include <gtest/gtest.h>

#include <cmath>

#include "core/averaging/averaging.hpp"
#include "core/closure/deconvolver.hpp"
#include "core/closure/forward_operator.hpp"
#include "core/closure/reconstruction.hpp"
#include "core/base/registry.hpp"
#include "core/sph/scene.hpp"
#include "core/sph/sph_run.hpp"

using namespace closurelab;

TEST(DeconvolutionOfSphData, RecoversParticleRowsFromTheirAverages) {
  const Registry& reg = builtin_registry();
  const auto scene = reg.scenes.create(json{{"name", "poiseuille-periodic"}, {"n_y", 48}}, "/scene");
  ParticleSystem ps = scene->make_particles();
  SphRunOptions opt;
  opt.to_steady_state = false;
  opt.target_time = 1.0;
  ASSERT_EQ(run_direct_sph(*scene, ps, opt).status, Status::target_time);

  const auto kernel = reg.kernels.create(json{{"name", "gaussian"}, {"eta", scene->eta}}, "/kernel");
  const UniformMesh1D coarse = UniformMesh1D::cell_centred(0.0, 1.0, 32, false);  // spacing η'/2
  const UniformMesh1D fine = UniformMesh1D::cell_centred(0.0, 1.0, scene->ny, false);  // the particle rows
  const TensorMesh2D column{UniformMesh1D{0.0, scene->box.lx, 1, true, scene->box.lx}, coarse};
  const Eigen::VectorXd b = average_particles(ps, scene->box, *kernel, column, AveragingRequest{}).vx;

  // The truth: the mean velocity of each particle row (walls at rest).
  Eigen::VectorXd rows = Eigen::VectorXd::Zero(scene->ny);
  for (std::size_t a = 0; a < ps.size(); ++a)
    rows[static_cast<Eigen::Index>(std::floor(ps.y[a] / scene->dx))] += ps.vx[a] / scene->nx;
  std::vector<Vec2> row_points;
  for (int j = 0; j < fine.count; ++j) row_points.emplace_back(fine.node(j), 0.0);
  const double scale = rows.cwiseAbs().maxCoeff();
  const TensorMesh2D coarse_line{coarse, UniformMesh1D{0.0, 1.0, 1, false, 0.0}};
  const double zero_order = (Reconstruction(coarse_line, 1, b).sample(row_points) - rows).cwiseAbs().maxCoeff() / scale;

  const ForwardOperator a = make_averaging_operator_1d(*kernel, coarse, fine, Discretization::coarse_fine);
  std::cout << "zero-order (the averages) max row error " << zero_order << "\n";
  for (const json& cfg : {json{{"name", "tikhonov"}, {"rule", "gcv"}}, json{{"name", "tsvd"}, {"rule", "gcv"}},
                          json{{"name", "tikhonov"}, {"rule", "lcurve"}}, json{{"name", "cgls"}, {"iterations", 30}}}) {
    auto d = reg.deconvolvers.create(cfg, "/deconvolver");
    d->setup(a);
    const DeconvolutionResult r = d->solve(b);
    ASSERT_TRUE(r.x.allFinite()) << cfg.dump();
    const double err = (r.x - rows).cwiseAbs().maxCoeff() / scale;
    std::cout << cfg.dump() << ": max row error " << err << " (parameter " << r.stats.chosen_parameter << ")\n";
    EXPECT_LT(err, 0.5 * zero_order) << cfg.dump();
  }
}
