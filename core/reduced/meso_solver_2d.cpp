#include "core/reduced/meso_solver_2d.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "core/averaging/averaging.hpp"
#include "core/base/errors.hpp"
#include "core/base/memory_limit.hpp"
#include "core/closure/reconstruction.hpp"
#include "core/continuum/coarse_navier_stokes_2d.hpp"
#include "core/continuum/continuum_navier_stokes_2d.hpp"
#include "core/reduced/walled_box_2d.hpp"
#include "core/sph/sph_run.hpp"

namespace closurelab {

namespace {

const std::vector<std::string> kXFaceComponents{"xx", "yx"}, kYFaceComponents{"xy", "yy"};

ConfigError under_quadrature(const ConfigError& e) { return ConfigError("/quadrature" + e.path(), e.message()); }

void add_setup(QuadratureCost& total, const QuadratureCost& one) {
  total.bond_weights += one.bond_weights;
  total.sample_points += one.sample_points;
  total.setup_seconds += one.setup_seconds;
}

}  // namespace

void check_meso_solver_2d(const Scene& scene, const AveragingKernel& kernel, const StressQuadrature& quadrature,
                          const MesoSolver2DOptions& o) {
  const TensorMesh2D coarse = continuum_mesh_for(scene, kernel, o.spacing_over_eta);
  if (scene.cavity) check_walled_meso_2d(coarse, o);
  try {
    quadrature.check(scene, scene.cavity ? walled_faces_of(coarse, 0) : x_faces_of(coarse), kXFaceComponents);
    quadrature.check(scene, scene.cavity ? walled_faces_of(coarse, 1) : y_faces_of(coarse), kYFaceComponents);
  } catch (const ConfigError& e) {
    throw under_quadrature(e);
  }
}

void check_meso_run_2d(const Scene& scene, const AveragingKernel& kernel, const json& solver,
                       const MesoSolver2DOptions& o, const std::string& path) {
  const bool convective =
      o.equations == CoarseEquations::mass_momentum || (o.equations == CoarseEquations::incompressible && o.transport);
  if (convective && o.discretization == Discretization::fine_fine)
    throw ConfigError(path + "/equations",
                      name_of(o.equations) +
                          " averages the closure's velocity products with the "
                          "forward operator onto the coarse nodes; the fine_fine operator maps to the "
                          "lattice (use closure.discretization coarse_coarse or coarse_fine)");
  if (o.equations == CoarseEquations::mass_momentum && scene.van_der_waals)
    throw ConfigError(path + "/equations", "mass_momentum takes the weakly compressible equation of state; scene '" +
                                               scene.name + "' has the van der Waals one");
  const TensorMesh2D coarse = continuum_mesh_for(scene, kernel, o.spacing_over_eta);
  const double h = std::min(coarse.x.spacing, coarse.y.spacing);
  check_stepped_run(scene, solver, h, coarse_time_step(o.kappa, scene.rho0, h, scene.max_viscosity(), 0.0), path);
}

MesoSolver2D::MesoSolver2D(const Scene& scene, const AveragingKernel& kernel, Deconvolver& deconvolver,
                           StressQuadrature& on_x_faces, StressQuadrature& on_y_faces, Integrator& integrator,
                           MesoSolver2DOptions options)
    : scene_(scene),
      deconvolver_(deconvolver),
      on_x_faces_(on_x_faces),
      on_y_faces_(on_y_faces),
      integrator_(integrator),
      opt_(std::move(options)) {
  coarse_ = continuum_mesh_for(scene, kernel, opt_.spacing_over_eta);
  if (scene.cavity) {
    check_walled_meso_2d(coarse_, opt_);
    walls_ = std::make_shared<WalledBox2D>(scene, kernel, coarse_, opt_.divergence_order);
    fine_ = walls_->averaging.fluid_lattice;
  } else {
    fine_ = TensorMesh2D{UniformMesh1D::cell_centred(0.0, scene.box.lx, scene.nx, true),
                         UniformMesh1D::cell_centred(0.0, scene.box.ly, scene.ny, true)};
  }
  solution_ = opt_.discretization == Discretization::coarse_coarse ? coarse_ : fine_;
  op_ = make_averaging_operator_2d(kernel, coarse_, fine_, opt_.discretization);
  try {
    deconvolver_.setup(op_);
  } catch (const ConfigError& e) {
    throw ConfigError("/closure/deconvolver" + e.path(), e.message());
  }
  try {
    on_x_faces_.setup(scene, kernel, walls_ ? walled_faces_of(coarse_, 0) : x_faces_of(coarse_), kXFaceComponents);
    on_y_faces_.setup(scene, kernel, walls_ ? walled_faces_of(coarse_, 1) : y_faces_of(coarse_), kYFaceComponents);
  } catch (const ConfigError& e) {
    throw under_quadrature(e);
  }
  add_setup(quad_cost_, on_x_faces_.setup_cost());
  add_setup(quad_cost_, on_y_faces_.setup_cost());
  // ρ̄ (2.8) and F̄ = (2.14) / (2.8) of the lattice: the mass-weighted average of the body force, i.e. the
  // velocity average (2.9) of particles that carry F(q) as their velocity.
  averaged_body_force(scene, kernel, coarse_, fx_, fy_, &rho_bar_);
  lattice_pressure_factor_ = lattice_pressure_factor(scene);
  if (opt_.equations == CoarseEquations::incompressible && !walls_)
    projection_ = std::make_unique<PeriodicProjection2D>(
        divergence_symbol(coarse_.nx(), coarse_.x.spacing, opt_.divergence_order),
        divergence_symbol(coarse_.ny(), coarse_.y.spacing, opt_.divergence_order));
  particle_mass_ = scene.particle_mass();
  vx_ = vy_ = Eigen::VectorXd::Zero(coarse_.size());
}

void MesoSolver2D::set_velocity(const Eigen::VectorXd& vx, const Eigen::VectorXd& vy) {
  if (vx.size() != vx_.size() || vy.size() != vy_.size()) throw ConfigError("", "velocity has the wrong size");
  vx_ = vx;
  vy_ = vy;
  if (projection_) projection_->project(vx_, vy_);
}

bool MesoSolver2D::deconvolve(const Eigen::VectorXd& v, int component, Eigen::VectorXd& x, std::string& issue) {
  const auto t0 = std::chrono::steady_clock::now();
  Eigen::VectorXd b = walls_ ? walls_->averaging.fluid_data(v, component) : v;
  if (opt_.discretization == Discretization::fine_fine) {  // the coarse data interpolated onto the lattice
    std::vector<Vec2> pts(static_cast<std::size_t>(fine_.size()));
    for (int n = 0; n < fine_.size(); ++n) pts[static_cast<std::size_t>(n)] = fine_.node(n);
    b = Reconstruction(coarse_, 2, v).sample(pts);
  }
  const DeconvolutionResult r = deconvolver_.solve(b, opt_.noise_level);
  matvecs_ += r.cost.matvecs;
  choice_.add(r.stats);
  deconvolution_issues_.count(r);
  x = r.x;
  deconv_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!x.allFinite()) {
    issue = "deconvolution returned non-finite values (" + r.stats.message + ")";
    return false;
  }
  return true;
}

bool MesoSolver2D::face_stress(bool closure, bool stress, FaceStress& s, std::string& issue) {
  if ((closure || stress) && (!deconvolve(vx_, 0, s.rx, issue) || !deconvolve(vy_, 1, s.ry, issue))) return false;
  if (!stress) {  // zero on each face mesh (a walled box has one face more than cells along each axis)
    const Eigen::Index n = coarse_.size();
    s.txx = s.tyx = Eigen::VectorXd::Zero(walls_ ? n + coarse_.ny() : n);
    s.txy = s.tyy = Eigen::VectorXd::Zero(walls_ ? n + coarse_.nx() : n);
    return true;
  }
  const VelocitySampler sampler = closure_sampler(s.rx, s.ry);
  const auto t1 = std::chrono::steady_clock::now();
  QuadratureResult on_x = on_x_faces_.evaluate(sampler);
  QuadratureResult on_y = on_y_faces_.evaluate(sampler);
  quad_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  quad_cost_.add(on_x);
  quad_cost_.add(on_y);
  for (const QuadratureResult* r : {&on_x, &on_y})
    if (r->status != Status::converged) {
      issue = r->message;
      return false;
    }
  s.txx = std::move(on_x.stress.at("xx"));
  s.tyx = std::move(on_x.stress.at("yx"));
  s.txy = std::move(on_y.stress.at("xy"));
  s.tyy = std::move(on_y.stress.at("yy"));
  return true;
}

VelocitySampler MesoSolver2D::closure_sampler(const Eigen::VectorXd& rx, const Eigen::VectorXd& ry) const {
  const auto recon_x = std::make_shared<Reconstruction>(solution_, 2, rx);
  const auto recon_y = std::make_shared<Reconstruction>(solution_, 2, ry);
  const Scene* walled = walls_ ? &scene_ : nullptr;  // points in a wall come back at its velocity
  return [recon_x, recon_y, walled](const std::vector<Vec2>& points) {
    Eigen::Matrix2Xd out = sample_pair(*recon_x, *recon_y, points);
    if (walled)
      for (std::size_t k = 0; k < points.size(); ++k)
        if (walled->solid_at(points[k].x(), points[k].y()))
          out.col(static_cast<Eigen::Index>(k)) =
              walled->solid_velocity ? walled->solid_velocity(points[k].x(), points[k].y()) : Vec2(0.0, 0.0);
    return out;
  };
}

bool MesoSolver2D::rate(Eigen::VectorXd& ax, Eigen::VectorXd& ay, std::string& issue) {
  return momentum_rate(RatePart::all, ax, ay, issue);
}

bool MesoSolver2D::momentum_rate(RatePart part, Eigen::VectorXd& ax, Eigen::VectorXd& ay, std::string& issue) {
  if (part == RatePart::nonstiff) {  // the body force alone
    ax = fx_;
    ay = fy_;
    return true;
  }
  FaceStress t;
  if (!face_stress(true, true, t, issue)) return false;
  const Eigen::VectorXd div_x = face_diff(t.txx, 0) + face_diff(t.txy, 1);
  const Eigen::VectorXd div_y = face_diff(t.tyx, 0) + face_diff(t.tyy, 1);
  ax = div_x.cwiseQuotient(rho_bar_);
  ay = div_y.cwiseQuotient(rho_bar_);
  if (part == RatePart::all) {
    ax += fx_;
    ay += fy_;
  }
  return true;
}

void MesoSolver2D::subtract_convective_flux(FaceStress& t) const {
  const int o = opt_.divergence_order;
  const auto [fxx, fxy, fyy] = convective_flux(t);
  t.txx -= to_faces(coarse_, fxx, 0, o);
  t.tyx -= to_faces(coarse_, fxy, 0, o);
  t.txy -= to_faces(coarse_, fxy, 1, o);
  t.tyy -= to_faces(coarse_, fyy, 1, o);
}

std::array<Eigen::VectorXd, 3> MesoSolver2D::convective_flux(const FaceStress& t) const {
  // Φ = ρ̄ [A(V⊗V) − v̄⊗A(V) − A(V)⊗v̄ + 2 v̄⊗v̄] at the centres (ρ̄v̄⊗v̄ − T_c of (2.12), V the closure's velocities).
  const Eigen::VectorXd wx = op_.apply(t.rx), wy = op_.apply(t.ry);
  const auto flux = [&](const Eigen::VectorXd& ra, const Eigen::VectorXd& rb, const Eigen::VectorXd& va,
                        const Eigen::VectorXd& vb, const Eigen::VectorXd& wa, const Eigen::VectorXd& wb) {
    const Eigen::VectorXd q = op_.apply(ra.cwiseProduct(rb));
    return Eigen::VectorXd(rho_bar_.array() * (q.array() - va.array() * wb.array() - wa.array() * vb.array() +
                                               2.0 * va.array() * vb.array()));
  };
  return {flux(t.rx, t.rx, vx_, vx_, wx, wx), flux(t.rx, t.ry, vx_, vy_, wx, wy), flux(t.ry, t.ry, vy_, vy_, wy, wy)};
}

bool MesoSolver2D::incompressible_rate(RatePart part, Eigen::VectorXd& ax, Eigen::VectorXd& ay, std::string& issue) {
  const bool stress = part != RatePart::nonstiff;
  const bool explicit_terms = part != RatePart::stiff, convective = opt_.transport && explicit_terms;
  FaceStress t;
  if (!face_stress(convective, stress, t, issue)) return false;
  Eigen::VectorXd cx = Eigen::VectorXd::Zero(vx_.size()), cy = cx;  // the walls' constraint forces
  if (walls_) {
    if (!add_wall_terms(convective, stress, t, cx, cy, issue)) return false;
  } else if (convective) {
    subtract_convective_flux(t);
  }
  ax = (face_diff(t.txx, 0) + face_diff(t.txy, 1) + cx).cwiseQuotient(rho_bar_);
  ay = (face_diff(t.tyx, 0) + face_diff(t.tyy, 1) + cy).cwiseQuotient(rho_bar_);
  if (explicit_terms) {
    ax += fx_;
    ay += fy_;
  }
  if (walls_)
    walls_->projection.project(ax, ay);
  else
    projection_->project(ax, ay);
  return true;
}

bool MesoSolver2D::conservative_rate(RatePart part, const Eigen::VectorXd& u, Eigen::VectorXd& dudt,
                                     std::string& issue) {
  const Eigen::Index n = vx_.size();
  const Eigen::VectorXd mx = u.segment(0, n), my = u.segment(n, n);
  rho_bar_ = u.segment(2 * n, n);
  if (!(rho_bar_.array() > 0.0).all()) {
    issue = "the coarse density is not positive at every node";
    return false;
  }
  vx_ = mx.cwiseQuotient(rho_bar_);
  vy_ = my.cwiseQuotient(rho_bar_);
  const bool explicit_terms = part != RatePart::stiff, transport = opt_.transport && explicit_terms;
  FaceStress t;
  if (!face_stress(transport, part != RatePart::nonstiff, t, issue)) return false;
  const int o = opt_.divergence_order;
  const auto faces = [&](const Eigen::VectorXd& c, int axis) { return to_faces(coarse_, c, axis, o); };
  Eigen::VectorXd drho = Eigen::VectorXd::Zero(n);
  if (transport) {
    subtract_convective_flux(t);
    drho = -(face_diff(faces(mx, 0), 0) + face_diff(faces(my, 1), 1));
  }
  if (opt_.coarse_pressure && explicit_terms) {
    Eigen::VectorXd p(n);
    for (Eigen::Index k = 0; k < n; ++k)
      p[k] = -lattice_pressure_factor_ * scene_.pressure(rho_bar_[k] / particle_mass_, particle_mass_);
    t.txx += faces(p, 0);
    t.tyy += faces(p, 1);
  }
  dudt.resize(3 * n);
  dudt.segment(0, n) = face_diff(t.txx, 0) + face_diff(t.txy, 1);
  dudt.segment(n, n) = face_diff(t.tyx, 0) + face_diff(t.tyy, 1);
  if (explicit_terms) {
    dudt.segment(0, n) += rho_bar_.cwiseProduct(fx_);
    dudt.segment(n, n) += rho_bar_.cwiseProduct(fy_);
  }
  dudt.segment(2 * n, n) = drho;
  return true;
}

bool MesoSolver2D::step(double dt, std::string& issue) {
  const Eigen::Index n = vx_.size();
  if (opt_.equations == CoarseEquations::mass_momentum) {  // u = (ρ̄v̄_x, ρ̄v̄_y, ρ̄)
    const auto part = [&](RatePart p) {
      return [this, p](const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string& why) {
        return conservative_rate(p, u, dudt, why);
      };
    };
    CoarseRate f{part(RatePart::all)};
    f.stiff = part(RatePart::stiff);
    f.nonstiff = part(RatePart::nonstiff);
    Eigen::VectorXd u(3 * n);
    u << rho_bar_.cwiseProduct(vx_), rho_bar_.cwiseProduct(vy_), rho_bar_;
    const bool ok = integrator_.step(f, dt, u, issue);
    rho_bar_ = u.segment(2 * n, n);
    vx_ = u.segment(0, n).cwiseQuotient(rho_bar_);
    vy_ = u.segment(n, n).cwiseQuotient(rho_bar_);
    return ok;
  }
  // The state u = (v̄_x, v̄_y), its rate (∂_t v̄_x, ∂_t v̄_y); no node is held (doubly periodic).
  const bool incompressible = opt_.equations == CoarseEquations::incompressible;
  const auto part = [&](RatePart p) {
    return [this, p, n, incompressible](const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string& why) {
      vx_ = u.head(n);
      vy_ = u.tail(n);
      Eigen::VectorXd ax, ay;
      if (!(incompressible ? incompressible_rate(p, ax, ay, why) : momentum_rate(p, ax, ay, why))) return false;
      dudt.resize(2 * n);
      dudt << ax, ay;
      return true;
    };
  };
  CoarseRate f{part(RatePart::all)};
  f.stiff = part(RatePart::stiff);
  f.nonstiff = part(RatePart::nonstiff);
  Eigen::VectorXd u(2 * n);
  u << vx_, vy_;
  const bool ok = integrator_.step(f, dt, u, issue);
  vx_ = u.head(n);
  vy_ = u.tail(n);
  return ok;
}

double MesoSolver2D::time_step() const {
  // (5.21)–(5.22) with the smaller spacing and the largest speed; ρ0 as the 1D model takes it.
  // Under mass_momentum the signal speed is the sound speed plus the largest speed.
  const double speed = (vx_.array().square() + vy_.array().square()).sqrt().maxCoeff() +
                       (opt_.equations == CoarseEquations::mass_momentum ? scene_.sound_speed : 0.0);
  return coarse_time_step(opt_.kappa, scene_.rho0, std::min(coarse_.x.spacing, coarse_.y.spacing),
                          scene_.max_viscosity(), speed);
}

MesoResult2D MesoSolver2D::run() {
  SteppedModel model;
  model.name = "reduced model (2D)";
  model.time_step = [&] { return time_step(); };
  model.step = [&](double dt, std::string& issue) { return step(dt, issue); };
  model.observe = [&] {
    Eigen::VectorXd o(2 * vx_.size());
    o << vx_, vy_;
    return o;
  };
  model.check_state = [&](std::string& issue) {
    const bool finite = vx_.allFinite() && vy_.allFinite();
    return coarse_state_ok(finite, finite ? std::max(vx_.cwiseAbs().maxCoeff(), vy_.cwiseAbs().maxCoeff()) : 0.0,
                           scene_.analytic_peak, opt_.divergence_factor, issue);
  };
  if (opt_.on_snapshot) model.snapshot = [&](double t) { opt_.on_snapshot(t, vx_, vy_); };
  model.describe = [&] {
    std::ostringstream os;
    os << "max|v_x| = " << vx_.cwiseAbs().maxCoeff();
    return os.str();
  };
  MesoResult2D res;
  static_cast<TimeLoopResult&>(res) = run_time_loop(model, opt_);
  res.mesh = coarse_;
  res.vx = vx_;
  res.vy = vy_;
  res.deconvolution_matvecs = matvecs_;
  res.parameter_choice = choice_;
  res.deconvolution_issues = deconvolution_issues_;
  res.deconvolution_seconds = deconv_seconds_;
  res.quadrature_seconds = quad_seconds_;
  res.quadrature_cost = quad_cost_;
  return res;
}

}  // namespace closurelab
