// The scheduler through the test harness: rates, order, delayed edges, stops, RNG streams.
#include <gtest/gtest.h>

#include <functional>

#include "somasim/error.hpp"
#include "somasim/port_types.hpp"
#include "somasim/rng.hpp"
#include "somasim/testing/harness.hpp"
#include "test_support.hpp"

namespace somasim::test {
namespace {

using somasim::testing::Harness;

TEST(Scheduler, NodeAtQuarterRateStepsEveryFourTicks) {
  Harness h(R"(
base_rate_hz: 1000
nodes:
  slow: {plugin: counter, rate_hz: 250, params: {start: 0}}
  fast: {plugin: counter, params: {start: 0}}
)",
            {kTestPluginDir});
  const double& slow = h.output<double>("slow.value");
  const double& fast = h.output<double>("fast.value");
  std::vector<double> slow_seen;
  for (int tick = 0; tick < 9; ++tick) {
    ASSERT_TRUE(h.step());
    slow_seen.push_back(slow);
    EXPECT_EQ(fast, tick + 1);
  }
  // Steps at ticks 0, 4 and 8.
  EXPECT_EQ(slow_seen, (std::vector<double>{1, 1, 1, 1, 2, 2, 2, 2, 3}));
  EXPECT_DOUBLE_EQ(h.time_s(), 0.009);
  h.finish();
  EXPECT_EQ(h.metric("slow", "steps"), 3);
  EXPECT_EQ(h.metric("fast", "steps"), 9);
}

TEST(Scheduler, ConsumerSeesProducersValueOfTheSameTick) {
  // The consumer is listed first: the order comes from the wiring, not the file.
  Harness h(R"(
nodes:
  sum: {plugin: adder, inputs: {a: c.value, b: c2.value}}
  c: {plugin: counter, params: {start: 10}}
  c2: {plugin: counter, params: {start: 100, increment: 2}}
)",
            {kTestPluginDir});
  EXPECT_EQ(h.experiment().order, (std::vector<int>{1, 2, 0}));
  h.step();
  EXPECT_EQ(h.output<double>("sum.sum"), 11 + 102);
  h.step();
  EXPECT_EQ(h.output<double>("sum.sum"), 12 + 104);
}

TEST(Scheduler, DelayedEdgeReadsThePreviousTick) {
  Harness h(R"(
nodes:
  c: {plugin: counter, params: {start: 0}}
  now: {plugin: adder, inputs: {a: c.value}}
  late: {plugin: adder, inputs: {a: {from: c.value, delayed: true}}}
)",
            {kTestPluginDir});
  for (int tick = 1; tick <= 3; ++tick) {
    h.step();
    EXPECT_EQ(h.output<double>("now.sum"), tick);
    EXPECT_EQ(h.output<double>("late.sum"), tick - 1);
  }
}

TEST(Scheduler, FeedbackLoopThroughDelayedEdge) {
  // acc = c + acc(previous tick): a running sum of 1, 2, 3, ...
  Harness h(R"(
nodes:
  c: {plugin: counter, params: {start: 0}}
  acc: {plugin: adder, inputs: {a: c.value, b: {from: acc.sum, delayed: true}}}
)",
            {kTestPluginDir});
  h.step(4);
  EXPECT_EQ(h.output<double>("acc.sum"), 1 + 2 + 3 + 4);
}

TEST(Scheduler, RequestStopEndsTheRun) {
  Harness h(R"(
nodes:
  c: {plugin: counter, params: {start: 0, stop_after: 5}}
)",
            {kTestPluginDir});
  EXPECT_FALSE(h.step(10));
  EXPECT_FALSE(h.step());
  h.finish();
  EXPECT_EQ(h.metric("c", "steps"), 5);
  EXPECT_EQ(h.output<double>("c.value"), 5);
}

TEST(Scheduler, DurationEndsTheRun) {
  Harness h(R"(
duration_s: 0.01
base_rate_hz: 1000
nodes:
  c: {plugin: counter, params: {start: 0}}
)",
            {kTestPluginDir});
  EXPECT_FALSE(h.step(100));
  EXPECT_EQ(h.output<double>("c.value"), 10);
}

// Values of a noisy counter `node` over `ticks` ticks in a graph.
std::vector<double> draws(const std::string& yaml, const std::string& node = "c", int ticks = 20) {
  Harness h(yaml, {kTestPluginDir});
  std::vector<double> out;
  for (int i = 0; i < ticks; ++i) {
    h.step();
    out.push_back(h.output<double>(node + ".value"));
  }
  return out;
}

TEST(Scheduler, RandomStreamsDependOnlyOnSeedAndNodeName) {
  const std::string alone = R"(
seed: 7
nodes:
  c: {plugin: counter, params: {start: 0, mode: noisy}}
)";
  const std::string crowded = R"(
seed: 7
nodes:
  a: {plugin: counter, params: {start: 0, mode: noisy}}
  c: {plugin: counter, params: {start: 0, mode: noisy}}
  z: {plugin: counter, rate_hz: 500, params: {start: 0, mode: noisy}}
  s: {plugin: adder, inputs: {a: a.value, b: z.value}}
)";
  const auto reference = draws(alone);
  EXPECT_EQ(draws(alone), reference);    // repeatable
  EXPECT_EQ(draws(crowded), reference);  // other nodes do not disturb c's stream
  std::string reseeded = alone;
  reseeded.replace(reseeded.find("seed: 7"), 7, "seed: 8");
  EXPECT_NE(draws(reseeded), reference);
  // The same node under another name gets another stream.
  std::string renamed = alone;
  renamed.replace(renamed.find("  c:"), 4, "  d:");
  EXPECT_NE(draws(renamed, "d"), reference);
  EXPECT_EQ(draws(crowded, "a"), draws(renamed.replace(renamed.find("  d:"), 4, "  a:"), "a"));
  // The derivation is part of the determinism promise: pin it.
  EXPECT_EQ(node_stream_seed(7, "c"), splitmix64(splitmix64(7) ^ fnv1a64("c")));
  EXPECT_NE(node_stream_seed(7, "c"), node_stream_seed(7, "d"));
}

TEST(Scheduler, HarnessFeedsInputs) {
  Harness h(R"(
nodes:
  s: {plugin: adder, inputs: {a: harness.x, b: harness.y}}
  t: {plugin: adder, inputs: {a: harness.x}}
)",
            {kTestPluginDir});
  h.input<double>("x") = 2;
  h.input<double>("y") = 3;
  h.step();
  EXPECT_EQ(h.output<double>("s.sum"), 5);
  EXPECT_EQ(h.output<double>("t.sum"), 2);  // one harness input may feed several nodes
  h.input<double>("x") = -1;
  h.step();
  EXPECT_EQ(h.output<double>("s.sum"), 2);
  h.finish();
  EXPECT_EQ(h.metric("s", "final"), 2);
  EXPECT_TRUE(h.metric("s", "nothing").is_null());
}

std::string harness_error(const std::function<void(Harness&)>& f) {
  Harness h(R"(
nodes:
  s: {plugin: adder, inputs: {a: harness.x}}
)",
            {kTestPluginDir});
  try {
    f(h);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Scheduler, HarnessMisuseMessages) {
  EXPECT_EQ(harness_error([](Harness& h) { h.input<double>("q"); }),
            "no input is wired to 'harness.q'");
  EXPECT_EQ(harness_error([](Harness& h) { h.input<Eigen::Vector3d>("x"); }),
            "harness input 'x' is 'scalar', not 'vector3'");
  EXPECT_EQ(harness_error([](Harness& h) { h.output<double>("s.total"); }),
            "node 's' has no output 'total'");
  EXPECT_EQ(harness_error([](Harness& h) { h.output<Eigen::Vector3d>("s.sum"); }),
            "output 's.sum' is 'scalar', not 'vector3'");
  EXPECT_EQ(harness_error([](Harness& h) { h.output<double>("nobody.sum"); }), "no node 'nobody'");
}

TEST(Scheduler, HarnessRejectsBadGraphsLikeValidate) {
  try {
    Harness h("nodes:\n  s: {plugin: adder}\n", {kTestPluginDir});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "<inline>:2:3: node 's', key 'inputs.a': required input is not wired (expected "
                 "'node.port' giving 'scalar': first term)");
  }
}

TEST(Scheduler, FailingStepPropagatesAndFinishStillRuns) {
  Harness h(R"(
nodes:
  c: {plugin: counter, params: {start: 0, fail: true}}
)",
            {kTestPluginDir});
  EXPECT_TRUE(h.step(2));
  try {
    h.step();
    FAIL() << "no error";
  } catch (const RunError& e) {
    EXPECT_STREQ(e.what(), "deliberate failure");
  }
  EXPECT_EQ(h.finish(), "");
  EXPECT_EQ(h.metric("c", "steps"), 3);
}

}  // namespace
}  // namespace somasim::test
