#include "mpi_session.hpp"

#include <mpi.h>

#include <cstdio>
#include <cstdlib>  // getenv, mkdtemp (POSIX)
#include <exception>
#include <string>

#include "somasim/error.hpp"

// Linking: this executable links libmpi itself (the calls below), so libmpi is loaded at start-up
// into the global symbol scope. Plugins that use MPI (body_schema) are dlopen'ed later with
// RTLD_LOCAL; had libmpi first come in as their dependency, it would be local to them, and
// OpenMPI's own components (mca_*.so, which libmpi dlopens) could fail to resolve libmpi's
// symbols ("undefined symbol: ompi_..."). Being NEEDED by the executable rules that out, whatever
// the plugin loader's flags.

namespace somasim::app {

bool launched_as_mpi_rank() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr;
}

MpiSession::MpiSession() {
  if (!launched_as_mpi_rank()) return;
  int provided = 0;
  if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    throw RunError("cannot initialise MPI (launched by mpirun, but MPI_Init_thread failed)");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  if (!active()) return;
  if (std::uncaught_exceptions() > 0) abort_job(1);  // the others may wait for this rank
  remove_scratch();
  MPI_Finalize();
}

std::filesystem::path MpiSession::run_folder(const std::filesystem::path& out) {
  if (rank_ == 0) return out;
  if (scratch_.empty()) {
    std::string dir = (std::filesystem::temp_directory_path() /
                       ("somasim-rank" + std::to_string(rank_) + "-XXXXXX"))
                          .string();
    if (::mkdtemp(dir.data()) == nullptr)
      throw RunError("MPI rank " + std::to_string(rank_) +
                     ": cannot create a scratch run folder in " +
                     std::filesystem::temp_directory_path().string());
    scratch_ = dir;
  }
  return scratch_;
}

int MpiSession::end(int exit_code) {
  if (!active() || exit_code == 0) return exit_code;
  abort_job(exit_code);
}

void MpiSession::abort_job(int exit_code) {
  std::fflush(stdout);
  std::fflush(stderr);
  remove_scratch();
  MPI_Abort(MPI_COMM_WORLD, exit_code);
  std::_Exit(exit_code);  // MPI_Abort does not return; in case it does
}

void MpiSession::remove_scratch() {
  if (scratch_.empty()) return;
  std::error_code ec;
  std::filesystem::remove_all(scratch_, ec);
  scratch_.clear();
}

}  // namespace somasim::app
