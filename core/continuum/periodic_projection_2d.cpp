#include "core/continuum/periodic_projection_2d.hpp"

#include <cmath>
#include <stdexcept>

#include "core/base/periodic_fft_2d.hpp"

namespace closurelab {

using Complex = std::complex<double>;

// The 2D transform of a real field (flat j · nx + i) and the real part of an inverse.
struct PeriodicProjection2D::Fft {
  PeriodicFft2D fft;
  std::vector<Complex> hx, hy, phi;

  Fft(int nx, int ny) : fft(nx, ny) {}
  int nx() const { return fft.nx(); }
  int ny() const { return fft.ny(); }

  void forward(const Eigen::VectorXd& f, std::vector<Complex>& hat) {
    hat.assign(f.data(), f.data() + f.size());
    fft.forward(hat);
  }

  // The real part of the inverse transform (scaled: inverse(forward(f)) = f).
  void inverse(std::vector<Complex>& hat, Eigen::VectorXd& f) {
    fft.inverse(hat);
    f.resize(static_cast<Eigen::Index>(hat.size()));
    for (std::size_t k = 0; k < hat.size(); ++k) f[static_cast<Eigen::Index>(k)] = hat[k].real();
  }
};

PeriodicProjection2D::PeriodicProjection2D(std::vector<double> sigma_x, std::vector<double> sigma_y)
    : sx_(std::move(sigma_x)), sy_(std::move(sigma_y)) {
  if (sx_.empty() || sy_.empty()) throw std::invalid_argument("periodic projection: empty mesh");
  fft_ = std::make_unique<Fft>(static_cast<int>(sx_.size()), static_cast<int>(sy_.size()));
}

PeriodicProjection2D::~PeriodicProjection2D() = default;

std::vector<double> PeriodicProjection2D::central_symbol(int n, double h) {
  std::vector<double> s(static_cast<size_t>(n));
  for (int m = 0; m < n; ++m) s[m] = std::sin(2.0 * M_PI * m / n) / h;
  // Central-difference modes at the Nyquist index have sin θ = 0 exactly in exact arithmetic; make it so.
  if (n % 2 == 0) s[n / 2] = 0.0;
  s[0] = 0.0;
  return s;
}

void PeriodicProjection2D::project(Eigen::VectorXd& vx, Eigen::VectorXd& vy, Eigen::VectorXd* potential) {
  Fft& f = *fft_;
  if (vx.size() != static_cast<Eigen::Index>(f.nx()) * f.ny() || vy.size() != vx.size())
    throw std::invalid_argument("periodic projection: the field must have one value per node");
  f.forward(vx, f.hx);
  f.forward(vy, f.hy);
  if (potential) f.phi.assign(f.hx.size(), Complex(0.0, 0.0));
  for (int j = 0; j < f.ny(); ++j)
    for (int i = 0; i < f.nx(); ++i) {
      const double dx = sx_[i], dy = sy_[j], d2 = dx * dx + dy * dy;
      if (d2 == 0.0) continue;  // no discrete divergence to remove
      const size_t k = static_cast<size_t>(j) * f.nx() + i;
      const Complex s = (dx * f.hx[k] + dy * f.hy[k]) / d2;
      f.hx[k] -= dx * s;
      f.hy[k] -= dy * s;
      if (potential) f.phi[k] = Complex(0.0, -1.0) * s;
    }
  f.inverse(f.hx, vx);
  f.inverse(f.hy, vy);
  if (potential) f.inverse(f.phi, *potential);
}

}  // namespace closurelab
