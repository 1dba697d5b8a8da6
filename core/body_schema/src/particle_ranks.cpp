#include "somasim/body_schema/particle_ranks.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "somasim/error.hpp"

namespace somasim::body_schema {

ParticleShare particle_share(int particles, int ranks, int rank) {
  const int base = particles / ranks;
  const int extra = particles % ranks;
  return {rank * base + std::min(rank, extra), base + (rank < extra ? 1 : 0)};
}

bool ParticleRanks::mpi_running() {
  int initialised = 0;
  int finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  return initialised != 0 && finalised == 0;
}

ParticleRanks::ParticleRanks() {
  MPI_Comm_dup(MPI_COMM_WORLD, &comm_);
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

ParticleRanks::~ParticleRanks() {
  if (comm_ != MPI_COMM_NULL && mpi_running()) MPI_Comm_free(&comm_);
}

std::vector<double> ParticleRanks::gather(const std::vector<double>& local, int particles) const {
  std::vector<int> counts(static_cast<std::size_t>(size_));
  std::vector<int> offsets(static_cast<std::size_t>(size_));
  for (int r = 0; r < size_; ++r) {
    const ParticleShare s = particle_share(particles, size_, r);
    counts[static_cast<std::size_t>(r)] = s.count;
    offsets[static_cast<std::size_t>(r)] = s.begin;
  }
  if (static_cast<int>(local.size()) != counts[static_cast<std::size_t>(rank_)])
    throw RunError(fmt::format("particle ranks: rank {} scored {} particles, its share is {}",
                               rank_, local.size(), counts[static_cast<std::size_t>(rank_)]));
  std::vector<double> all(static_cast<std::size_t>(particles));
  const int rc = MPI_Allgatherv(local.data(), static_cast<int>(local.size()), MPI_DOUBLE,
                                all.data(), counts.data(), offsets.data(), MPI_DOUBLE, comm_);
  if (rc != MPI_SUCCESS)
    throw RunError(fmt::format("particle ranks: MPI_Allgatherv failed (error {})", rc));
  return all;
}

}  // namespace somasim::body_schema
