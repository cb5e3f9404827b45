#pragma once
// What a confident-looking result may hide, computed from the study store alone and
// shown in report.md and on stderr:
//   - a variable at (within 0.5 % of) a bound: the optimum may lie outside the bounds,
//   - the study stopped at the iteration limit instead of converging,
//   - the verification run far from the surrogate's prediction (more than 50 % apart),
//   - the best run's misfit far above the noise of the data (RMS misfit > 3 x noise), where
//     the noise of a target is estimated from its second differences (sigma^2 = sum(d2^2)/(6(n-2))),
//   - runs far from quasi-static: a model that can check it returns a curve named
//     kQuasiStaticCurve whose y is the run's kinetic/elastic energy ratio divided by the case's own
//     limit (pellet compression: 1 %, docs/spec.md 2.1), so y > 1 means inertia, not the contact law,
//     shaped part of the measured curve,
// plus, per target, the RMS misfit of the best run in the curve's own units and as a multiple of
// that noise (the objective translated into physical terms).
#include <string>
#include <vector>

#include "demfit/identify/study_store.hpp"

namespace demfit::identify {

// Name of the optional quasi-static check curve (y = kinetic/elastic energy over the case's limit).
inline constexpr const char* kQuasiStaticCurve = "quasi_static_check";

struct TargetMisfit {
  std::string target;
  std::string y_label;
  double rms = 0.0;    // best run vs target at the target's x, in y_label units
  double noise = 0.0;  // estimated noise sigma of the target, same units
};

struct StudyDiagnostics {
  std::vector<TargetMisfit> misfits;  // mse targets whose curve the best run produced
  std::vector<std::string> warnings;  // one sentence each
};

StudyDiagnostics study_diagnostics(const StudySpec& spec, const std::vector<EvaluationRecord>& runs,
                                   const std::vector<IterationRecord>& iterations, const EvaluationRecord* best,
                                   const std::optional<nlohmann::json>& result);
StudyDiagnostics study_diagnostics(const StudyStore& store);

}  // namespace demfit::identify
