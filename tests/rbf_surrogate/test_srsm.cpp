// SRSM limiting cases from the update formulas of docs/spec.md section 3 (Stander & Craig 2002).
#include "demfit/rbf_surrogate/srsm.hpp"

#include <catch2/catch.hpp>

using namespace demfit::rbf_surrogate;

namespace {

SrsmState state_at(double center, double range, int dims, VectorXd previous = VectorXd()) {
  return SrsmState{Subregion{VectorXd::Constant(dims, center), VectorXd::Constant(dims, range)}, previous};
}

}  // namespace

TEST_CASE("SRSM zooms by eta when the optimum is at the centre", "[rbf_surrogate][srsm]") {
  // d = 0 => lambda = eta regardless of the oscillation history.
  const SrsmSettings s;
  for (VectorXd prev : {VectorXd(), VectorXd(VectorXd::Constant(2, 1.0)), VectorXd(VectorXd::Constant(2, -0.5))}) {
    const SrsmState st = srsm_update(state_at(0.5, 0.4, 2, prev), VectorXd::Constant(2, 0.5), s, Box::unit(2));
    CHECK((st.region.range - VectorXd::Constant(2, 0.4 * s.eta)).norm() < 1e-15);
    CHECK((st.region.center - VectorXd::Constant(2, 0.5)).norm() < 1e-15);
    CHECK(st.previous_move.norm() == 0.0);
  }
}

TEST_CASE("SRSM pans without contraction on a consistent move to the boundary", "[rbf_surrogate][srsm]") {
  // d_k = d_{k-1} = 1 => c = 1, gamma = gamma_pan, lambda = gamma_pan = 1: size kept, centre moved.
  SrsmSettings s;
  const SrsmState st =
      srsm_update(state_at(0.4, 0.2, 2, VectorXd::Constant(2, 1.0)), VectorXd::Constant(2, 0.5), s, Box::unit(2));
  CHECK((st.region.range - VectorXd::Constant(2, 0.2)).norm() < 1e-15);
  CHECK((st.region.center - VectorXd::Constant(2, 0.5)).norm() < 1e-15);
  CHECK((st.previous_move - VectorXd::Constant(2, 1.0)).norm() < 1e-15);
  // A pan factor > 1 enlarges (gamma_pan = 1.2 => lambda = 1.2).
  s.gamma_pan = 1.2;
  const SrsmState big =
      srsm_update(state_at(0.4, 0.2, 2, VectorXd::Constant(2, 1.0)), VectorXd::Constant(2, 0.5), s, Box::unit(2));
  CHECK(big.region.range[0] == Approx(0.24).epsilon(1e-14));
}

TEST_CASE("SRSM contracts by gamma_osc when the move reverses at the boundary", "[rbf_surrogate][srsm]") {
  // d_k = -1, d_{k-1} = +1 => c = -1, gamma = gamma_osc, lambda = gamma_osc.
  const SrsmSettings s{1.0, 0.5, 0.7};
  const SrsmState st =
      srsm_update(state_at(0.5, 0.2, 1, VectorXd::Constant(1, 1.0)), VectorXd::Constant(1, 0.4), s, Box::unit(1));
  CHECK(st.region.range[0] == Approx(0.2 * 0.5).epsilon(1e-14));
  // Intermediate case against the formulas evaluated by hand: d = 0.5, d_prev = -0.5
  // => c = -0.5, gamma = 0.5(1*0.5 + 0.5*1.5) = 0.625, lambda = 0.7 + 0.5(0.625 - 0.7) = 0.6625.
  const SrsmState mid =
      srsm_update(state_at(0.5, 0.2, 1, VectorXd::Constant(1, -0.5)), VectorXd::Constant(1, 0.55), s, Box::unit(1));
  CHECK(mid.region.range[0] == Approx(0.2 * 0.6625).epsilon(1e-13));
}

TEST_CASE("SRSM first update uses a neutral oscillation indicator", "[rbf_surrogate][srsm]") {
  // No previous move: c = 0, gamma = (gamma_pan + gamma_osc)/2 = 0.8; boundary move d = 1 => lambda = 0.8.
  const SrsmState st = srsm_update(srsm_start(Box::unit(1)), VectorXd::Constant(1, 1.0), {}, Box::unit(1));
  CHECK(st.region.range[0] == Approx(0.8).epsilon(1e-14));
}

TEST_CASE("SRSM subregion is shifted inside the bounds keeping its size", "[rbf_surrogate][srsm]") {
  const SrsmSettings s;
  const Box bounds = Box::unit(2);
  const SrsmState st =
      srsm_update(state_at(0.85, 0.3, 2, VectorXd::Constant(2, 1.0)), VectorXd::Constant(2, 1.0), s, bounds);
  // lambda = 1 (consistent boundary move): size 0.3 kept, centred on 1.0 would leave the bounds.
  CHECK(st.region.range[0] == Approx(0.3));
  CHECK(st.region.center[0] == Approx(0.85));
  CHECK(bounds.contains(st.region.box().lower, 1e-15));
  CHECK(bounds.contains(st.region.box().upper, 1e-15));
  // A subregion larger than the bounds is cut to the bounds.
  SrsmSettings pan;
  pan.gamma_pan = 1.5;
  const SrsmState wide =
      srsm_update(state_at(0.5, 0.9, 1, VectorXd::Constant(1, 1.0)), VectorXd::Constant(1, 0.95), pan, Box::unit(1));
  CHECK(wide.region.range[0] == Approx(1.0));
  CHECK(wide.region.center[0] == Approx(0.5));
}

TEST_CASE("SRSM settings are validated", "[rbf_surrogate][srsm]") {
  CHECK_THROWS_WITH(validate(SrsmSettings{1.0, 0.6, 0.0}), Catch::Contains("eta"));
  CHECK_THROWS_WITH(validate(SrsmSettings{0.5, 0.6, 0.6}), Catch::Contains("gamma_pan"));
}
