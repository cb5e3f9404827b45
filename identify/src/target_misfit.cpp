// Misfit figures of the best run for the report (see target_misfit.hpp).
#include "target_misfit.hpp"

#include <algorithm>
#include <cmath>

#include "demfit/identify/objective.hpp"
#include "demfit/imaging/profile_metrics.hpp"

namespace demfit::identify::detail {
namespace {

double target_scale(const TargetSpec& t) {
  double gmax = 0.0;
  for (double y : t.data.y) gmax = std::max(gmax, std::abs(y));
  return t.scale > 0.0 ? t.scale : (gmax > 0.0 ? gmax : 1.0);
}

// The imaging metrics are integrals of z differences over x: they hold in any consistent units,
// so the curves are passed in their own (x_mm, z_mm -> mm and mm^2).
imaging::SurfaceProfile as_profile(const Curve& curve) {
  imaging::SurfaceProfile profile;
  std::vector<std::size_t> order(curve.x.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return curve.x[a] < curve.x[b]; });
  for (std::size_t i : order) {
    profile.x.push_back(curve.x[i]);
    profile.z.push_back(curve.y[i]);
  }
  return profile;
}

TargetMisfit misfit(const TargetSpec& t, const Curve& simulated) {
  TargetMisfit m;
  if (t.metric == CurveMetric::profile_area) {
    const imaging::SurfaceProfile a = as_profile(simulated), b = as_profile(t.data);
    m.rms = imaging::profile_rms_distance(a, b);
    m.area = imaging::profile_differing_area(a, b);
  } else if (t.metric == CurveMetric::mse) {
    const std::vector<double> f = resample_monotone(simulated, t.data.x);
    double sum = 0.0;
    for (std::size_t i = 0; i < f.size(); ++i) sum += (f[i] - t.data.y[i]) * (f[i] - t.data.y[i]);
    m.rms = std::sqrt(sum / static_cast<double>(f.size()));
  } else {
    // Residuals of this target alone: r = sqrt(w/K) (dx_k, dy_k) in normalised coordinates.
    const CompositeObjective objective({t});
    const Eigen::VectorXd r = objective.residuals(objective.responses({{t.curve, simulated}}));
    const Eigen::Index stations = r.size() / 2;
    const double unscale = target_scale(t) / std::sqrt(t.weight / static_cast<double>(stations));
    double sum = 0.0;
    for (Eigen::Index k = 0; k < stations; ++k) sum += std::pow(r(2 * k + 1) * unscale, 2);
    m.rms = std::sqrt(sum / static_cast<double>(stations));
  }
  m.available = std::isfinite(m.rms);
  return m;
}

}  // namespace

std::vector<TargetMisfit> target_misfits(const std::vector<TargetSpec>& targets, const CurveSet& curves) {
  std::vector<TargetMisfit> out;
  for (const auto& t : targets) {
    const auto found = curves.find(t.curve);
    TargetMisfit m;
    if (found != curves.end()) {
      try {
        m = misfit(t, found->second);
      } catch (const std::exception&) {
        m = TargetMisfit{};  // not comparable (e.g. no common x-range): reported as "-"
      }
    }
    out.push_back(m);
  }
  return out;
}

}  // namespace demfit::identify::detail
