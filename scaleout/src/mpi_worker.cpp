#include <mpi.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <thread>

#include "demfit/identify/experiments.hpp"
#include "demfit/scaleout/mpi_evaluator.hpp"
#include "demfit/scaleout/wire_format.hpp"

namespace demfit::scaleout {
namespace {

std::string receive_text(int source, int tag, MPI_Status& status) {
  int length = 0;
  MPI_Get_count(&status, MPI_CHAR, &length);
  std::string text(static_cast<std::size_t>(length), '\0');
  MPI_Recv(text.data(), length, MPI_CHAR, source, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return text;
}

// Fault injection for the scale-out tests (documented in README): the worker with rank
// DEMFIT_TEST_FAULT_RANK dies (SIGKILL) or hangs when it receives its
// DEMFIT_TEST_FAULT_AFTER-th run, as selected by DEMFIT_TEST_FAULT=kill|hang.
void maybe_inject_fault(int rank, int runs_received, bool in_evaluation) {
  const char* fault = std::getenv("DEMFIT_TEST_FAULT");
  const char* fault_rank = std::getenv("DEMFIT_TEST_FAULT_RANK");
  const char* fault_after = std::getenv("DEMFIT_TEST_FAULT_AFTER");
  if (!fault || !fault_rank || !fault_after) return;
  if (std::atoi(fault_rank) != rank || std::atoi(fault_after) != runs_received) return;
  if (!in_evaluation && std::string(fault) == "kill") std::raise(SIGKILL);
  if (in_evaluation && std::string(fault) == "hang") {
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
  }
}

}  // namespace

void run_worker(const identify::Model& model, int threads_per_job, unsigned long seed) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const identify::EvaluationContext context{threads_per_job, seed};
  const std::vector<const identify::Model*> experiments = identify::experiment_models(model);
  int runs_received = 0;
  for (;;) {
    MPI_Status status;
    if (MPI_Probe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &status) != MPI_SUCCESS) return;  // rank 0 gone
    const std::string text = receive_text(0, status.MPI_TAG, status);
    if (status.MPI_TAG == tag_stop) {
      if (text == "L") {  // a peer was lost: finalising would wait for it
        std::fflush(nullptr);
        std::_Exit(0);
      }
      return;
    }
    maybe_inject_fault(rank, ++runs_received, false);
    // The first 8 bytes carry the run's batch index, echoed back so rank 0 can match answers.
    const std::string index_prefix = text.substr(0, 8);
    identify::EvaluationOutcome outcome;
    // The simulation runs on its own thread so that this (MPI) thread can still hear rank 0
    // give up on a run that hangs: the worker then leaves at once instead of blocking mpirun.
    std::atomic<bool> finished{false};
    std::thread evaluation([&] {
      maybe_inject_fault(rank, runs_received, true);
      try {
        const identify::EvaluationJob job = decode_job(text.substr(8));
        if (job.experiment >= experiments.size())
          throw std::runtime_error("experiment " + std::to_string(job.experiment) + " does not exist here");
        outcome = identify::evaluate_safely(*experiments[job.experiment], job.parameters, context);
      } catch (const std::exception& e) {
        outcome.ok = false;
        outcome.error = std::string("malformed run message on worker: ") + e.what();
      }
      finished.store(true);
    });
    while (!finished.load()) {
      int stop = 0;
      MPI_Iprobe(0, tag_stop, MPI_COMM_WORLD, &stop, MPI_STATUS_IGNORE);
      if (stop) std::_Exit(0);  // retired by rank 0 while hung; its run is retried elsewhere
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    evaluation.join();
    const std::string reply = index_prefix + encode_outcome(outcome);
    MPI_Send(reply.data(), static_cast<int>(reply.size()), MPI_CHAR, 0, tag_outcome, MPI_COMM_WORLD);
  }
}

}  // namespace demfit::scaleout
