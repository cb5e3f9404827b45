#pragma once
// Evaluating batches of parameter sets. The loop only sees Evaluator: submit a batch, get the
// outcomes back in submission order. ThreadPoolEvaluator runs up to `jobs` simulations at once
// in this process; an MPI evaluator implements the same interface with ranks.
// Results never depend on the number of jobs: each evaluation is independent and outcomes are
// returned by index, whatever order they finish in.
#include <functional>
#include <string>
#include <vector>

#include "demfit/identify/model.hpp"

namespace demfit::identify {

struct EvaluationOutcome {
  bool ok = false;
  CurveSet curves;    // empty when !ok
  std::string error;  // one line, when !ok
  double wall_seconds = 0.0;
};

// One unit of work: a parameter set for one experiment's model (experiments.hpp; 0 = the model
// itself when it is not an ExperimentSetModel). The parameters are complete for that model.
struct EvaluationJob {
  std::size_t experiment = 0;
  ParameterSet parameters;
};

class Evaluator {
 public:
  virtual ~Evaluator() = default;
  // Called once per finished evaluation, serialised (never concurrently), with the batch index.
  // If it throws, no further evaluation of the batch is started and evaluate_jobs rethrows
  // after the running ones finish.
  using DoneCallback = std::function<void(std::size_t index, const EvaluationOutcome&)>;
  virtual std::vector<EvaluationOutcome> evaluate_jobs(const std::vector<EvaluationJob>& jobs,
                                                       const DoneCallback& on_done) = 0;
  // Complete design points of `model` (the model this evaluator was built for): a point of an
  // experiments model is split into one job per experiment (experiments.hpp PointJobs), so its
  // experiments run in parallel too; outcomes and on_done are per point, with the curves of all
  // its experiments. on_done is called when a point's last experiment finishes.
  std::vector<EvaluationOutcome> evaluate_points(const Model& model, const std::vector<ParameterSet>& points,
                                                 const DoneCallback& on_done);
  virtual int concurrency() const = 0;
};

// Threads of this process. A job runs experiment_models(model)[job.experiment]; each calls Model::evaluate with
// EvaluationContext{threads_per_job, seed}; the caller chooses threads_per_job (the CLI default is 1, so `--jobs` uses
// `jobs` cores; set jobs x threads_per_job <= cores). A model exception becomes a failed outcome with its message.
class ThreadPoolEvaluator final : public Evaluator {
 public:
  ThreadPoolEvaluator(const Model& model, int jobs, int threads_per_job, unsigned long seed);
  std::vector<EvaluationOutcome> evaluate_jobs(const std::vector<EvaluationJob>& jobs,
                                               const DoneCallback& on_done) override;
  int concurrency() const override { return jobs_; }

 private:
  std::vector<const Model*> models_;  // by experiment index
  int jobs_;
  int threads_per_job_;
  unsigned long seed_;
};

// Evaluates one parameter set, catching every exception into the outcome (shared by evaluators).
EvaluationOutcome evaluate_safely(const Model& model, const ParameterSet& parameters, const EvaluationContext& context);

}  // namespace demfit::identify
