// Bounded Levenberg-Marquardt on model evaluations; see least_squares.hpp.
#include "demfit/diagnose/least_squares.hpp"

#include "demfit/identify/evaluator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "demfit/identify/objective.hpp"

namespace demfit::diagnose {

int near_bound(const FitVariable& variable, double value, double fraction) {
  const double margin = fraction * (variable.upper - variable.lower);
  if (value >= variable.upper - margin) return 1;
  return value <= variable.lower + margin ? -1 : 0;
}

bool at_bound(const FitVariable& variable, double value) { return near_bound(variable, value, 1e-6) != 0; }

std::vector<std::size_t> monotone_branches(const std::vector<double>& x) {
  std::vector<std::size_t> starts{0};
  int direction = 0;  // +1 increasing, -1 decreasing, 0 not yet known in this branch
  for (std::size_t i = 1; i < x.size(); ++i) {
    const int d = x[i] > x[i - 1] ? 1 : (x[i] < x[i - 1] ? -1 : 0);
    if (d == 0) continue;
    if (direction != 0 && d != direction) {
      // The turning point belongs to both branches: the new branch starts at the reversal point.
      starts.push_back(i - 1);
      direction = d;
      continue;
    }
    direction = d;
  }
  starts.push_back(x.size());
  return starts;
}

namespace {

identify::Curve slice(const identify::Curve& c, std::size_t begin, std::size_t end) {
  identify::Curve out{c.x_label, c.y_label, {}, {}};
  out.x.assign(c.x.begin() + static_cast<std::ptrdiff_t>(begin), c.x.begin() + static_cast<std::ptrdiff_t>(end));
  out.y.assign(c.y.begin() + static_cast<std::ptrdiff_t>(begin), c.y.begin() + static_cast<std::ptrdiff_t>(end));
  return out;
}

// Simulated y at the data abscissae, branch by branch (a single branch is the usual monotone
// resampling). The turning point of the data, shared by two branches, is taken from the first.
std::vector<double> resample_branches(const identify::Curve& simulated, const identify::Curve& data) {
  const auto data_branches = monotone_branches(data.x);
  if (data_branches.size() <= 2) return identify::resample_monotone(simulated, data.x);
  const auto model_branches = monotone_branches(simulated.x);
  const std::size_t n_data = data_branches.size() - 1, n_model = model_branches.size() - 1;
  if (n_model < n_data)
    throw std::runtime_error("curve '" + simulated.y_label + "' has " + std::to_string(n_model) +
                             " monotone branches, the data " + std::to_string(n_data));
  std::vector<double> out(data.x.size());
  // Branch b spans [starts[b], starts[b+1]], the turning point included (it starts the next one).
  auto branch_end = [](const std::vector<std::size_t>& starts, std::size_t b) {
    return b + 2 < starts.size() ? starts[b + 1] + 1 : starts[b + 1];
  };
  for (std::size_t b = 0; b < n_data; ++b) {
    const std::size_t begin = b == 0 ? 0 : data_branches[b] + 1, end = branch_end(data_branches, b);
    if (begin >= end) continue;
    const std::size_t model_end = std::max(branch_end(model_branches, b), model_branches[b] + 2);
    const identify::Curve branch = slice(simulated, model_branches[b], std::min(model_end, simulated.x.size()));
    const std::vector<double> at(data.x.begin() + static_cast<std::ptrdiff_t>(begin),
                                 data.x.begin() + static_cast<std::ptrdiff_t>(end));
    const auto values = identify::resample_monotone(branch, at);
    std::copy(values.begin(), values.end(), out.begin() + static_cast<std::ptrdiff_t>(begin));
  }
  return out;
}

}  // namespace

std::vector<std::vector<double>> raw_residuals(const identify::CurveSet& curves,
                                               const std::vector<FitTarget>& targets) {
  std::vector<std::vector<double>> out;
  for (const auto& t : targets) {
    const auto found = curves.find(t.curve);
    if (found == curves.end()) throw std::runtime_error("the model produced no curve '" + t.curve + "'");
    std::vector<double> r = resample_branches(found->second, t.data);
    for (std::size_t i = 0; i < r.size(); ++i) {
      r[i] -= t.data.y[i];
      if (!std::isfinite(r[i])) throw std::runtime_error("curve '" + t.curve + "' contains a non-finite value");
    }
    out.push_back(std::move(r));
  }
  return out;
}

Eigen::VectorXd normalised_residual(const identify::CurveSet& curves, const std::vector<FitTarget>& targets) {
  const auto raw = raw_residuals(curves, targets);
  std::size_t size = 0;
  for (const auto& r : raw) size += r.size();
  Eigen::VectorXd out(static_cast<Eigen::Index>(size));
  Eigen::Index k = 0;
  for (std::size_t t = 0; t < raw.size(); ++t) {
    const auto n = static_cast<Eigen::Index>(raw[t].size());
    if (targets[t].noise_factor.size() > 0) {
      if (targets[t].noise_factor.rows() != n || targets[t].noise_factor.cols() != n)
        throw std::logic_error("target '" + targets[t].name + "': noise factor does not match its data points");
      const Eigen::Map<const Eigen::VectorXd> r(raw[t].data(), n);
      out.segment(k, n) = targets[t].noise_factor.triangularView<Eigen::Lower>().solve(r);
      k += n;
    } else {
      for (double v : raw[t]) out(k++) = v / targets[t].sigma;
    }
  }
  return out;
}

std::vector<identify::CurveSet> evaluate_many(const identify::Model& model,
                                              const std::vector<identify::ParameterSet>& sets, int jobs,
                                              unsigned long seed) {
  // The identify thread pool: same scheduling, failure capture and ordering as a study's runs.
  identify::ThreadPoolEvaluator evaluator(model, jobs, 1, seed);
  std::vector<identify::CurveSet> out;
  for (auto& outcome : evaluator.evaluate_points(model, sets, nullptr)) {
    out.push_back(outcome.ok ? std::move(outcome.curves) : identify::CurveSet{});  // empty: failed run
  }
  return out;
}

std::vector<Eigen::VectorXd> residuals_at(const identify::Model& model, const std::vector<identify::ParameterSet>& sets,
                                          const std::vector<FitTarget>& targets, const FitOptions& options) {
  std::vector<Eigen::VectorXd> out;
  for (const auto& curves : evaluate_many(model, sets, options.jobs, options.seed)) {
    Eigen::VectorXd r;
    if (!curves.empty()) {
      try {
        r = normalised_residual(curves, targets);
      } catch (const std::exception&) { r.resize(0); }
    }
    out.push_back(r);
  }
  return out;
}

namespace {

struct Problem {
  const identify::Model& model;
  const identify::ParameterSet& fixed;
  const std::vector<FitVariable>& variables;
  const std::vector<FitTarget>& targets;
  const FitOptions& options;
  int evaluations = 0;

  identify::ParameterSet parameters(const Eigen::VectorXd& u) const {
    identify::ParameterSet p = fixed;
    for (std::size_t j = 0; j < variables.size(); ++j)
      p[variables[j].name] = variables[j].lower + u(j) * (variables[j].upper - variables[j].lower);
    return p;
  }
  // Residuals at several normalised points; an empty vector marks a failed evaluation.
  std::vector<Eigen::VectorXd> residuals(const std::vector<Eigen::VectorXd>& points) {
    std::vector<identify::ParameterSet> sets;
    for (const auto& u : points) sets.push_back(parameters(u));
    evaluations += static_cast<int>(points.size());
    return residuals_at(model, sets, targets, options);
  }
};

// Finite differences in normalised coordinates: forward (backwards at the upper bound), or central
// where both sides fit in [0, 1] (one-sided otherwise). A failed evaluation leaves its column 0.
Eigen::MatrixXd jacobian(Problem& problem, const Eigen::VectorXd& u, const Eigen::VectorXd& r) {
  const Eigen::Index n = u.size();
  const double h = problem.options.fd_step;
  std::vector<Eigen::VectorXd> points;
  std::vector<std::pair<int, int>> index;  // per column: plus point, minus point (-1 = centre u)
  std::vector<double> spans;
  for (Eigen::Index j = 0; j < n; ++j) {
    const bool up = u(j) + h <= 1.0, down = u(j) - h >= 0.0;
    int plus = -1, minus = -1;
    if (up || !down) {
      Eigen::VectorXd p = u;
      p(j) = std::min(1.0, u(j) + h);
      plus = static_cast<int>(points.size());
      points.push_back(p);
    }
    if (!up || (problem.options.central_differences && down)) {
      Eigen::VectorXd p = u;
      p(j) = std::max(0.0, u(j) - h);
      minus = static_cast<int>(points.size());
      points.push_back(p);
    }
    const double hi = plus >= 0 ? points[plus](j) : u(j), lo = minus >= 0 ? points[minus](j) : u(j);
    index.emplace_back(plus, minus);
    spans.push_back(hi - lo);
  }
  const auto rs = problem.residuals(points);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(r.size(), n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const auto [plus, minus] = index[j];
    const Eigen::VectorXd& a = plus >= 0 ? rs[plus] : r;
    const Eigen::VectorXd& b = minus >= 0 ? rs[minus] : r;
    if (a.size() == r.size() && b.size() == r.size() && spans[j] > 0.0) J.col(j) = (a - b) / spans[j];
  }
  return J;
}

// One Levenberg-Marquardt step from (u, r) with Jacobian J: damped normal equations, clamped to
// the unit box. Variables at a bound that the step pushes outwards are held there and the step
// re-solved for the others (a projected step; plain clamping would stall on such a variable).
Eigen::VectorXd lm_trial(const Eigen::MatrixXd& J, const Eigen::VectorXd& r, const Eigen::VectorXd& u, double lambda) {
  const Eigen::Index n = u.size();
  const Eigen::MatrixXd JtJ = J.transpose() * J;
  const Eigen::VectorXd g = J.transpose() * r;
  std::vector<bool> held(static_cast<std::size_t>(n), false);
  Eigen::VectorXd step = Eigen::VectorXd::Zero(n);
  for (int pass = 0; pass < 2; ++pass) {
    Eigen::MatrixXd A = JtJ;
    Eigen::VectorXd b = -g;
    for (Eigen::Index j = 0; j < n; ++j) {
      A(j, j) += lambda * std::max(JtJ(j, j), 1e-12);
      if (held[j]) {
        A.row(j).setZero();
        A.col(j).setZero();
        A(j, j) = 1.0;
        b(j) = 0.0;
      }
    }
    step = A.ldlt().solve(b);
    bool changed = false;
    for (Eigen::Index j = 0; j < n; ++j)
      if (!held[j] && ((u(j) <= 0.0 && step(j) < 0.0) || (u(j) >= 1.0 && step(j) > 0.0))) held[j] = changed = true;
    if (!changed) break;
  }
  return (u + step).cwiseMax(0.0).cwiseMin(1.0);
}

// Broyden's "good" secant update: the smallest change of J for which J s = r(u + s) - r(u).
void broyden_update(Eigen::MatrixXd& J, const Eigen::VectorXd& s, const Eigen::VectorXd& r_new,
                    const Eigen::VectorXd& r) {
  const double ss = s.squaredNorm();
  if (ss <= 0.0) return;
  J += ((r_new - r) - J * s) * (s.transpose() / ss);
}

}  // namespace

FitResult fit_least_squares(const identify::Model& model, const identify::ParameterSet& fixed,
                            const std::vector<FitVariable>& variables, const std::vector<FitTarget>& targets,
                            const FitOptions& options, const Eigen::MatrixXd* initial_jacobian) {
  Problem problem{model, fixed, variables, targets, options};
  const Eigen::Index n = static_cast<Eigen::Index>(variables.size());
  Eigen::VectorXd u(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const auto& v = variables[j];
    u(j) = std::clamp((v.start - v.lower) / (v.upper - v.lower), 0.0, 1.0);
  }
  Eigen::VectorXd r = problem.residuals({u}).front();
  if (r.size() == 0) throw std::runtime_error("least-squares fit: the model cannot be evaluated at the start point");
  double cost = r.squaredNorm();
  const bool reuse = initial_jacobian && initial_jacobian->rows() == r.size() && initial_jacobian->cols() == n;
  Eigen::MatrixXd J = n == 0 ? Eigen::MatrixXd(r.size(), 0) : (reuse ? *initial_jacobian : jacobian(problem, u, r));
  bool fresh = !reuse;  // J was computed by finite differences at the current u
  double lambda = 1e-3;
  int iteration = 0;
  int accepted_steps = 0;  // numbers the on_step reports
  auto out_of_budget = [&] { return options.max_evaluations > 0 && problem.evaluations >= options.max_evaluations; };
  for (; iteration < options.max_iterations && n > 0 && !out_of_budget(); ++iteration) {
    bool accepted = false, step_from_fresh = false;
    double new_cost = cost;
    for (int attempt = 0; attempt < 12 && !accepted && !out_of_budget(); ++attempt) {
      const Eigen::VectorXd trial = lm_trial(J, r, u, lambda);
      if ((trial - u).lpNorm<Eigen::Infinity>() < 1e-14) break;  // pinned at the bounds: no move left
      const Eigen::VectorXd rt = problem.residuals({trial}).front();
      const bool valid = rt.size() == r.size();
      // A secant over a step shorter than the finite-difference step would be dominated by the
      // model's own noise (DEM trajectories): such steps do not update J.
      const bool secant = options.broyden && valid && (trial - u).lpNorm<Eigen::Infinity>() >= options.fd_step;
      if (valid && rt.squaredNorm() < cost) {
        step_from_fresh = fresh;
        if (secant) broyden_update(J, trial - u, rt, r);
        u = trial;
        r = rt;
        new_cost = rt.squaredNorm();
        accepted = true;
        fresh = false;
        lambda = std::max(lambda / 3.0, 1e-9);
      } else {
        if (secant) broyden_update(J, trial - u, rt, r);  // still a Jacobian at u: `fresh` unchanged
        lambda *= 4.0;
        // A Jacobian carried over from an earlier point that fails twice is replaced.
        if (!fresh && attempt >= 1 && !out_of_budget()) {
          J = jacobian(problem, u, r);
          fresh = true;
        }
      }
    }
    if (!accepted) {
      if (fresh || out_of_budget()) break;
      J = jacobian(problem, u, r);  // stalled on an approximate Jacobian: refresh, try again
      fresh = true;
      continue;
    }
    const double decrease = cost - new_cost;
    cost = new_cost;
    if (options.on_step) options.on_step(++accepted_steps, problem.evaluations, cost);
    const bool converged = decrease <= options.relative_tolerance * cost || decrease <= options.absolute_tolerance;
    if (converged && step_from_fresh) {
      ++iteration;
      break;
    }
    // A small decrease on an approximate Jacobian may be a poor direction, not the optimum:
    // check with finite differences before stopping.
    if (converged || !options.broyden) {
      J = jacobian(problem, u, r);
      fresh = true;
    }
  }
  FitResult result;
  result.parameters = problem.parameters(u);
  for (Eigen::Index j = 0; j < n; ++j) result.values.push_back(result.parameters.at(variables[j].name));
  result.chi_square = cost;
  result.residual = r;
  result.jacobian = J;
  result.evaluations = problem.evaluations;
  result.iterations = iteration;
  return result;
}

}  // namespace demfit::diagnose
