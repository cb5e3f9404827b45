#include "demfit/scaleout/mpi_session.hpp"

#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <stdexcept>

namespace demfit::scaleout {

MpiSession::MpiSession(int& argc, char**& argv) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  int provided = 0;
  // FUNNELED: a worker evaluates on a second thread, but only its main thread calls MPI.
  if (!initialised && MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
    throw std::runtime_error("--mpi: MPI_Init failed; start demfit with mpirun (Open MPI)");
  }
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

void MpiSession::finish(int exit_code) {
  if (finished_) return;
  finished_ = true;
  if (peer_lost_) {
    std::cout.flush();
    std::cerr.flush();
    std::fflush(nullptr);
    std::_Exit(exit_code);
  }
  MPI_Finalize();
}

void MpiSession::abort_job(int exit_code) {
  finished_ = true;
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  MPI_Abort(MPI_COMM_WORLD, exit_code);
  std::_Exit(exit_code);  // MPI_Abort returned (it should not)
}

MpiSession::~MpiSession() { finish(0); }

}  // namespace demfit::scaleout
