// The "expected_improvement" study strategy: batch expected improvement on the composite objective
// (rbf_surrogate/strategy.hpp), driven by the study loop through ask/tell.
#include "study_strategy.hpp"

#include "demfit/rbf_surrogate/design.hpp"

namespace demfit::identify::detail {

namespace {

rbf_surrogate::ExpensiveOptions study_options(const StudySpec& spec, const rbf_surrogate::FidelityLevel& cheap_level) {
  rbf_surrogate::ExpensiveOptions o;
  o.strategy = rbf_surrogate::InfillStrategy::expected_improvement;
  o.seed = spec.seed;
  // Simulated objectives carry trajectory noise (a tiny parameter change gives another packing):
  // the nugget is estimated, and the incumbent is the lowest predicted mean at a run, not the
  // luckiest run. On noise-free models the likelihood drives the nugget to its floor.
  o.kriging.estimate_noise = true;
  o.lower_fidelity = cheap_level;
  return o;
}

}  // namespace

StudyStrategy::StudyStrategy(const StudySpec& spec, int dims, const rbf_surrogate::FidelityLevel& cheap_level)
    : strategy_(rbf_surrogate::make_strategy(dims, study_options(spec, cheap_level))), dims_(dims) {}

void StudyStrategy::tell(const Eigen::MatrixXd& unit_points, const Eigen::VectorXd& objectives) {
  strategy_->tell(unit_points, objectives);
}

Eigen::MatrixXd StudyStrategy::ask(int count, const Eigen::MatrixXd& planned, std::uint64_t seed) {
  Eigen::MatrixXd out(count, dims_);
  int n = 0;
  const auto close_to = [](const Eigen::MatrixXd& rows, int upto, const Eigen::VectorXd& x) {
    for (int i = 0; i < upto; ++i)
      if ((rows.row(i).transpose() - x).norm() < 1e-5) return true;
    return false;
  };
  if (count > 0) {
    const Eigen::MatrixXd asked = strategy_->ask(count);
    for (Eigen::Index i = 0; i < asked.rows() && n < count; ++i) {
      const Eigen::VectorXd x = asked.row(i).transpose();
      if (close_to(planned, static_cast<int>(planned.rows()), x)) continue;
      out.row(n++) = x.transpose();
    }
  }
  if (n < count) {  // the strategy returned fewer (duplicates): maximin over everything run or planned
    const auto& h = strategy_->history();
    Eigen::MatrixXd existing(h.size() + planned.rows() + n, dims_);
    existing << h.all_points(), planned, out.topRows(n);
    out.bottomRows(count - n) =
        rbf_surrogate::space_filling_augment(existing, count - n, rbf_surrogate::Box::unit(dims_), seed);
  }
  return out;
}

std::unique_ptr<StudyStrategy> make_study_strategy(const StudySpec& spec,
                                                   const rbf_surrogate::FidelityLevel& cheap_level) {
  if (spec.strategy != SamplingStrategy::expected_improvement) return nullptr;
  return std::make_unique<StudyStrategy>(spec, static_cast<int>(spec.variables.size()), cheap_level);
}

}  // namespace demfit::identify::detail

namespace demfit::identify {

const char* strategy_name(SamplingStrategy strategy) {
  switch (strategy) {
    case SamplingStrategy::srsm:
      return "srsm";
    case SamplingStrategy::adaptive_infill:
      return "adaptive_infill";
    default:
      return "expected_improvement";
  }
}

}  // namespace demfit::identify

namespace demfit::identify::detail {

nlohmann::json posterior_json(const StudySpec& spec, const RunSample& sample, const std::filesystem::path& output_dir,
                              bool plots, std::string& warning) {
  PosteriorOptions options;
  options.seed = spec.seed;
  PosteriorEstimate e;
  try {
    e = sample_posterior_from_runs(sample, spec.variables, options);
  } catch (const std::invalid_argument& error) {
    warning = error.what();
    return nullptr;
  }
  nlohmann::json variables = nlohmann::json::object();
  for (std::size_t j = 0; j < spec.variables.size(); ++j)
    variables[spec.variables[j].name] = {{"median", e.median[j]},
                                         {"lower_95", e.lower[j]},
                                         {"upper_95", e.upper[j]},
                                         {"unidentifiable", static_cast<bool>(e.unidentifiable[j])}};
  std::vector<std::vector<double>> correlation(spec.variables.size(), std::vector<double>(spec.variables.size()));
  for (std::size_t i = 0; i < correlation.size(); ++i)
    for (std::size_t j = 0; j < correlation.size(); ++j)
      correlation[i][j] = e.correlation(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
  nlohmann::json out = {{"method", "Gibbs sampling of the posterior on the local linear residual surrogate"},
                        {"variables", variables},
                        {"correlation", correlation},
                        {"simulation_noise_variance", e.simulation_noise_variance},
                        {"data_noise_variance", e.data_noise_variance},
                        {"runs_used", e.runs_used}};
  if (plots) {
    warning = write_posterior_pair_plot(e, spec.variables, output_dir / "posterior_pairs.png");
    if (warning.empty()) out["pair_plot"] = "posterior_pairs.png";
  }
  return out;
}

}  // namespace demfit::identify::detail
