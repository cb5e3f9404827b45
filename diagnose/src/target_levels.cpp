// Per-target levels of a fit's residual; see target_levels.hpp.
#include "demfit/diagnose/target_levels.hpp"

#include <algorithm>
#include <stdexcept>

#include "text_format.hpp"

namespace demfit::diagnose {

Eigen::VectorXd raw_residual(const FitTarget& target, const Eigen::VectorXd& normalised) {
  if (target.noise_factor.size() > 0) return target.noise_factor.triangularView<Eigen::Lower>() * normalised;
  return target.sigma * normalised;
}

std::vector<TargetLevel> target_levels(const std::vector<FitTarget>& targets, const Eigen::VectorXd& residual) {
  std::vector<TargetLevel> out;
  Eigen::Index offset = 0;
  for (const FitTarget& t : targets) {
    const auto n = static_cast<Eigen::Index>(t.data.x.size());
    if (n == 0 || offset + n > residual.size())
      throw std::invalid_argument("target_levels: the residual is shorter than the targets' points");
    const Eigen::VectorXd raw = raw_residual(t, residual.segment(offset, n));
    TargetLevel level;
    level.target = t.name;
    level.mean = raw.mean();
    level.mean_over_sigma = t.sigma > 0.0 ? level.mean / t.sigma : 0.0;
    const double mean_square = raw.squaredNorm() / static_cast<double>(n);
    level.level_share = mean_square > 0.0 ? std::min(1.0, level.mean * level.mean / mean_square) : 0.0;
    out.push_back(level);
    offset += n;
  }
  if (offset != residual.size())
    throw std::invalid_argument("target_levels: the residual is longer than the targets' points");
  return out;
}

std::string opposite_levels_text(const std::vector<TargetLevel>& levels) {
  const TargetLevel* above = nullptr;
  const TargetLevel* below = nullptr;
  for (const TargetLevel& l : levels) {
    if (l.level_share < kLevelShareToReport) continue;
    if (l.mean > 0.0 && (above == nullptr || l.mean_over_sigma > above->mean_over_sigma)) above = &l;
    if (l.mean < 0.0 && (below == nullptr || l.mean_over_sigma < below->mean_over_sigma)) below = &l;
  }
  if (above == nullptr || below == nullptr) return "";
  return " Between targets: the base fit lies above its data in '" + above->target +
         detail::format("' (mean residual %+.4g, %.2g sigma, %.0f %% of its squared residual)", above->mean,
                        above->mean_over_sigma, 100.0 * above->level_share) +
         " and below it in '" + below->target +
         detail::format("' (%+.4g, %.2g sigma, %.0f %%)", below->mean, below->mean_over_sigma,
                        100.0 * below->level_share) +
         ": the model changes between these targets differently from the data, a structure between them that no "
         "shared parameter moving both the same way can remove.";
}

}  // namespace demfit::diagnose
