// minimise_expensive: the in-memory driver of the ask/tell strategies (strategy.hpp). It asks for a
// batch, evaluates the points in order until the stopping rule fires, and tells the results.
#include "demfit/rbf_surrogate/expensive.hpp"

#include "demfit/rbf_surrogate/strategy.hpp"

#include <cmath>
#include <stdexcept>

namespace demfit::rbf_surrogate {

ExpensiveResult minimise_expensive(const std::function<double(const VectorXd&)>& f,
                                   const std::vector<Variable>& variables, const ExpensiveOptions& options) {
  validate(variables);
  if (variables.empty()) throw std::invalid_argument("minimise_expensive: no variables");
  const int dims = static_cast<int>(variables.size());
  const std::unique_ptr<AskTellStrategy> strategy = make_strategy(dims, options);
  if (options.max_evaluations < strategy->initial_points())
    throw std::invalid_argument("minimise_expensive: max_evaluations must be at least the initial design size");
  const StoppingRule rule{options.max_evaluations, options.target};
  const int batch = default_batch_size(dims, options);
  ExpensiveResult r;
  while (stop_reason(strategy->history(), rule) == StopReason::none) {
    const MatrixXd asked = strategy->ask(batch);
    // Evaluated one by one so that the budget and the target are checked after every run.
    Eigen::Index done = 0;
    VectorXd values(asked.rows());
    for (; done < asked.rows(); ++done) {
      const auto& h = strategy->history();
      if (h.size() + done >= rule.max_evaluations) break;
      if (rule.target && done > 0 && values.head(done).minCoeff() <= *rule.target) break;
      values[done] = f(from_unit(variables, asked.row(done).transpose()));
      if (!std::isfinite(values[done]))
        throw std::runtime_error("minimise_expensive: the function returned NaN or infinity");
    }
    strategy->tell(asked.topRows(done), values.head(done));
  }
  const EvaluationHistory& h = strategy->history();
  r.evaluations = h.size();
  r.values = Eigen::Map<const VectorXd>(h.values().data(), h.size());
  r.points = MatrixXd(h.size(), dims);
  for (int i = 0; i < h.size(); ++i) r.points.row(i) = from_unit(variables, h.point(i)).transpose();
  r.x = from_unit(variables, h.best_point());
  r.value = h.best();
  r.best_so_far = h.best_so_far();
  r.stop_reason = to_string(stop_reason(h, rule));
  return r;
}

}  // namespace demfit::rbf_surrogate
