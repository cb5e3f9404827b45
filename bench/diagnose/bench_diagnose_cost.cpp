// Evaluations and wall time of one diagnosis on the analytic effects model (101 points,
// sigma 0.01, 3 base variables, 3 candidates), averaged over noise seeds, for each hidden effect.
// Prints a table; not run by ctest. Usage: bench_diagnose_cost [seeds (default 20)]
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "demfit/diagnose/analytic_effects_model.hpp"
#include "demfit/diagnose/effect.hpp"
#include "demfit/diagnose/workflow.hpp"

using namespace demfit;
using namespace demfit::diagnose;

namespace {

// Counts evaluations independently of the workflow's own bookkeeping.
class CountingModel final : public identify::Model {
 public:
  explicit CountingModel(const identify::Model& inner) : inner_(inner) {}
  std::vector<identify::ParameterDescriptor> parameters() const override { return inner_.parameters(); }
  identify::ParameterSet default_parameters() const override { return inner_.default_parameters(); }
  identify::CurveSet evaluate(const identify::ParameterSet& p, const identify::EvaluationContext& c) const override {
    ++count;
    return inner_.evaluate(p, c);
  }
  mutable std::atomic<long> count{0};

 private:
  const identify::Model& inner_;
};

}  // namespace

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 20;
  const std::vector<std::pair<std::string, double>> hidden{{"", 0.0},
                                                           {"stiffening_coefficient", 1.5},
                                                           {"toe_shift", 0.05},
                                                           {"yield_drop", 0.25},
                                                           {"ripple_amplitude", 0.03}};
  const AnalyticEffectsModel analytic(101);
  const CountingModel model(analytic);
  std::printf(
      "hidden effect            | mean evaluations (base / screening / re-fits) | max | named as hidden | ms per "
      "diagnosis\n");
  for (const auto& [parameter, value] : hidden) {
    double base = 0, screen = 0, refit = 0, total = 0, max_total = 0, seconds = 0;
    int correct = 0;
    for (int s = 0; s < seeds; ++s) {
      identify::ParameterSet truth{{"amplitude", 1.0}, {"rate", 3.0}, {"slope", 0.5}};
      if (!parameter.empty()) truth[parameter] = value;
      const long before = model.count;
      const auto start = std::chrono::steady_clock::now();
      const Diagnosis d = run_diagnosis(analytic_effects_study(truth, 1000 + s, 0.01), model,
                                        analytic_effect_candidates(), DiagnoseOptions{});
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      base += d.base_evaluations;
      screen += d.screening_evaluations;
      refit += d.refit_evaluations;
      const long counted = model.count - before;
      if (counted != d.evaluations)
        std::printf("warning: counted %ld evaluations, the diagnosis reports %d\n", counted, d.evaluations);
      total += static_cast<double>(counted);
      max_total = std::max<double>(max_total, static_cast<double>(counted));
      const std::string named = d.chosen >= 0 ? d.refits[d.chosen].effect : "";
      const bool right = parameter.empty() || parameter == "ripple_amplitude" ? named.empty()
                         : parameter == "stiffening_coefficient"              ? named == "stiffening"
                                                                              : named == parameter;
      correct += right;
    }
    std::printf("%-24s | %6.1f (%5.1f / %4.1f / %5.1f)                  | %4.0f | %d/%d | %.2f\n",
                parameter.empty() ? "none" : parameter.c_str(), total / seeds, base / seeds, screen / seeds,
                refit / seeds, max_total, correct, seeds, 1e3 * seconds / seeds);
  }
  return 0;
}
