// Stochastic-RBF infill (Regis & Shoemaker 2007, "A stochastic radial basis function method for the
// global optimization of expensive functions"): candidates around the best point and uniformly in the
// region, scored by a weighted sum of the scaled predicted value and the scaled distance to points
// already run; the weight cycles so successive points move from exploration to exploitation.
#include "demfit/rbf_surrogate/adaptive_infill.hpp"

#include "demfit/rbf_surrogate/design.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace demfit::rbf_surrogate {

namespace {

constexpr std::array<double, 4> kWeightCycle{0.3, 0.5, 0.8, 0.95};
constexpr double kMinSeparation = 1e-5;  // unit coordinates; closer points add nothing but ill-conditioning

VectorXd best_point(const RbfNetwork& model, const MatrixXd& existing, const Box& region) {
  VectorXd best = region.center();
  double best_value = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < existing.rows(); ++i) {
    const VectorXd x = existing.row(i).transpose();
    if (!region.contains(x, 1e-12)) continue;
    const double v = model.predict_output(x, 0);
    if (v < best_value) {
      best_value = v;
      best = x;
    }
  }
  return best;
}

MatrixXd candidates(const VectorXd& best, const Box& region, std::mt19937_64& rng) {
  const int dims = region.dims();
  const int count = std::clamp(300 * dims, 1000, 6000);
  MatrixXd c(count, dims);
  const VectorXd width = region.width();
  for (int k = 0; k < count; ++k) {
    if (k % 2 == 0) {
      // Perturbations of the best point; step sizes 20 %, 5 % and 1 % of the region alternate
      // so both the basin and the final digits get candidates.
      const double sigma = (k % 6 == 0) ? 0.2 : (k % 6 == 2 ? 0.05 : 0.01);
      for (int i = 0; i < dims; ++i) c(k, i) = best[i] + sigma * width[i] * normal01(rng);
      c.row(k) = region.clamp(c.row(k).transpose()).transpose();
    } else {
      for (int i = 0; i < dims; ++i) c(k, i) = region.lower[i] + uniform01(rng) * width[i];
    }
  }
  return c;
}

VectorXd scaled_to_unit(const VectorXd& v) {
  const double lo = v.minCoeff(), hi = v.maxCoeff();
  if (!(hi > lo)) return VectorXd::Zero(v.size());
  return (v.array() - lo) / (hi - lo);
}

}  // namespace

MatrixXd adaptive_infill(const RbfNetwork& model, const MatrixXd& existing, int points, const Box& region,
                         std::uint64_t seed, int iteration) {
  validate(region);
  if (points < 0) throw std::invalid_argument("adaptive_infill: number of points must be >= 0");
  if (region.dims() != model.dims())
    throw std::invalid_argument("adaptive_infill: region and model have different dimensions");
  if (existing.rows() > 0 && existing.cols() != model.dims())
    throw std::invalid_argument("adaptive_infill: existing points have the wrong number of columns");
  std::mt19937_64 rng(seed ^ (0x9E3779B97F4A7C15ULL * static_cast<std::uint64_t>(iteration + 1)));
  const MatrixXd cand = candidates(best_point(model, existing, region), region, rng);
  const VectorXd value_scaled = scaled_to_unit(model.predict_many(cand).col(0));
  VectorXd dist(cand.rows());
  for (Eigen::Index k = 0; k < cand.rows(); ++k) {
    double d2 = std::numeric_limits<double>::infinity();
    for (Eigen::Index i = 0; i < existing.rows(); ++i) d2 = std::min(d2, (cand.row(k) - existing.row(i)).squaredNorm());
    dist[k] = std::sqrt(d2);
  }
  MatrixXd chosen(points, model.dims());
  for (int j = 0; j < points; ++j) {
    const double w = kWeightCycle[static_cast<std::size_t>(iteration * points + j) % kWeightCycle.size()];
    VectorXd finite = dist;
    for (auto& d : finite)
      if (!std::isfinite(d)) d = 1.0;
    const VectorXd dist_scaled = VectorXd::Ones(dist.size()) - scaled_to_unit(finite);
    Eigen::Index pick = -1;
    double best_score = std::numeric_limits<double>::infinity();
    for (Eigen::Index k = 0; k < cand.rows(); ++k) {
      if (dist[k] < kMinSeparation) continue;
      const double score = w * value_scaled[k] + (1.0 - w) * dist_scaled[k];
      if (score < best_score) {
        best_score = score;
        pick = k;
      }
    }
    if (pick < 0) pick = 0;  // region collapsed onto existing points: nothing better exists
    chosen.row(j) = cand.row(pick);
    for (Eigen::Index k = 0; k < cand.rows(); ++k) dist[k] = std::min(dist[k], (cand.row(k) - cand.row(pick)).norm());
  }
  return chosen;
}

}  // namespace demfit::rbf_surrogate
