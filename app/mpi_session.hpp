#pragma once
// `somasim run` as one rank of an MPI job (OpenMPI; README "MPI"). MPI is initialised only when
// this process was started by an MPI launcher (mpirun, or srun --mpi=pmix: their environment
// names the rank); a plain `somasim run` never touches MPI. Every rank runs the same
// deterministic experiment; nodes that know MPI (body_schema_filter with `distribute: mpi`) share
// their work over MPI_COMM_WORLD. Rank 0 writes the run folder the user asked for; ranks > 0
// write theirs into a private scratch folder that is removed at the end.
//
// Failures: a rank that fails while the others may be waiting for it in a collective operation
// would hang the job, so any failure on any rank ends the whole job with MPI_Abort (after the
// rank printed its error); mpirun then exits non-zero.
#include <filesystem>
#include <string>

namespace somasim::app {

/// Whether the environment says this process is one rank of an MPI job (OMPI_COMM_WORLD_SIZE
/// from OpenMPI's mpirun, or PMIX_RANK from a PMIx launcher such as srun --mpi=pmix).
bool launched_as_mpi_rank();

class MpiSession {
 public:
  /// Initialises MPI (thread level funneled: only the main thread calls MPI) when
  /// launched_as_mpi_rank(); otherwise does nothing. Throws RunError when MPI cannot start.
  MpiSession();
  /// Removes the scratch folder and finalises MPI; while an exception is unwinding (a failure
  /// that was not reported through end()), aborts the job instead of waiting for the others.
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  MpiSession(MpiSession&&) = delete;
  MpiSession& operator=(MpiSession&&) = delete;

  bool active() const { return size_ > 0; }
  int rank() const { return rank_; }  ///< 0 when not active
  int size() const { return size_; }  ///< 0 when not active
  bool is_root() const { return rank_ == 0; }

  /// This rank's run folder: `out` on rank 0 (and without MPI), a fresh private scratch folder
  /// on ranks > 0 (removed by the destructor). Throws RunError when it cannot be made.
  std::filesystem::path run_folder(const std::filesystem::path& out);

  /// A rank's exit code at the end of its run: returned as is when 0 or without MPI; any other
  /// code ends the whole job (MPI_Abort with that code), so no rank waits for this one forever.
  int end(int exit_code);

 private:
  [[noreturn]] void abort_job(int exit_code);
  void remove_scratch();

  int rank_ = 0;
  int size_ = 0;
  std::filesystem::path scratch_;
};

}  // namespace somasim::app
