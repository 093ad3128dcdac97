#include "core/base/periodic_fft_2d.hpp"

#include <stdexcept>
#include <unsupported/Eigen/FFT>

namespace closurelab {

using Complex = std::complex<double>;

struct PeriodicFft2D::Plan {
  Eigen::FFT<double> fft;
  std::vector<Complex> in_x, out_x, in_y, out_y;
};

PeriodicFft2D::PeriodicFft2D(int nx, int ny) : plan_(std::make_unique<Plan>()), nx_(nx), ny_(ny) {
  if (nx < 1 || ny < 1) throw std::invalid_argument("periodic FFT: empty mesh");
  plan_->in_x.resize(nx);
  plan_->out_x.resize(nx);
  plan_->in_y.resize(ny);
  plan_->out_y.resize(ny);
}

PeriodicFft2D::~PeriodicFft2D() = default;

namespace {

void check_size(const std::vector<Complex>& f, int nx, int ny) {
  if (f.size() != static_cast<std::size_t>(nx) * ny)
    throw std::invalid_argument("periodic FFT: the field must have one value per node");
}

}  // namespace

void PeriodicFft2D::forward(std::vector<Complex>& f) {
  check_size(f, nx_, ny_);
  Plan& p = *plan_;
  for (int j = 0; j < ny_; ++j) {
    for (int i = 0; i < nx_; ++i) p.in_x[i] = f[static_cast<std::size_t>(j) * nx_ + i];
    p.fft.fwd(p.out_x, p.in_x);
    for (int i = 0; i < nx_; ++i) f[static_cast<std::size_t>(j) * nx_ + i] = p.out_x[i];
  }
  for (int i = 0; i < nx_; ++i) {
    for (int j = 0; j < ny_; ++j) p.in_y[j] = f[static_cast<std::size_t>(j) * nx_ + i];
    p.fft.fwd(p.out_y, p.in_y);
    for (int j = 0; j < ny_; ++j) f[static_cast<std::size_t>(j) * nx_ + i] = p.out_y[j];
  }
}

void PeriodicFft2D::inverse(std::vector<Complex>& f) {
  check_size(f, nx_, ny_);
  Plan& p = *plan_;
  for (int i = 0; i < nx_; ++i) {
    for (int j = 0; j < ny_; ++j) p.in_y[j] = f[static_cast<std::size_t>(j) * nx_ + i];
    p.fft.inv(p.out_y, p.in_y);
    for (int j = 0; j < ny_; ++j) f[static_cast<std::size_t>(j) * nx_ + i] = p.out_y[j];
  }
  for (int j = 0; j < ny_; ++j) {
    for (int i = 0; i < nx_; ++i) p.in_x[i] = f[static_cast<std::size_t>(j) * nx_ + i];
    p.fft.inv(p.out_x, p.in_x);
    for (int i = 0; i < nx_; ++i) f[static_cast<std::size_t>(j) * nx_ + i] = p.out_x[i];
  }
}

}  // namespace closurelab
