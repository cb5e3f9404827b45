#pragma once
// Multi-fidelity kriging: one response computed at several levels of accuracy and cost (a coarse
// model run many times, a fine one a few times), combined in the autoregressive form of Kennedy &
// O'Hagan (2000, Biometrika 87:1), fitted level by level as in the recursive formulation of
// Le Gratiet & Garnier (2014, Int. J. Uncertainty Quantification 4:365):
//   f_0(x) = Z_0(x),   f_t(x) = ρ_t f_{t−1}(x) + δ_t(x)   (t = 1 … L−1, coarse to fine)
// Z_0 and each correction δ_t are independent kriging models (kriging.hpp; level t is a kriging
// model with level t − 1 as its KrigingTrend). Level t is fitted to its own points only: δ_t to
// y_t − ρ_t m_{t−1}(x_t), with ρ_t the scale whose correction has the highest likelihood (a shift
// of the values leaves the likelihood's Jacobian unchanged, so the corrections' likelihoods
// compare directly). Prediction:
//   m_t(x) = ρ_t m_{t−1}(x) + m_δt(x),   s_t²(x) = ρ_t² s_{t−1}²(x) + s_δt²(x).
// Cheap runs map the landscape through Z_0; the few fine runs only have to teach the correction,
// which is smoother than the response when the levels share its shape (Forrester, Sóbester &
// Keane 2007, Proc. R. Soc. A 463:3251). Points of different levels need not coincide.
#include <memory>
#include <vector>

#include "demfit/rbf_surrogate/kriging.hpp"

namespace demfit::rbf_surrogate {

/// The runs of one fidelity level: points n×d (rows, unit cube) and their values.
struct FidelityLevel {
  MatrixXd points;
  VectorXd values;
};

struct MultiFidelityOptions {
  KrigingOptions kriging{};  ///< for the coarsest model and every correction
  /// Search interval of each scale ρ_t: [−max_scale, max_scale] (a level that follows the coarser
  /// one with the opposite sign is allowed; a scale of 0 means the coarser level tells nothing).
  double max_scale = 10.0;
};

/// ρ of highest likelihood for a kriging correction of `level`'s values y − ρ c, where `coarser`
/// holds the coarser level's mean at the level's points.
double autoregressive_scale(const FidelityLevel& level, const VectorXd& coarser, const MultiFidelityOptions& options);

class MultiFidelityModel {
 public:
  /// `levels` from the coarsest to the finest, at least one, each with at least 2 points of the
  /// same dimension. Throws std::invalid_argument (one line naming the level) otherwise, or on
  /// NaN/inf values.
  static MultiFidelityModel fit(const std::vector<FidelityLevel>& levels, const MultiFidelityOptions& options = {});

  /// Mean and standard deviation of the finest level at x (unit cube).
  void predict(const VectorXd& x, double& mean, double& standard_deviation) const {
    predict_level(levels() - 1, x, mean, standard_deviation);
  }
  /// The same for level t (0 = coarsest).
  void predict_level(int level, const VectorXd& x, double& mean, double& standard_deviation) const;
  [[nodiscard]] double mean(const VectorXd& x) const;

  [[nodiscard]] int levels() const { return static_cast<int>(models_.size()); }
  /// ρ_t of level t ≥ 1 (the scale of level t − 1 in level t); 1 for level 0.
  [[nodiscard]] double scale(int level) const {
    return level == 0 ? 1.0 : models_.at(static_cast<std::size_t>(level))->trend().scale;
  }
  /// The model of level t: Z_0 for level 0; for t ≥ 1 the correction δ_t with level t − 1 as its
  /// trend (its mean and deviation are those of level t).
  [[nodiscard]] const KrigingModel& model(int level) const { return *models_.at(static_cast<std::size_t>(level)); }

 private:
  std::vector<std::shared_ptr<const KrigingModel>> models_;
};

}  // namespace demfit::rbf_surrogate
