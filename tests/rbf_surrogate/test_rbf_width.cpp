// Width selection on Franke's function (Rippa 1999 leave-one-out; GCV).
#include "demfit/rbf_surrogate/design.hpp"
#include "demfit/rbf_surrogate/rbf_network.hpp"
#include "test_functions.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace demfit::rbf_surrogate;

namespace {

struct FrankeSetup {
  MatrixXd x, y;
  FrankeSetup() : x(latin_hypercube_maximin(60, 2, 2024, Box::unit(2))), y(60, 1) {
    for (int i = 0; i < 60; ++i) y(i, 0) = testfn::franke(x(i, 0), x(i, 1));
  }
};

// RMS error against the true function on a 50x50 grid over [0,1]^2.
double grid_rms(const RbfNetwork& net) {
  double sum = 0.0;
  for (int i = 0; i < 50; ++i)
    for (int j = 0; j < 50; ++j) {
      VectorXd p(2);
      p << i / 49.0, j / 49.0;
      sum += std::pow(net.predict(p)[0] - testfn::franke(p[0], p[1]), 2);
    }
  return std::sqrt(sum / 2500.0);
}

double franke_range() {
  double lo = 1e9, hi = -1e9;
  for (int i = 0; i < 200; ++i)
    for (int j = 0; j < 200; ++j) {
      const double f = testfn::franke(i / 199.0, j / 199.0);
      lo = std::min(lo, f);
      hi = std::max(hi, f);
    }
  return hi - lo;
}

}  // namespace

TEST_CASE("Leave-one-out width on Franke with 60 LHS points gives RMS error below 2 % of the range",
          "[rbf_surrogate][rbf]") {
  const FrankeSetup s;
  const RbfNetwork net = RbfNetwork::fit(s.x, s.y);
  const double rms = grid_rms(net), range = franke_range();
  INFO("width " << net.width() << " rms " << rms << " range " << range << " loo " << net.loo_rms()[0]);
  CHECK(rms < 0.02 * range);
}

TEST_CASE("GCV width on Franke with 60 LHS points gives RMS error below 2 % of the range", "[rbf_surrogate][rbf]") {
  const FrankeSetup s;
  RbfOptions o;
  o.criterion = WidthCriterion::gcv;
  const RbfNetwork net = RbfNetwork::fit(s.x, s.y, o);
  const double rms = grid_rms(net), range = franke_range();
  INFO("width " << net.width() << " rms " << rms << " range " << range);
  CHECK(rms < 0.02 * range);
}

TEST_CASE("Width chosen by leave-one-out is within a factor 2 of the test-error-optimal width",
          "[rbf_surrogate][rbf]") {
  // Scan: the true grid error over 40 log-spaced widths; its minimiser is the reference.
  const FrankeSetup s;
  for (Basis basis : {Basis::multiquadric, Basis::gaussian}) {
    RbfOptions o;
    o.basis = basis;
    const RbfNetwork chosen = RbfNetwork::fit(s.x, s.y, o);
    double best_width = 0.0, best_error = 1e300;
    for (int k = 0; k < 40; ++k) {
      RbfOptions f = o;
      f.fixed_width = 0.01 * std::pow(10.0, 2.5 * k / 39.0);
      double e = 1e300;
      try {
        e = grid_rms(RbfNetwork::fit(s.x, s.y, f));
      } catch (const std::invalid_argument&) {  // numerically singular width: not a candidate
      }
      if (e < best_error) {
        best_error = e;
        best_width = *f.fixed_width;
      }
    }
    INFO("basis " << static_cast<int>(basis) << " loo width " << chosen.width() << " best width " << best_width
                  << " error at loo width " << grid_rms(chosen) << " best error " << best_error);
    CHECK(chosen.width() > 0.5 * best_width);
    CHECK(chosen.width() < 2.0 * best_width);
  }
}
