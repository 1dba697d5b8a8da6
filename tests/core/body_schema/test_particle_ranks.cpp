// particle_share: how one filter's particles are split over MPI ranks, for generated particle
// and rank counts (the collective calls are tested under mpirun in test_body_schema_mpi).
#include <random>

#include <gtest/gtest.h>

#include "somasim/body_schema/particle_ranks.hpp"

using somasim::body_schema::particle_share;
using somasim::body_schema::ParticleShare;

TEST(ParticleShare, RanksCoverEveryParticleOnceInOrderAndBalanced) {
  std::mt19937_64 rng(2);
  std::uniform_int_distribution<int> particles_of(1, 5000), ranks_of(1, 64);
  for (int trial = 0; trial < 500; ++trial) {
    const int particles = particles_of(rng);
    const int ranks = std::min(ranks_of(rng), particles);
    int next = 0, smallest = particles, largest = 0;
    for (int r = 0; r < ranks; ++r) {
      const ParticleShare s = particle_share(particles, ranks, r);
      EXPECT_EQ(s.begin, next) << particles << " over " << ranks << ", rank " << r;
      next += s.count;
      smallest = std::min(smallest, s.count);
      largest = std::max(largest, s.count);
      if (r > 0) {  // the larger shares come first
        EXPECT_LE(s.count, particle_share(particles, ranks, r - 1).count);
      }
    }
    EXPECT_EQ(next, particles);
    EXPECT_LE(largest - smallest, 1);
    EXPECT_GE(smallest, 1);
  }
}

TEST(ParticleShare, OneRankHoldsEverything) {
  const ParticleShare s = particle_share(200, 1, 0);
  EXPECT_EQ(s.begin, 0);
  EXPECT_EQ(s.count, 200);
}
