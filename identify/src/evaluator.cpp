#include "demfit/identify/evaluator.hpp"

#include "demfit/identify/experiments.hpp"

#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <string>
#include <thread>

namespace demfit::identify {

EvaluationOutcome evaluate_safely(const Model& model, const ParameterSet& parameters,
                                  const EvaluationContext& context) {
  EvaluationOutcome outcome;
  const auto start = std::chrono::steady_clock::now();
  try {
    outcome.curves = model.evaluate(parameters, context);
    outcome.ok = true;
  } catch (const std::exception& e) { outcome.error = e.what(); } catch (...) {
    outcome.error = "unknown exception in the model";
  }
  // One line: error messages go into CSV files and progress lines.
  for (char& c : outcome.error)
    if (c == '\n' || c == '\r') c = ' ';
  outcome.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return outcome;
}

std::vector<EvaluationOutcome> Evaluator::evaluate_points(const Model& model, const std::vector<ParameterSet>& points,
                                                          const DoneCallback& on_done) {
  PointJobs jobs(model, points);
  std::vector<EvaluationOutcome> outcomes(points.size());
  evaluate_jobs(jobs.jobs(), [&](std::size_t index, const EvaluationOutcome& part) {
    std::size_t point = 0;
    EvaluationOutcome outcome;
    if (!jobs.finish(index, part, point, outcome)) return;
    outcomes[point] = outcome;
    if (on_done) on_done(point, outcomes[point]);
  });
  return outcomes;
}

ThreadPoolEvaluator::ThreadPoolEvaluator(const Model& model, int jobs, int threads_per_job, unsigned long seed)
    : models_(experiment_models(model)),
      jobs_(jobs < 1 ? 1 : jobs),
      threads_per_job_(threads_per_job < 1 ? 1 : threads_per_job),
      seed_(seed) {}

std::vector<EvaluationOutcome> ThreadPoolEvaluator::evaluate_jobs(const std::vector<EvaluationJob>& batch,
                                                                  const DoneCallback& on_done) {
  std::vector<EvaluationOutcome> outcomes(batch.size());
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex callback_mutex;
  std::exception_ptr failure;
  const EvaluationContext context{threads_per_job_, seed_};
  auto worker = [&] {
    while (!stop.load()) {
      const std::size_t index = next.fetch_add(1);
      if (index >= batch.size()) return;
      const EvaluationJob& job = batch[index];
      if (job.experiment < models_.size()) {
        outcomes[index] = evaluate_safely(*models_[job.experiment], job.parameters, context);
      } else {
        outcomes[index].error = "job names experiment " + std::to_string(job.experiment) + " of a model with " +
                                std::to_string(models_.size());
      }
      std::lock_guard<std::mutex> lock(callback_mutex);
      if (stop.load()) return;
      try {
        if (on_done) on_done(index, outcomes[index]);
      } catch (...) {
        failure = std::current_exception();
        stop.store(true);
        return;
      }
    }
  };
  const int workers = static_cast<int>(std::min<std::size_t>(jobs_, batch.size()));
  if (workers <= 1) {
    worker();
  } else {
    std::vector<std::thread> threads;
    for (int i = 0; i < workers; ++i) threads.emplace_back(worker);
    for (auto& t : threads) t.join();
  }
  if (failure) std::rethrow_exception(failure);
  return outcomes;
}

}  // namespace demfit::identify
