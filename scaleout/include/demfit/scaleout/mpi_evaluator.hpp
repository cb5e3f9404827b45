#pragma once
// Rank 0's side of `demfit identify --mpi`: an identify::Evaluator whose jobs run on the other
// ranks. Scheduling is dynamic (a free worker takes the next run), so a run costing 10x another
// does not hold a batch back. Outcomes are returned by batch index, so the loop sees exactly what
// a --jobs run would see (same seed -> same design points and answer).
//
// Faults: a worker that does not answer within the per-run timeout (it died or hangs) is retired;
// its run is retried once on another worker, then recorded as failed. When no worker is left the
// remaining runs are recorded as failed with a message saying so.
#include <string>
#include <vector>

#include "demfit/identify/evaluator.hpp"
#include "demfit/scaleout/mpi_session.hpp"

namespace demfit::scaleout {

struct MpiEvaluatorOptions {
  // Seconds a run may take before its worker is considered dead or hung. <= 0: automatic, i.e.
  // max(minimum_timeout, timeout_factor x the longest successful run so far).
  double run_timeout_seconds = 0.0;
  double minimum_timeout_seconds = 120.0;
  double timeout_factor = 10.0;
  int attempts = 2;  // first try + one retry elsewhere
};

class MpiEvaluator final : public identify::Evaluator {
 public:
  MpiEvaluator(MpiSession& session, MpiEvaluatorOptions options);
  ~MpiEvaluator() override;  // tells the live workers to stop
  std::vector<identify::EvaluationOutcome> evaluate_jobs(const std::vector<identify::EvaluationJob>& batch,
                                                         const DoneCallback& on_done) override;
  int concurrency() const override;
  int live_workers() const;

 private:
  struct Running;
  double current_timeout() const;
  void retire(int worker, const std::string& why);

  MpiSession& session_;
  MpiEvaluatorOptions options_;
  std::vector<bool> alive_;  // by rank; rank 0 is the loop itself
  double longest_run_seconds_ = 0.0;
};

// The other ranks: receive jobs, evaluate them with the job's experiment of the model
// (identify::experiment_models), send the outcomes back, until rank 0 says stop.
// `threads_per_job` OpenMP threads per run.
void run_worker(const identify::Model& model, int threads_per_job, unsigned long seed);

// Message tags shared by both sides.
inline constexpr int tag_job = 11;
inline constexpr int tag_outcome = 12;
inline constexpr int tag_stop = 13;

}  // namespace demfit::scaleout
