// bench_mpi_throughput RUNS SECONDS_PER_RUN
// Evaluates a fixed batch of RUNS evaluations of a CPU-bound stand-in model (the analytic curve
// family plus a fixed amount of arithmetic calibrated to SECONDS_PER_RUN on this machine), on
// rank 0 alone (1 rank) or over the other ranks. Prints one line "ranks R runs N seconds S
// runs_per_second X per_run_seconds T". The stand-in keeps the benchmark short and repeatable;
// a DEM run has the same shape (CPU-bound, no I/O), only longer.
#include <mpi.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "demfit/identify/analytic_model.hpp"
#include "demfit/scaleout/mpi_evaluator.hpp"

using namespace demfit;

namespace {

volatile double sink = 0.0;

void burn(long iterations) {
  double accumulator = 0.0;
  for (long i = 0; i < iterations; ++i) accumulator += std::sin(1e-6 * static_cast<double>(i));
  sink = accumulator;
}

class CostlyModel final : public identify::Model {
 public:
  explicit CostlyModel(long iterations) : iterations_(iterations) {}
  std::vector<identify::ParameterDescriptor> parameters() const override { return inner_.parameters(); }
  identify::ParameterSet default_parameters() const override { return inner_.default_parameters(); }
  identify::CurveSet evaluate(const identify::ParameterSet& p, const identify::EvaluationContext& c) const override {
    burn(iterations_);
    return inner_.evaluate(p, c);
  }

 private:
  identify::AnalyticCurveModel inner_{41};
  long iterations_;
};

long calibrate(double seconds) {
  const long probe = 2'000'000;
  const auto start = std::chrono::steady_clock::now();
  burn(probe);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return static_cast<long>(probe * seconds / elapsed);
}

}  // namespace

int main(int argc, char** argv) {
  scaleout::MpiSession session(argc, argv);
  const int runs = argc > 1 ? std::atoi(argv[1]) : 12;
  const double seconds_per_run = argc > 2 ? std::atof(argv[2]) : 0.5;
  long iterations = session.rank() == 0 ? calibrate(seconds_per_run) : 0;
  MPI_Bcast(&iterations, 1, MPI_LONG, 0, MPI_COMM_WORLD);
  const CostlyModel model(iterations);
  if (session.rank() != 0) {
    scaleout::run_worker(model, 1, 1);
    return 0;
  }
  std::vector<identify::ParameterSet> batch;
  for (int i = 0; i < runs; ++i) batch.push_back({{"a", 1.0 + 0.01 * i}});
  const auto start = std::chrono::steady_clock::now();
  double run_seconds = 0.0;
  if (session.size() == 1) {
    for (const auto& p : batch) run_seconds += identify::evaluate_safely(model, p, {1, 1}).wall_seconds;
  } else {
    scaleout::MpiEvaluator evaluator(session, {});
    for (const auto& outcome : evaluator.evaluate_points(model, batch, nullptr)) run_seconds += outcome.wall_seconds;
  }
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("ranks %d runs %d seconds %.3f runs_per_second %.3f per_run_seconds %.3f\n", session.size(), runs,
              elapsed, runs / elapsed, run_seconds / runs);
  return 0;
}
