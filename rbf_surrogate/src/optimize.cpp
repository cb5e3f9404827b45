// Global + local minimisation of a cheap objective with NLopt (docs/spec.md section 3: the predicted
// optimum of the surrogate in the current subregion).
#include "demfit/rbf_surrogate/optimize.hpp"

#include "demfit/rbf_surrogate/design.hpp"

#include <nlopt.hpp>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace demfit::rbf_surrogate {

namespace {

// Maps NLopt's free variables (dimensions of non-zero width) to the full point, keeps every
// evaluation for the choice of local starts, remembers the best point ever seen, and carries
// exceptions across NLopt's C interface (which would otherwise replace them by "nlopt failure").
struct Evaluator {
  const Objective* objective = nullptr;
  VectorXd fixed;         // full point template (degenerate dims at their bound)
  std::vector<int> free;  // indices of free dims
  bool record = false;
  std::vector<std::pair<double, VectorXd>> history;
  VectorXd best_x;
  double best_value = std::numeric_limits<double>::infinity();
  int evaluations = 0;
  std::exception_ptr error;

  VectorXd full(const double* z) const {
    VectorXd x = fixed;
    for (std::size_t k = 0; k < free.size(); ++k) x[free[k]] = z[k];
    return x;
  }
  double operator()(const double* z, double* grad) {
    const VectorXd x = full(z);
    VectorXd g;
    double v = (*objective)(x, grad ? &g : nullptr);
    ++evaluations;
    if (!std::isfinite(v)) v = std::numeric_limits<double>::max();
    if (grad) {
      if (g.size() != x.size()) throw std::invalid_argument("minimize: objective did not fill the gradient");
      for (std::size_t k = 0; k < free.size(); ++k) grad[k] = g[free[k]];
    }
    if (record) history.emplace_back(v, x);
    if (v < best_value) {
      best_value = v;
      best_x = x;
    }
    return v;
  }
};

double nlopt_callback(unsigned, const double* z, double* grad, void* data) {
  auto* e = static_cast<Evaluator*>(data);
  try {
    return (*e)(z, grad);
  } catch (...) {
    e->error = std::current_exception();
    throw nlopt::forced_stop();
  }
}

void run(nlopt::opt& opt, Evaluator& e, std::vector<double> z) {
  opt.set_min_objective(nlopt_callback, &e);
  double value = 0.0;
  try {
    opt.optimize(z, value);
  } catch (const std::invalid_argument&) {
    if (!e.error) throw;  // NLopt rejected its arguments: a bug, not a numerical event
  } catch (const std::exception&) {
    // forced_stop, roundoff_limited or a generic failure (e.g. an L-BFGS line search stalling on
    // a kink of a small-width RBF surface): the best point so far is kept in e either way.
  }
  if (e.error) std::rethrow_exception(e.error);
}

std::vector<double> free_coordinates(const Evaluator& e, const VectorXd& x) {
  std::vector<double> z(e.free.size());
  for (std::size_t k = 0; k < e.free.size(); ++k) z[k] = x[e.free[k]];
  return z;
}

void set_bounds(nlopt::opt& opt, const Evaluator& e, const Box& box) {
  opt.set_lower_bounds(free_coordinates(e, box.lower));
  opt.set_upper_bounds(free_coordinates(e, box.upper));
}

// Best `count` recorded points that are pairwise at least 5 % of the box apart (box-local distance).
std::vector<VectorXd> distinct_best(const Evaluator& e, const Box& box, int count) {
  std::vector<std::size_t> order(e.history.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return e.history[a].first < e.history[b].first; });
  const VectorXd width = box.width().cwiseMax(1e-300);
  std::vector<VectorXd> starts;
  for (std::size_t idx : order) {
    if (static_cast<int>(starts.size()) >= count) break;
    const VectorXd& x = e.history[idx].second;
    bool distinct = true;
    for (const auto& s : starts)
      if ((x - s).cwiseQuotient(width).norm() < 0.05) {
        distinct = false;
        break;
      }
    if (distinct) starts.push_back(x);
  }
  return starts;
}

}  // namespace

MinimizeResult minimize(const Objective& objective, const Box& box, const MinimizeOptions& options) {
  validate(box);
  if (options.global_evaluations < 1) throw std::invalid_argument("minimize: global_evaluations must be >= 1");
  Evaluator e;
  e.objective = &objective;
  e.fixed = box.lower;
  for (int i = 0; i < box.dims(); ++i)
    if (box.upper[i] - box.lower[i] > 1e-14) e.free.push_back(i);
  if (e.free.empty()) {
    e(nullptr, nullptr);
    return {e.best_x, e.best_value, e.evaluations};
  }
  const auto nfree = static_cast<unsigned>(e.free.size());
  e.record = true;
  // Global stage 1: a seeded Latin hypercube (a quarter of the budget) for diverse local starts.
  const int sampled = std::max(1, options.global_evaluations / 4);
  const MatrixXd lhs = latin_hypercube_random(sampled, box.dims(), options.seed, box);
  for (int i = 0; i < sampled; ++i) {
    const auto z = free_coordinates(e, lhs.row(i).transpose());
    e(z.data(), nullptr);
  }
  // Global stage 2: DIRECT-L (Gablonsky & Kelley), deterministic, on the rest of the budget.
  const int direct_budget = options.global_evaluations - sampled;
  if (direct_budget > 0) {
    nlopt::opt direct(nlopt::GN_DIRECT_L, nfree);
    set_bounds(direct, e, box);
    direct.set_maxeval(direct_budget);
    run(direct, e, free_coordinates(e, box.center()));
  }
  e.record = false;
  // Local polishing from the best distinct points.
  for (const VectorXd& start : distinct_best(e, box, std::max(options.local_starts, 1))) {
    nlopt::opt local(options.use_gradient ? nlopt::LD_LBFGS : nlopt::LN_BOBYQA, nfree);
    set_bounds(local, e, box);
    local.set_maxeval(options.local_evaluations);
    local.set_xtol_rel(1e-10);
    local.set_ftol_abs(1e-14);
    if (!options.use_gradient) local.set_initial_step(free_coordinates(e, 0.05 * box.width()));
    run(local, e, free_coordinates(e, start));
  }
  return {box.clamp(e.best_x), e.best_value, e.evaluations};
}

}  // namespace demfit::rbf_surrogate
