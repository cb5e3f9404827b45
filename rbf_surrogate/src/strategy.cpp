// Ask/tell bookkeeping shared by every strategy: the evaluation history (failed runs included),
// the initial design, the fallback while too few runs succeeded to fit, and the stopping rule.
#include "demfit/rbf_surrogate/strategy.hpp"

#include "demfit/rbf_surrogate/design.hpp"
#include "strategy_internal.hpp"

#include <cmath>
#include <stdexcept>

namespace demfit::rbf_surrogate {

void EvaluationHistory::add(const VectorXd& unit, double value) {
  if (unit.size() != dims_) throw std::invalid_argument("tell: a point has the wrong number of coordinates");
  if (!unit.allFinite()) throw std::invalid_argument("tell: a point has a NaN or infinite coordinate");
  if (std::isinf(value)) throw std::invalid_argument("tell: an infinite value; report a failed run as NaN");
  points_.push_back(unit);
  values_.push_back(value);
  if (!std::isnan(value)) {
    fit_rows_.push_back(static_cast<int>(values_.size()) - 1);
    best_ = std::min(best_, value);
  }
  best_so_far_.push_back(best_);
}

bool EvaluationHistory::is_new(const VectorXd& x, double tolerance) const {
  for (const auto& p : points_)
    if ((p - x).norm() < tolerance) return false;
  return true;
}

MatrixXd EvaluationHistory::all_points() const {
  MatrixXd x(static_cast<Eigen::Index>(points_.size()), dims_);
  for (std::size_t i = 0; i < points_.size(); ++i) x.row(static_cast<Eigen::Index>(i)) = points_[i].transpose();
  return x;
}

MatrixXd EvaluationHistory::fit_points() const {
  MatrixXd x(static_cast<Eigen::Index>(fit_rows_.size()), dims_);
  for (std::size_t i = 0; i < fit_rows_.size(); ++i)
    x.row(static_cast<Eigen::Index>(i)) = points_[static_cast<std::size_t>(fit_rows_[i])].transpose();
  return x;
}

VectorXd EvaluationHistory::fit_values() const {
  VectorXd y(static_cast<Eigen::Index>(fit_rows_.size()));
  for (std::size_t i = 0; i < fit_rows_.size(); ++i)
    y[static_cast<Eigen::Index>(i)] = values_[static_cast<std::size_t>(fit_rows_[i])];
  return y;
}

VectorXd EvaluationHistory::best_point() const {
  if (fit_rows_.empty()) throw std::logic_error("best_point: no successful evaluation yet");
  int best = fit_rows_.front();
  for (int i : fit_rows_)
    if (values_[static_cast<std::size_t>(i)] < values_[static_cast<std::size_t>(best)]) best = i;
  return points_[static_cast<std::size_t>(best)];
}

StopReason stop_reason(const EvaluationHistory& history, const StoppingRule& rule) {
  if (rule.target && history.best() <= *rule.target) return StopReason::target;
  if (history.size() >= rule.max_evaluations) return StopReason::budget;
  return StopReason::none;
}

std::string to_string(StopReason reason) {
  switch (reason) {
    case StopReason::budget:
      return "evaluation budget reached";
    case StopReason::target:
      return "target reached";
    default:
      return "";
  }
}

MatrixXd AskTellStrategy::ask(int batch_size) {
  if (batch_size < 1) throw std::invalid_argument("ask: batch size must be at least 1");
  const int dims = history_.dims();
  const bool first = !asked_;
  asked_ = true;
  if (first && history_.size() < initial_points()) {
    pending_ = Pending::design;
    return keep_new(latin_hypercube_maximin(initial_points(), dims, seed_, Box::unit(dims)));
  }
  if (history_.successes() < minimum_fit_points()) {
    // Too many failed runs to fit yet: spread more points over the domain (seeded by the run count,
    // so a replay gives the same points).
    pending_ = Pending::design;
    return keep_new(space_filling_augment(history_.all_points(), batch_size, Box::unit(dims),
                                          seed_ + 104729ULL * static_cast<std::uint64_t>(history_.size())));
  }
  pending_ = Pending::proposal;
  return propose(batch_size);
}

void AskTellStrategy::tell(const MatrixXd& points, const VectorXd& values) {
  if (points.rows() != values.size()) throw std::invalid_argument("tell: points and values have different counts");
  const int before = history_.size();
  for (Eigen::Index i = 0; i < points.rows(); ++i) history_.add(points.row(i).transpose(), values[i]);
  if (pending_ == Pending::proposal) told(before);
  pending_ = Pending::none;
}

MatrixXd AskTellStrategy::keep_new(const MatrixXd& rows) const {
  MatrixXd kept(rows.rows(), rows.cols());
  Eigen::Index n = 0;
  for (Eigen::Index i = 0; i < rows.rows(); ++i) {
    const VectorXd x = rows.row(i).transpose();
    bool fresh = history_.is_new(x);
    for (Eigen::Index j = 0; j < n && fresh; ++j) fresh = (kept.row(j).transpose() - x).norm() >= 1e-5;
    if (fresh) kept.row(n++) = x.transpose();
  }
  return kept.topRows(n);
}

MatrixXd AskTellStrategy::unstall_point(std::uint64_t seed) const {
  return keep_new(space_filling_augment(history_.all_points(), 1, Box::unit(history_.dims()), seed));
}

namespace detail {

RbfNetwork RbfFitSchedule::fit(const EvaluationHistory& history) {
  RbfOptions o = options_.rbf;
  const int count = history.successes();
  const bool reuse = width_ > 0.0 && !o.fixed_width && count < (11 * searched_at_) / 10;
  if (reuse)
    o.fixed_width = width_;
  else if (width_ > 0.0)
    o.width_hint = width_;
  VectorXd y = history.fit_values();
  // Regis & Shoemaker (2007): large values far from the optimum otherwise dominate the fit.
  if (options_.clip_above_median) y = y.cwiseMin(upper_median(std::vector<double>(y.data(), y.data() + y.size())));
  RbfNetwork net = RbfNetwork::fit(history.fit_points(), y, o);
  if (!reuse && !options_.rbf.fixed_width) {
    width_ = net.width();
    searched_at_ = count;
  }
  return net;
}

}  // namespace detail

int default_batch_size(int dims, const ExpensiveOptions& options) {
  if (options.points_per_iteration > 0) return options.points_per_iteration;
  return options.strategy == InfillStrategy::srsm ? static_cast<int>(std::ceil(1.5 * (dims + 1))) + 1 : 1;
}

std::unique_ptr<AskTellStrategy> make_strategy(int dims, const ExpensiveOptions& options) {
  if (dims < 1) throw std::invalid_argument("make_strategy: no variables");
  validate(options.srsm);
  switch (options.strategy) {
    case InfillStrategy::srsm:
      return detail::make_srsm_strategy(dims, options);
    case InfillStrategy::adaptive:
      return detail::make_adaptive_strategy(dims, options);
    default:
      return detail::make_expected_improvement_strategy(dims, options);
  }
}

}  // namespace demfit::rbf_surrogate
