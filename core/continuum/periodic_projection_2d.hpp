#pragma once
// The discrete Leray projection of a vector field on a doubly periodic n_x × n_y mesh (flat j · n_x + i), exact in
// Fourier space: for a discrete divergence D v whose symbol on the mode e^{i(θ_x m + θ_y l)} is i (σ_x v̂_x + σ_y v̂_y)
// (σ real: the imaginary part of the discrete ∂_x, ∂_y symbols), each mode loses its part along σ = (σ_x, σ_y), so
// that D(Π v) = 0 to round-off; modes with σ = 0 (the mean, and the Nyquist modes of a central difference) are kept.
// Used by the coarse continuum baseline (central differences) and by the 2D reduced model's incompressible
// equations (the staggered face difference of face-interpolated values, orders 2 and 4).
#include <Eigen/Core>
#include <complex>
#include <memory>
#include <vector>

namespace closurelab {

class PeriodicProjection2D {
 public:
  // sigma_x[m] for m = 0 .. n_x − 1 (θ_x = 2π m / n_x), sigma_y likewise.
  PeriodicProjection2D(std::vector<double> sigma_x, std::vector<double> sigma_y);
  ~PeriodicProjection2D();
  PeriodicProjection2D(const PeriodicProjection2D&) = delete;
  PeriodicProjection2D& operator=(const PeriodicProjection2D&) = delete;

  // v ← Π v. With `potential`, also the φ whose discrete gradient (symbol i σ) was removed, v_in = Π v + G φ.
  void project(Eigen::VectorXd& vx, Eigen::VectorXd& vy, Eigen::VectorXd* potential = nullptr);

  // The symbol of the central difference (f_{m+1} − f_{m−1}) / (2h): sin θ / h, zeroed at the mean and Nyquist.
  static std::vector<double> central_symbol(int n, double h);

 private:
  struct Fft;
  std::unique_ptr<Fft> fft_;
  std::vector<double> sx_, sy_;
};

}  // namespace closurelab
