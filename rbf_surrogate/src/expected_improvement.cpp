// Expected improvement and its maximisation over a box (Jones, Schonlau & Welch 1998, eq. 15).
#include "demfit/rbf_surrogate/expected_improvement.hpp"

#include "demfit/rbf_surrogate/design.hpp"

#include <nlopt.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

namespace demfit::rbf_surrogate {

namespace {

constexpr double kInvSqrt2Pi = 0.3989422804014327;
constexpr double kLogFloor = -1e300;

double normal_pdf(double z) { return kInvSqrt2Pi * std::exp(-0.5 * z * z); }
double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

struct Acquisition {
  const KrigingModel* model;
  double best;
  const AcquisitionOptions* options;
  double operator()(const VectorXd& x) const {
    for (const auto& c : options->excluded_centres)
      if ((x - c).norm() < options->excluded_radius) return kLogFloor;
    for (const auto& c : options->failed_points)
      if ((x - c).norm() < options->failed_radius) return kLogFloor;
    if (!std::isfinite(best)) return std::log(std::max(model->standard_deviation(x), 1e-300));
    double m = 0.0, s = 0.0;
    model->predict(x, m, s);
    return log_expected_improvement(m, s, best);
  }
};

struct Polish {
  const Acquisition* acquisition;
  double operator()(unsigned n, const double* z) const {
    const double v = (*acquisition)(Eigen::Map<const VectorXd>(z, n));
    return std::isfinite(v) ? -v : std::numeric_limits<double>::max();
  }
};

double polish_callback(unsigned n, const double* z, double*, void* data) {
  return (*static_cast<const Polish*>(data))(n, z);
}

MatrixXd candidate_points(const VectorXd& incumbent, const Box& region, int count, double local_fraction,
                          std::mt19937_64& rng) {
  static constexpr double kSigma[4] = {0.2, 0.05, 0.01, 0.002};
  const int dims = region.dims();
  const VectorXd width = region.width();
  MatrixXd c(count, dims);
  const int local = static_cast<int>(std::lround(std::clamp(local_fraction, 0.0, 1.0) * count));
  // Local candidates take the even slots while they last (uniform ones the rest), so the ranking's
  // ties (e.g. candidates clamped onto the same face) do not favour one kind; measured on
  // Hartmann-6, 20 seeds: median 34.5 evaluations interleaved, 39.5 with all local ones first.
  int placed = 0;
  for (int k = 0; k < count; ++k) {
    const bool near = (k % 2 == 0 && placed < local) || (count - k <= local - placed);
    if (near) {
      const double sigma = kSigma[placed++ % 4];
      for (int i = 0; i < dims; ++i) c(k, i) = incumbent[i] + sigma * width[i] * normal01(rng);
      c.row(k) = region.clamp(c.row(k).transpose()).transpose();
    } else {
      for (int i = 0; i < dims; ++i) c(k, i) = region.lower[i] + uniform01(rng) * width[i];
    }
  }
  return c;
}

// Indices of the `count` best candidates that are pairwise ≥ 2 % of the region apart.
std::vector<Eigen::Index> distinct_best(const MatrixXd& c, const VectorXd& score, const Box& region, int count) {
  std::vector<Eigen::Index> order(static_cast<std::size_t>(c.rows()));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return score[a] > score[b]; });
  const VectorXd width = region.width().cwiseMax(1e-300);
  std::vector<Eigen::Index> picked;
  for (Eigen::Index k : order) {
    if (static_cast<int>(picked.size()) >= count) break;
    bool distinct = true;
    for (Eigen::Index p : picked)
      if ((c.row(k) - c.row(p)).transpose().cwiseQuotient(width).norm() < 0.02) {
        distinct = false;
        break;
      }
    if (distinct) picked.push_back(k);
  }
  return picked;
}

}  // namespace

double expected_improvement(double mean, double sd, double best) {
  if (!(sd > 0.0)) return std::max(best - mean, 0.0);
  const double z = (best - mean) / sd;
  return (best - mean) * normal_cdf(z) + sd * normal_pdf(z);
}

double log_expected_improvement(double mean, double sd, double best) {
  if (!(sd > 0.0)) return best > mean ? std::log(best - mean) : kLogFloor;
  const double z = (best - mean) / sd;
  // Direct form down to z = −20: the cancellation in zΦ(z) + φ(z) ≈ φ(z)/z² costs at most
  // log10(400) < 3 of 16 digits there. Below, the Mills-ratio series
  // zΦ(z) + φ(z) = φ(z)(w − 3w² + 15w³ − 105w⁴ + 945w⁵ − …), w = 1/z², (truncation < 1e-12 relative)
  // keeps log EI finite and ordered where φ(z) itself underflows.
  if (z > -20.0) return std::log(std::max(sd * (z * normal_cdf(z) + normal_pdf(z)), 1e-300));
  const double w = 1.0 / (z * z);
  const double series = w * (1.0 - w * (3.0 - w * (15.0 - w * (105.0 - 945.0 * w))));
  return std::log(sd) - 0.5 * z * z + std::log(kInvSqrt2Pi) + std::log(series);
}

AcquisitionResult maximise_expected_improvement(const KrigingModel& model, double best, const VectorXd& incumbent,
                                                const Box& region, std::uint64_t seed,
                                                const AcquisitionOptions& options) {
  validate(region);
  if (region.dims() != model.dims() || incumbent.size() != model.dims())
    throw std::invalid_argument("maximise_expected_improvement: region, incumbent and model dimensions differ");
  const int dims = region.dims();
  const int count = options.candidates > 0 ? options.candidates : std::clamp(400 * dims, 2000, 4000);
  std::mt19937_64 rng(seed);
  const MatrixXd c = candidate_points(incumbent, region, count, options.local_fraction, rng);
  const Acquisition acquisition{&model, best, &options};
  VectorXd score(c.rows());
  for (Eigen::Index k = 0; k < c.rows(); ++k) score[k] = acquisition(c.row(k).transpose());
  AcquisitionResult result;
  Eigen::Index top = 0;
  score.maxCoeff(&top);
  result.x = c.row(top).transpose();
  result.log_ei = score[top];
  const Polish polish{&acquisition};
  std::vector<double> lower(region.lower.data(), region.lower.data() + dims);
  std::vector<double> upper(region.upper.data(), region.upper.data() + dims);
  for (Eigen::Index k : distinct_best(c, score, region, options.local_starts)) {
    nlopt::opt opt(nlopt::LN_BOBYQA, static_cast<unsigned>(dims));
    opt.set_lower_bounds(lower);
    opt.set_upper_bounds(upper);
    opt.set_min_objective(polish_callback, const_cast<Polish*>(&polish));
    opt.set_maxeval(options.local_evaluations);
    opt.set_xtol_rel(1e-8);
    std::vector<double> step(static_cast<std::size_t>(dims));
    for (int i = 0; i < dims; ++i) step[static_cast<std::size_t>(i)] = std::max(0.01 * region.width()[i], 1e-12);
    opt.set_initial_step(step);
    std::vector<double> z(static_cast<std::size_t>(dims));
    for (int i = 0; i < dims; ++i) z[static_cast<std::size_t>(i)] = c(k, i);
    double value = 0.0;
    try {
      opt.optimize(z, value);
    } catch (const std::exception&) { value = polish(static_cast<unsigned>(dims), z.data()); }
    if (-value > result.log_ei) {
      result.log_ei = -value;
      result.x = region.clamp(Eigen::Map<const VectorXd>(z.data(), dims));
    }
  }
  return result;
}

}  // namespace demfit::rbf_surrogate
