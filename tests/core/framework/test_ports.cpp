// Port mechanics: deep copies on delayed edges, copies only after a producer step, recorders
// other than CSV, and the size check of the wiring.
#include <gtest/gtest.h>

#include "somasim/error.hpp"
#include "somasim/testing/harness.hpp"
#include "test_support.hpp"

namespace somasim::test {
namespace {

using somasim::testing::Harness;

// The producer mutates its buffer in place; operator= would share it, so the delayed
// consumer would see this tick's value. The copy hook keeps the previous one.
TEST(Ports, DelayedEdgeDeepCopiesWithTheTypesCopyHook) {
  Harness h(R"(
nodes:
  src: {plugin: buffer_source}
  sink: {plugin: buffer_sink, inputs: {in: {from: src.buffer, delayed: true}}}
)",
            {kTestPluginDir});
  h.step(4);
  h.finish();
  // Tick 0 reads the default (empty) value, then the value of the tick before.
  EXPECT_EQ(h.metric("sink", "seen"), nlohmann::json({-1.0, 1.0, 2.0, 3.0}));
}

// A delayed edge is copied at the end of the ticks its producer stepped in, not every tick.
TEST(Ports, DelayedEdgeIsCopiedOnlyWhenItsProducerStepped) {
  Harness h(R"(
base_rate_hz: 100
nodes:
  src: {plugin: buffer_source, rate_hz: 25}
  sink: {plugin: buffer_sink, inputs: {in: {from: src.buffer, delayed: true}}}
)",
            {kTestPluginDir});
  h.step(12);  // the source steps at ticks 0, 4 and 8
  h.finish();
  EXPECT_EQ(h.metric("sink", "copies"), 3);
  EXPECT_EQ(h.metric("sink", "seen"),
            nlohmann::json({-1.0, 1.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0, 3.0, 3.0, 3.0}));
}

TEST(Ports, ATypeWithItsOwnRecorderIsRecordedByIt) {
  Harness h(R"(
nodes:
  src: {plugin: buffer_source, rate_hz: 500}
record: [src.buffer]
)",
            {kTestPluginDir});
  h.step(4);
  h.finish();
  EXPECT_EQ(read_file(h.out_dir() / "src.buffer.txt"), "0: 1\n0.002: 2\n");
  EXPECT_FALSE(std::filesystem::exists(h.out_dir() / "src.buffer.csv"));
}

TEST(Ports, ATypeWithoutCsvOrRecorderCannotBeRecorded) {
  try {
    Harness h(R"(
nodes:
  w: {plugin: wide_source}
record: [w.value]
)",
              {kTestPluginDir});
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "<inline>:4:10: key 'record': port 'w.value' of type 'scalar' cannot be recorded "
              "(its type has neither CSV columns nor a recorder)");
  }
}

TEST(Ports, WiringChecksTheSizeOfTypesOfTheSameName) {
  try {
    Harness h(R"(
nodes:
  w: {plugin: wide_source}
  sum: {plugin: adder, inputs: {a: w.value}}
)",
              {kTestPluginDir});
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "<inline>:4:36: node 'sum', key 'inputs.a': type 'scalar' is 16 bytes in 'w' (" +
                  kTestPluginLib + ") but 8 bytes in 'sum' (" + kTestPluginLib +
                  "): the two plugin libraries were built against different definitions of it; "
                  "rebuild both against this somasim");
  }
}

}  // namespace
}  // namespace somasim::test
