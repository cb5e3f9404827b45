// Multi-fidelity kriging (see multi_fidelity.hpp).
#include "demfit/rbf_surrogate/multi_fidelity.hpp"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

namespace demfit::rbf_surrogate {
namespace {

void validate_levels(const std::vector<FidelityLevel>& levels, const MultiFidelityOptions& options) {
  if (levels.empty()) throw std::invalid_argument("multi-fidelity model: no levels given; give at least one");
  if (!(options.max_scale > 0.0) || !std::isfinite(options.max_scale))
    throw std::invalid_argument("multi-fidelity model: max_scale must be a positive finite number");
  const auto dims = levels.front().points.cols();
  for (std::size_t t = 0; t < levels.size(); ++t) {
    const FidelityLevel& level = levels[t];
    const std::string name = "multi-fidelity model: level " + std::to_string(t);
    if (level.points.rows() != level.values.size())
      throw std::invalid_argument(name + " has " + std::to_string(level.points.rows()) + " points but " +
                                  std::to_string(level.values.size()) + " values; give one value per point");
    if (level.points.rows() < 2) throw std::invalid_argument(name + " has fewer than 2 points; run at least 2");
    if (level.points.cols() != dims)
      throw std::invalid_argument(name + " has points of dimension " + std::to_string(level.points.cols()) +
                                  ", level 0 of " + std::to_string(dims) + "; use the same variables at every level");
    if (!level.points.allFinite() || !level.values.allFinite())
      throw std::invalid_argument(name + " has a NaN or infinite point or value; drop failed runs before fitting");
  }
}

// Least-squares slope of y on the coarser prediction (with an intercept): the first guess of ρ.
double least_squares_scale(const VectorXd& coarser, const VectorXd& values) {
  const double mean_c = coarser.mean(), mean_y = values.mean();
  const double spread = (coarser.array() - mean_c).square().sum();
  if (!(spread > 0.0)) return 1.0;
  return ((coarser.array() - mean_c) * (values.array() - mean_y)).sum() / spread;
}

struct ScaledCorrection {
  double scale = 1.0;
  double negative_log_likelihood = 0.0;
};

ScaledCorrection correction_at(const FidelityLevel& level, const VectorXd& coarser, double scale,
                               const KrigingOptions& options) {
  const KrigingModel delta = KrigingModel::fit(level.points, level.values - scale * coarser, options);
  return {scale, delta.data_negative_log_likelihood()};
}

// ρ of highest correction likelihood: a scan of [−max, max] (the likelihood in ρ can have several
// minima) and the least-squares slope, then a golden-section refinement around the best of them.
double best_scale_of(const FidelityLevel& level, const VectorXd& coarser, const MultiFidelityOptions& options) {
  constexpr int kScan = 40;
  const double step = 2.0 * options.max_scale / kScan;
  ScaledCorrection best = correction_at(level, coarser, 0.0, options.kriging);
  auto consider = [&](double scale) {
    const ScaledCorrection c = correction_at(level, coarser, scale, options.kriging);
    if (c.negative_log_likelihood < best.negative_log_likelihood) best = c;
  };
  for (int k = 0; k <= kScan; ++k) consider(-options.max_scale + step * k);
  const double guess = least_squares_scale(coarser, level.values);
  if (std::fabs(guess) <= options.max_scale) consider(guess);
  constexpr double kInverseGolden = 0.6180339887498949;
  double a = std::max(best.scale - step, -options.max_scale), b = std::min(best.scale + step, options.max_scale);
  double c = b - kInverseGolden * (b - a), d = a + kInverseGolden * (b - a);
  double fc = correction_at(level, coarser, c, options.kriging).negative_log_likelihood;
  double fd = correction_at(level, coarser, d, options.kriging).negative_log_likelihood;
  for (int k = 0; k < 30 && b - a > 1e-4 * step; ++k) {
    if (fc < fd) {
      b = d, d = c, fd = fc;
      c = b - kInverseGolden * (b - a);
      fc = correction_at(level, coarser, c, options.kriging).negative_log_likelihood;
    } else {
      a = c, c = d, fc = fd;
      d = a + kInverseGolden * (b - a);
      fd = correction_at(level, coarser, d, options.kriging).negative_log_likelihood;
    }
  }
  if (fc < best.negative_log_likelihood) best = {c, fc};
  if (fd < best.negative_log_likelihood) best = {d, fd};
  return best.scale;
}

}  // namespace

double autoregressive_scale(const FidelityLevel& level, const VectorXd& coarser, const MultiFidelityOptions& options) {
  if (coarser.size() != level.values.size())
    throw std::invalid_argument("multi-fidelity scale: one coarser value per point is needed");
  return best_scale_of(level, coarser, options);
}

MultiFidelityModel MultiFidelityModel::fit(const std::vector<FidelityLevel>& levels,
                                           const MultiFidelityOptions& options) {
  validate_levels(levels, options);
  MultiFidelityModel model;
  model.models_.push_back(
      std::make_shared<const KrigingModel>(KrigingModel::fit(levels[0].points, levels[0].values, options.kriging)));
  for (std::size_t t = 1; t < levels.size(); ++t) {
    const FidelityLevel& level = levels[t];
    const std::shared_ptr<const KrigingModel>& coarser_model = model.models_.back();
    const VectorXd coarser = coarser_model->means(level.points);
    KrigingOptions level_options = options.kriging;
    level_options.trend = {coarser_model, best_scale_of(level, coarser, options)};
    model.models_.push_back(
        std::make_shared<const KrigingModel>(KrigingModel::fit(level.points, level.values, level_options)));
  }
  return model;
}

void MultiFidelityModel::predict_level(int level, const VectorXd& x, double& mean, double& standard_deviation) const {
  if (level < 0 || level >= levels()) throw std::out_of_range("multi-fidelity model: no such level");
  models_[static_cast<std::size_t>(level)]->predict(x, mean, standard_deviation);
}

double MultiFidelityModel::mean(const VectorXd& x) const { return models_.back()->mean(x); }

}  // namespace demfit::rbf_surrogate
