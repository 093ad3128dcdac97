// The 2D force-density model marched in time (core/reduced/force_density_2d.hpp): the stacked state
// z = (v̄_x, v̄_y, n̄) on the free nodes advanced by the model's Integrator with the closure applied at every rate
// evaluation, by the shared time loop (core/base/time_loop.hpp).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/reduced/force_density_2d.hpp"

namespace closurelab {

bool ForceDensitySolver2D::stacked_rate(RatePart part, const Eigen::VectorXd& u, Eigen::VectorXd& dudt,
                                        std::string& issue) {
  const Eigen::Index f = static_cast<Eigen::Index>(free_.size());
  vx_ = u.segment(0, f);
  vy_ = u.segment(f, f);
  n_ = u.segment(2 * f, f);
  ++rate_evaluations_;
  Eigen::VectorXd rx, ry, rn;
  if (!deconvolve(velocity_, vx_, rx, issue) || !deconvolve(velocity_, vy_, ry, issue) ||
      !deconvolve(density_, n_, rn, issue))
    return false;
  Eigen::VectorXd ax, ay, an;
  if (part == RatePart::all) {
    rates_from_reconstruction(rx, ry, rn, ax, ay, an);
  } else if (part == RatePart::stiff) {  // the pair forces' linear maps
    ax = viscous_ * rx + pressure_x_ * rn;
    ay = viscous_ * ry + pressure_y_ * rn;
    an = continuity_x_ * rx + continuity_y_ * ry;
  } else {  // the body force and the convective flux
    ax = body_x_;
    ay = body_y_;
    an = Eigen::VectorXd::Zero(coarse_.size());
    if (opt_.convective_stress) {
      Eigen::VectorXd qx, qy;
      convective_rates(rx, ry, qx, qy);
      ax += qx;
      ay += qy;
    }
  }
  dudt.resize(3 * f);
  dudt << on_free(ax), on_free(ay), on_free(an);
  if (!dudt.allFinite()) {
    issue = "the rate is not finite";
    return false;
  }
  return true;
}

bool ForceDensitySolver2D::step(double dt, std::string& issue) {
  const auto part = [this](RatePart p) {
    return [this, p](const Eigen::VectorXd& u, Eigen::VectorXd& dudt, std::string& why) {
      return stacked_rate(p, u, dudt, why);
    };
  };
  CoarseRate rate{part(RatePart::all)};  // no entry held: the state is the free nodes'
  rate.stiff = part(RatePart::stiff);
  rate.nonstiff = part(RatePart::nonstiff);
  const Eigen::Index f = static_cast<Eigen::Index>(free_.size());
  Eigen::VectorXd u(3 * f);
  u << vx_, vy_, n_;
  const bool ok = stepper_->step(rate, dt, u, issue);
  vx_ = u.segment(0, f);
  vy_ = u.segment(f, f);
  n_ = u.segment(2 * f, f);
  return ok;
}

double ForceDensitySolver2D::time_step() const {
  const double speed = std::sqrt((vx_.array().square() + vy_.array().square()).maxCoeff());
  const double spacing = coarse_.nx() == 1 ? coarse_.y.spacing : std::min(coarse_.x.spacing, coarse_.y.spacing);
  return coarse_time_step(opt_.kappa, scene_.rho0, spacing, scene_.max_viscosity(), speed + scene_.sound_speed);
}

void ForceDensitySolver2D::march(ForceDensity2DResult& res) {
  SteppedModel model;
  model.name = "reduced model (2D force density)";
  model.time_step = [this] { return time_step(); };
  model.step = [this](double dt, std::string& issue) { return step(dt, issue); };
  model.observe = [this] {
    Eigen::VectorXd o(vx_.size() + vy_.size());
    o << vx_, vy_;
    return o;
  };
  model.check_state = [this](std::string& issue) {
    const bool finite = vx_.allFinite() && vy_.allFinite() && n_.allFinite();
    const double peak = finite ? std::max(vx_.cwiseAbs().maxCoeff(), vy_.cwiseAbs().maxCoeff()) : 0.0;
    return coarse_state_ok(finite, peak, scene_.analytic_peak, 1e3, issue);
  };
  model.describe = [this] {
    std::ostringstream os;
    os << "max|v_x| = " << vx_.cwiseAbs().maxCoeff() << ", " << rate_evaluations_ << " rate evaluations";
    return os.str();
  };
  static_cast<TimeLoopResult&>(res) = run_time_loop(model, opt_);
}

}  // namespace closurelab
