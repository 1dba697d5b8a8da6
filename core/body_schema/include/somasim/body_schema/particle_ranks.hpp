#pragma once
/// @file
/// body_schema_filter `distribute: mpi`: one filter's particles spread over the ranks of an MPI
/// job (`mpirun -n K somasim run ...`; app/mpi_session.hpp starts MPI). Every rank runs the same
/// deterministic experiment and holds the same particles; each renders and scores its contiguous
/// share, and the likelihoods are gathered on every rank in particle order (MPI_Allgatherv of
/// doubles), so prediction, resampling, the estimate and every random draw run identically on
/// all ranks from the full vector.
#include <mpi.h>

#include <vector>

namespace somasim::body_schema {

/// Particles [begin, begin + count) of one rank.
struct ParticleShare {
  int begin = 0;
  int count = 0;
};

/// Rank `rank`'s share of `particles` over `ranks`: contiguous, in rank order, the first
/// particles % ranks ranks one particle more than the others.
ParticleShare particle_share(int particles, int ranks, int rank);

class ParticleRanks {
 public:
  /// Whether the application initialised MPI (somasim run under an MPI launcher).
  static bool mpi_running();

  /// Duplicates MPI_COMM_WORLD: a collective call, made by every rank at the same point of the
  /// (identical) configuration. Needs mpi_running().
  ParticleRanks();
  ~ParticleRanks();
  ParticleRanks(const ParticleRanks&) = delete;
  ParticleRanks& operator=(const ParticleRanks&) = delete;
  ParticleRanks(ParticleRanks&&) = delete;
  ParticleRanks& operator=(ParticleRanks&&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  ParticleShare share(int particles) const { return particle_share(particles, size_, rank_); }

  /// The likelihoods of all `particles` on every rank, in particle order, from each rank's
  /// `local` likelihoods of its share (size share(particles).count). Collective.
  std::vector<double> gather(const std::vector<double>& local, int particles) const;

 private:
  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace somasim::body_schema
