// Successive response surface method (SRSM) domain reduction, Stander & Craig (2002), as specified
// in docs/spec.md section 3. Everything is per variable, in unit coordinates.
#include "demfit/rbf_surrogate/srsm.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace demfit::rbf_surrogate {

Box Subregion::box() const { return Box{center - 0.5 * range, center + 0.5 * range}; }

Subregion Subregion::from_box(const Box& box) { return Subregion{box.center(), box.width()}; }

SrsmState srsm_start(const Box& region) {
  validate(region);
  return SrsmState{Subregion::from_box(region), VectorXd()};
}

void validate(const SrsmSettings& s) {
  auto check = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("SRSM settings: ") + what);
  };
  check(std::isfinite(s.eta) && s.eta > 0.0 && s.eta <= 1.0, "eta (zoom factor) must be in (0, 1]");
  check(std::isfinite(s.gamma_osc) && s.gamma_osc > 0.0 && s.gamma_osc <= 1.0,
        "gamma_osc (oscillation contraction) must be in (0, 1]");
  check(std::isfinite(s.gamma_pan) && s.gamma_pan >= s.gamma_osc && s.gamma_pan <= 1.5,
        "gamma_pan (pan factor) must be in [gamma_osc, 1.5]");
}

namespace {

// Centre the subregion on `center`, shrink a side that exceeds the bounds, then shift it inside
// the bounds keeping its size (docs/spec.md 3: "clipped to the bounds").
Subregion place_inside(VectorXd center, VectorXd range, const Box& bounds) {
  range = range.cwiseMin(bounds.width());
  for (Eigen::Index i = 0; i < center.size(); ++i) {
    const double half = 0.5 * range[i];
    center[i] = std::clamp(center[i], bounds.lower[i] + half, bounds.upper[i] - half);
  }
  return Subregion{center, range};
}

}  // namespace

SrsmState srsm_update(const SrsmState& state, const VectorXd& new_optimum, const SrsmSettings& settings,
                      const Box& bounds) {
  validate(settings);
  validate(bounds);
  const auto n = state.region.center.size();
  if (new_optimum.size() != n || state.region.range.size() != n || bounds.dims() != n)
    throw std::invalid_argument("SRSM update: optimum, subregion and bounds have different dimensions");
  const bool first = state.previous_move.size() == 0;
  if (!first && state.previous_move.size() != n)
    throw std::invalid_argument("SRSM update: previous move has the wrong dimension");
  VectorXd move(n), range(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double r = state.region.range[i];
    // d = 2Δx/r in [-1, 1]: 0 at the centre, ±1 on the subregion boundary.
    const double d = r > 0.0 ? std::clamp(2.0 * (new_optimum[i] - state.region.center[i]) / r, -1.0, 1.0) : 0.0;
    // Oscillation indicator ĉ = sign(d_k d_{k-1}) sqrt|d_k d_{k-1}|. At the first update there is
    // no previous move: we take d_0 = 0 (the start region was not reached by a move), so ĉ = 0 and
    // γ = (γ_pan + γ_osc)/2, neither rewarding a pan nor penalising an oscillation that has not
    // been observed.
    const double product = first ? 0.0 : d * state.previous_move[i];
    const double c_hat = (product > 0.0 ? 1.0 : (product < 0.0 ? -1.0 : 0.0)) * std::sqrt(std::abs(product));
    const double gamma = 0.5 * (settings.gamma_pan * (1.0 + c_hat) + settings.gamma_osc * (1.0 - c_hat));
    const double lambda = settings.eta + std::abs(d) * (gamma - settings.eta);
    move[i] = d;
    range[i] = lambda * r;
  }
  return SrsmState{place_inside(new_optimum, range, bounds), move};
}

}  // namespace demfit::rbf_surrogate
