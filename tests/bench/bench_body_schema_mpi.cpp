// The body-schema filter step with its particles spread over MPI ranks (body_schema_filter
// `distribute: mpi`), run under mpirun: scripts/bench_mpi.sh runs it with 1 and 2 ranks in the
// same session. Not a Google Benchmark target: its adaptive iteration counts would differ
// between ranks, and every iteration is a collective step, so all ranks run the same fixed
// number of steps.
//
// Per step (medians over the steps; per rank, the slowest rank reported): observe (colour
// segmentation of both eye images) + predict, score (forward kinematics, render and likelihoods
// of this rank's share), wait (barrier: load imbalance between ranks), gather (MPI_Allgatherv of
// the M likelihoods, doubles), update (weights, KDE estimate (O(M^2)), resampling); then the
// gather alone, timed 50 times with nothing else running.
// Usage: bench_body_schema_mpi [M=2000] [render threads per rank=1] [steps=10]
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "../core/body_schema/real_arm_views.hpp"
#include "somasim/body_schema/hypothesis_scorer.hpp"
#include "somasim/body_schema/observation.hpp"
#include "somasim/body_schema/particle_filter.hpp"
#include "somasim/body_schema/particle_ranks.hpp"

namespace {

using namespace somasim;
using namespace somasim::body_schema;
namespace support = somasim::body_schema::testing;
using Clock = std::chrono::steady_clock;

double ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

enum Phase : std::size_t {
  kObserve,
  kScore,
  kWait,
  kGather,
  kUpdate,
  kStep,
  kGatherAlone,
  kPhases
};
const char* const kNames[kPhases] = {"observe", "score", "wait",        "gather",
                                     "update",  "step",  "gather alone"};

// Keeps a result alive (the optimiser must not drop the call).
void benchmark_sink(const std::vector<double>& v) {
  volatile double sink = v.empty() ? 0.0 : v.front();
  (void)sink;
}

int run(int particles, int workers, int steps) {
  body_schema::ParticleRanks ranks;
  if (ranks.size() > particles) {
    if (ranks.rank() == 0) std::fprintf(stderr, "more ranks than particles\n");
    return 2;
  }
  const body_schema::ParticleShare mine = ranks.share(particles);
  const Eigen::VectorXd q = support::hand_before_eyes();
  const support::RealEyes eyes = support::look(q);
  const ArmHypothesisModel arm = arm_hypothesis_model(*support::icub(), {"r_hand"}, 8);
  HypothesisScorer scorer(support::icub(), arm, support::arm_dofs(), workers, ScorerOptions{});
  OffsetParticleFilter filter(7, particles, noise_schedule_preset("paper"), 1);

  std::vector<std::vector<double>> times(kPhases);
  for (int step = -1; step < steps; ++step) {  // step -1 warms up
    MPI_Barrier(MPI_COMM_WORLD);
    const Clock::time_point t0 = Clock::now();
    std::vector<cv::Mat> masks;
    for (const cv::Mat& rgb : eyes.rgb) masks.push_back(segment_colour(rgb, HsvRange{}));
    filter.predict();
    const Clock::time_point t1 = Clock::now();
    const std::vector<double> local =
        scorer.score(q, filter.particles().middleCols(mine.begin, mine.count), eyes.cameras, masks);
    const Clock::time_point t2 = Clock::now();
    MPI_Barrier(MPI_COMM_WORLD);
    const Clock::time_point t3 = Clock::now();
    const std::vector<double> all = ranks.gather(local, particles);
    const Clock::time_point t4 = Clock::now();
    filter.update(all);
    const Clock::time_point t5 = Clock::now();
    if (filter.sigma_deg() < 1.0) filter.reset();  // keep the particles spread as in a movement
    if (step < 0) continue;
    times[kObserve].push_back(ms(t0, t1));
    times[kScore].push_back(ms(t1, t2));
    times[kWait].push_back(ms(t2, t3));
    times[kGather].push_back(ms(t3, t4));
    times[kUpdate].push_back(ms(t4, t5));
    times[kStep].push_back(ms(t0, t5));
  }
  // The gather alone, 50 times after a barrier (no rendering competing for the cores).
  std::vector<double> gather_alone;
  const std::vector<double> local(static_cast<std::size_t>(mine.count), 0.5);
  for (int i = 0; i < 50; ++i) {
    MPI_Barrier(MPI_COMM_WORLD);
    const Clock::time_point t0 = Clock::now();
    benchmark_sink(ranks.gather(local, particles));
    gather_alone.push_back(ms(t0, Clock::now()));
  }
  times[kGatherAlone] = gather_alone;
  // The slowest rank's median of each phase.
  std::vector<double> local_medians(kPhases);
  std::vector<double> worst(kPhases);
  for (std::size_t p = 0; p < kPhases; ++p) local_medians[p] = median(times[p]);
  MPI_Reduce(local_medians.data(), worst.data(), static_cast<int>(kPhases), MPI_DOUBLE, MPI_MAX, 0,
             MPI_COMM_WORLD);
  if (ranks.rank() == 0) {
    std::printf("ranks %d, M %d, render threads per rank %d, steps %d, share %d particles\n",
                ranks.size(), particles, workers, steps, mine.count);
    for (std::size_t p = 0; p < kPhases; ++p)
      std::printf("  %-12s %9.3f ms\n", kNames[p], worst[p]);
    std::printf("  score per particle of a rank's share: %.4f ms\n", worst[kScore] / mine.count);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  const int particles = argc > 1 ? std::atoi(argv[1]) : 2000;
  const int workers = argc > 2 ? std::atoi(argv[2]) : 1;
  const int steps = argc > 3 ? std::atoi(argv[3]) : 10;
  int code = 0;
  try {
    code = run(particles, workers, steps);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    MPI_Abort(MPI_COMM_WORLD, 3);
  }
  MPI_Finalize();
  return code;
}
