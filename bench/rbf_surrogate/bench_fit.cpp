// Cost of RBF fits and predictions versus the number of outputs: a 200-point curve shares one
// factorisation per trial width, so it should cost little more than a scalar response.
// Prints times and the ratio curve/scalar for n = 50, 100, 200, 400 points in 6 dimensions.
#include "demfit/rbf_surrogate/design.hpp"
#include "demfit/rbf_surrogate/rbf_network.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>

using namespace demfit::rbf_surrogate;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

MatrixXd curves(const MatrixXd& x, int m) {
  MatrixXd y(x.rows(), m);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    for (int j = 0; j < m; ++j) {
      const double t = m > 1 ? j / double(m - 1) : 0.5;
      y(i, j) = std::sin(4 * t * (0.5 + x(i, 0))) * (1 + x(i, 1) * x(i, 2)) + t * x(i, 3) + x(i, 4) * x(i, 5);
    }
  return y;
}

}  // namespace

int main() {
  std::printf("%6s %12s %12s %8s %16s %16s\n", "points", "fit_m1_s", "fit_m200_s", "ratio", "predict_m200_us",
              "gradient_m200_us");
  for (int n : {50, 100, 200, 400}) {
    const MatrixXd x = latin_hypercube_maximin(n, 6, 1, Box::unit(6));
    const MatrixXd y1 = curves(x, 1), y200 = curves(x, 200);
    auto t0 = std::chrono::steady_clock::now();
    const RbfNetwork scalar = RbfNetwork::fit(x, y1);
    const double t1 = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    const RbfNetwork curve = RbfNetwork::fit(x, y200);
    const double t200 = seconds_since(t0);
    const VectorXd p = VectorXd::Constant(6, 0.4);
    double sink = 0.0;
    const int reps = 2000;
    t0 = std::chrono::steady_clock::now();
    for (int r = 0; r < reps; ++r) sink += curve.predict(p)[r % 200];
    const double tp = seconds_since(t0) / reps * 1e6;
    t0 = std::chrono::steady_clock::now();
    for (int r = 0; r < reps; ++r) sink += curve.gradient(p)(r % 200, 0);
    const double tg = seconds_since(t0) / reps * 1e6;
    std::printf("%6d %12.4f %12.4f %8.2f %16.1f %16.1f\n", n, t1, t200, t200 / t1, tp, tg);
    if (sink == 12345.678) std::printf("(unlikely)\n");
    (void)scalar;
  }
  return 0;
}
