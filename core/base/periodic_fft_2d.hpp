#pragma once
// The 2D discrete Fourier transform of a complex field on a doubly periodic n_x × n_y mesh (flat j · n_x + i), by
// 1D transforms (Eigen's FFT) along x, then along y; the inverse is scaled so that inverse(forward(f)) = f. Shared by
// the discrete Leray projection (core/continuum/periodic_projection_2d.hpp) and the coarse stress quadrature's
// periodic convolution (strategies/quadrature/coarse_quadrature.hpp). Not thread-safe: one instance per user.
#include <complex>
#include <memory>
#include <vector>

namespace closurelab {

class PeriodicFft2D {
 public:
  PeriodicFft2D(int nx, int ny);
  ~PeriodicFft2D();
  PeriodicFft2D(const PeriodicFft2D&) = delete;
  PeriodicFft2D& operator=(const PeriodicFft2D&) = delete;

  // In place; `field` must hold n_x · n_y values (std::invalid_argument otherwise).
  void forward(std::vector<std::complex<double>>& field);
  void inverse(std::vector<std::complex<double>>& field);
  int nx() const { return nx_; }
  int ny() const { return ny_; }

 private:
  struct Plan;
  std::unique_ptr<Plan> plan_;
  int nx_, ny_;
};

}  // namespace closurelab
