#include "demfit/scaleout/mpi_evaluator.hpp"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <deque>
#include <exception>
#include <iostream>
#include <map>
#include <stdexcept>
#include <thread>

#include "demfit/scaleout/wire_format.hpp"

namespace demfit::scaleout {
namespace {

using Clock = std::chrono::steady_clock;

std::string index_prefix(std::size_t index) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%08zu", index);
  return std::string(buffer, 8);
}

}  // namespace

struct MpiEvaluator::Running {
  std::size_t index;
  Clock::time_point started;
};

MpiEvaluator::MpiEvaluator(MpiSession& session, MpiEvaluatorOptions options)
    : session_(session), options_(options), alive_(static_cast<std::size_t>(session.size()), true) {
  if (session.rank() != 0) throw std::logic_error("MpiEvaluator lives on rank 0 only");
  if (session.size() < 2) {
    throw std::runtime_error(
        "--mpi needs at least 2 ranks (rank 0 runs the loop, the others evaluate): "
        "start with mpirun -np K, K >= 2");
  }
  alive_[0] = false;  // rank 0 runs the loop, not simulations
}

MpiEvaluator::~MpiEvaluator() {
  // 'L': a rank was lost, so MPI_Finalize could wait for it forever: workers leave without it.
  const char how = live_workers() + 1 < session_.size() ? 'L' : 'C';
  for (int worker = 1; worker < session_.size(); ++worker) {
    if (alive_[static_cast<std::size_t>(worker)]) MPI_Send(&how, 1, MPI_CHAR, worker, tag_stop, MPI_COMM_WORLD);
  }
}

int MpiEvaluator::concurrency() const { return std::max(1, live_workers()); }

int MpiEvaluator::live_workers() const { return static_cast<int>(std::count(alive_.begin(), alive_.end(), true)); }

double MpiEvaluator::current_timeout() const {
  if (options_.run_timeout_seconds > 0.0) return options_.run_timeout_seconds;
  return std::max(options_.minimum_timeout_seconds, options_.timeout_factor * longest_run_seconds_);
}

void MpiEvaluator::retire(int worker, const std::string& why) {
  alive_[static_cast<std::size_t>(worker)] = false;
  session_.mark_peer_lost();
  // A hung worker still listens on its MPI thread: tell it to leave (no wait if it is dead).
  MPI_Request request;
  static const char lost = 'L';  // static: the send may complete after this function returns
  if (MPI_Isend(&lost, 1, MPI_CHAR, worker, tag_stop, MPI_COMM_WORLD, &request) == MPI_SUCCESS) {
    MPI_Request_free(&request);
  }
  std::cerr << "demfit: warning: MPI rank " << worker << " retired (" << why << "); " << live_workers()
            << " worker(s) left\n";
}

std::vector<identify::EvaluationOutcome> MpiEvaluator::evaluate_jobs(const std::vector<identify::EvaluationJob>& batch,
                                                                     const DoneCallback& on_done) {
  std::vector<identify::EvaluationOutcome> outcomes(batch.size());
  std::vector<int> attempts(batch.size(), 0);
  std::deque<std::size_t> pending;
  for (std::size_t i = 0; i < batch.size(); ++i) pending.push_back(i);
  std::map<int, Running> running;  // by worker rank
  std::exception_ptr failure;
  std::size_t completed = 0;

  auto complete = [&](std::size_t index, identify::EvaluationOutcome outcome) {
    outcomes[index] = std::move(outcome);
    ++completed;
    if (failure) return;
    try {
      if (on_done) on_done(index, outcomes[index]);
    } catch (...) {
      failure = std::current_exception();  // start nothing new; let the running ones finish
      completed += pending.size();
      pending.clear();
    }
  };

  while (completed < batch.size()) {
    for (int worker = 1; worker < session_.size() && !pending.empty(); ++worker) {
      if (!alive_[static_cast<std::size_t>(worker)] || running.count(worker)) continue;
      const std::size_t index = pending.front();
      pending.pop_front();
      ++attempts[index];
      const std::string message = index_prefix(index) + encode_job(batch[index]);
      MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, worker, tag_job, MPI_COMM_WORLD);
      running[worker] = Running{index, Clock::now()};
    }
    if (running.empty() && !pending.empty()) {  // nobody left to run them
      while (!pending.empty()) {
        const std::size_t index = pending.front();
        pending.pop_front();
        identify::EvaluationOutcome lost;
        lost.error = "no live MPI worker left to run this evaluation";
        complete(index, std::move(lost));
      }
      continue;
    }
    int arrived = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, tag_outcome, MPI_COMM_WORLD, &arrived, &status);
    if (arrived) {
      int length = 0;
      MPI_Get_count(&status, MPI_CHAR, &length);
      std::string reply(static_cast<std::size_t>(length), '\0');
      MPI_Recv(reply.data(), length, MPI_CHAR, status.MPI_SOURCE, tag_outcome, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      const auto it = running.find(status.MPI_SOURCE);
      // A late answer from a retired worker, or one not matching its run, is ignored.
      if (it == running.end() || reply.size() < 8 || reply.substr(0, 8) != index_prefix(it->second.index)) continue;
      const std::size_t index = it->second.index;
      running.erase(it);
      identify::EvaluationOutcome outcome = decode_outcome(reply.substr(8));
      if (outcome.ok) longest_run_seconds_ = std::max(longest_run_seconds_, outcome.wall_seconds);
      complete(index, std::move(outcome));
      continue;
    }
    const double timeout = current_timeout();
    for (auto it = running.begin(); it != running.end();) {
      const double elapsed = std::chrono::duration<double>(Clock::now() - it->second.started).count();
      if (elapsed <= timeout) {
        ++it;
        continue;
      }
      const std::size_t index = it->second.index;
      const int worker = it->first;
      it = running.erase(it);
      retire(worker, "no answer after " + std::to_string(elapsed) + " s: died or hung");
      if (failure) {
        ++completed;
      } else if (attempts[index] < options_.attempts) {
        pending.push_front(index);  // retried once elsewhere
      } else {
        identify::EvaluationOutcome lost;
        lost.error = "lost twice: worker died or exceeded the per-run timeout of " + std::to_string(timeout) + " s";
        complete(index, std::move(lost));
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (failure) std::rethrow_exception(failure);
  return outcomes;
}

}  // namespace demfit::scaleout
