#pragma once
// MPI start-up and shut-down for `demfit identify --mpi`.
//
// Fault tolerance without ULFM: Open MPI 4 keeps the job alive when a rank dies only if mpirun
// is started with --enable-recovery; ranks then use MPI_ERRORS_RETURN and rank 0 detects a dead
// or hung worker by a per-run timeout. A job that lost a rank cannot call MPI_Finalize safely
// (it waits for the lost rank), so the session then ends the process directly after the caller
// has flushed its files (every evaluation is already committed to the study store).
namespace demfit::scaleout {

class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  // Called by rank 0 when a worker was lost: finalisation must not wait for it.
  void mark_peer_lost() { peer_lost_ = true; }
  // Ends MPI; if a peer was lost, flushes stdio and exits the process with `exit_code`.
  void finish(int exit_code);
  // Ends the whole job with `exit_code` (MPI_Abort): rank 0's fatal error. Exiting rank 0 alone
  // was reported by mpirun --enable-recovery as success (exit status 0).
  [[noreturn]] void abort_job(int exit_code);

 private:
  int rank_ = 0;
  int size_ = 1;
  bool peer_lost_ = false;
  bool finished_ = false;
};

}  // namespace demfit::scaleout
