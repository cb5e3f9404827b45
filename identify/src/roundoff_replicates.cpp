// Round-off replicates and their spread (see roundoff_replicates.hpp).
#include "demfit/identify/roundoff_replicates.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "study_support.hpp"

namespace demfit::identify {

Eigen::VectorXd replicate_point(const Eigen::VectorXd& unit, int replicate) {
  const double nudge = (replicate + 1) * kReplicateNudge;
  Eigen::VectorXd p = unit;
  for (Eigen::Index j = 0; j < p.size(); ++j) p(j) = p(j) + nudge <= 1.0 ? p(j) + nudge : p(j) - nudge;
  return p;
}

ParameterSet replicate_parameters(const StudySpec& spec, const ParameterSet& values, int replicate) {
  ParameterSet out = values;
  for (const VariableSpec& v : spec.variables) {
    const auto found = values.find(v.name);
    if (found == values.end()) continue;
    const rbf_surrogate::Variable mapping = detail::rbf_variable(v);
    Eigen::VectorXd unit(1);
    unit(0) = rbf_surrogate::to_unit(mapping, found->second);
    out[v.name] = rbf_surrogate::from_unit(mapping, replicate_point(unit, replicate)(0));
  }
  return out;
}

ReplicateSpread replicate_spread(const std::vector<double>& values) {
  if (values.empty()) throw std::invalid_argument("replicate spread: no values; run at least one replicate");
  ReplicateSpread s;
  s.count = static_cast<int>(values.size());
  s.lowest = s.highest = values.front();
  double sum = 0.0;
  for (const double v : values) {
    if (!std::isfinite(v)) throw std::invalid_argument("replicate spread: a value is not finite; drop the failed run");
    sum += v;
    s.lowest = std::min(s.lowest, v);
    s.highest = std::max(s.highest, v);
  }
  s.mean = sum / s.count;
  if (s.count < 2) return s;
  double squares = 0.0;
  for (const double v : values) squares += (v - s.mean) * (v - s.mean);
  s.standard_deviation = std::sqrt(squares / (s.count - 1));
  return s;
}

RatioOfMeans ratio_of_means(const ReplicateSpread& numerator, const ReplicateSpread& denominator) {
  if (!(denominator.mean > 0.0) || numerator.count < 1 || denominator.count < 1)
    throw std::invalid_argument("ratio of means: the denominator's mean must be positive, both with >= 1 value");
  const double r = numerator.mean / denominator.mean;
  const auto relative_variance = [](const ReplicateSpread& s) {
    return s.mean == 0.0 ? 0.0 : s.standard_deviation * s.standard_deviation / (s.count * s.mean * s.mean);
  };
  const double se = std::abs(r) * std::sqrt(relative_variance(numerator) + relative_variance(denominator));
  return {r, r - 2.0 * se, r + 2.0 * se};
}

}  // namespace demfit::identify
