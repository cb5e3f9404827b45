// Run under mpirun -np 3: rank 0 sends a batch of analytic-model runs to ranks 1-2 and checks
// every outcome against the same run evaluated locally (bitwise). With DEMFIT_TEST_FAULT=kill
// or hang (rank 2, second run), the lost run must be retried on rank 1 and the batch complete
// with identical results. Prints "N passed, M failed" and exits non-zero on any mismatch.
#include <cstdio>
#include <cstring>
#include <cstdlib>

#include "demfit/identify/analytic_model.hpp"
#include "demfit/scaleout/mpi_evaluator.hpp"

using namespace demfit;

namespace {

bool identical(const identify::EvaluationOutcome& a, const identify::EvaluationOutcome& b) {
  if (a.ok != b.ok || a.curves.size() != b.curves.size()) return false;
  for (const auto& [name, curve] : a.curves) {
    const auto it = b.curves.find(name);
    if (it == b.curves.end() || curve.x.size() != it->second.x.size() || curve.y.size() != it->second.y.size())
      return false;
    if (std::memcmp(curve.x.data(), it->second.x.data(), curve.x.size() * sizeof(double)) != 0) return false;
    if (std::memcmp(curve.y.data(), it->second.y.data(), curve.y.size() * sizeof(double)) != 0) return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  scaleout::MpiSession session(argc, argv);
  const identify::AnalyticCurveModel model(41);
  if (session.rank() != 0) {
    scaleout::run_worker(model, 1, 7);
    session.finish(0);
    return 0;
  }
  std::vector<identify::ParameterSet> batch;
  for (int i = 0; i < 12; ++i) batch.push_back({{"a", 1.0 + 0.1 * i}, {"r", 2.0 + 0.37 * i}, {"b", 0.05 * i}});
  batch.push_back({{"a", 1.0}, {"unknown_parameter", 1.0}});  // a model failure travels back as one
  int passed = 0, failed = 0, callbacks = 0;
  std::vector<identify::EvaluationOutcome> outcomes;
  {
    scaleout::MpiEvaluatorOptions options;
    options.run_timeout_seconds = 5.0;  // a hung worker is given up after 5 s
    scaleout::MpiEvaluator evaluator(session, options);
    outcomes =
        evaluator.evaluate_points(model, batch, [&](std::size_t, const identify::EvaluationOutcome&) { ++callbacks; });
  }
  const identify::EvaluationContext context{1, 7};
  for (std::size_t i = 0; i + 1 < batch.size(); ++i) {
    const bool same = identical(outcomes[i], identify::evaluate_safely(model, batch[i], context));
    same ? ++passed : ++failed;
    if (!same) std::printf("run %zu differs from the local evaluation: %s\n", i, outcomes[i].error.c_str());
  }
  const bool failure_reported = !outcomes.back().ok && !outcomes.back().error.empty() &&
                                outcomes.back().error.find("no live MPI worker") == std::string::npos;
  failure_reported ? ++passed : ++failed;
  (callbacks == static_cast<int>(batch.size())) ? ++passed : ++failed;
  std::printf("%d passed, %d failed\n", passed, failed);
  std::fflush(stdout);
  session.finish(failed == 0 ? 0 : 1);
  return failed == 0 ? 0 : 1;
}
