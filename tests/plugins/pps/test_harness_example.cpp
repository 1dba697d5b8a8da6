// The example in somasim/testing/harness.hpp's documentation, verbatim: it compiles and runs.
// (tests/tools/harness_example_in_sync.cmake checks that every line of the documented example
// appears here, so the two cannot drift apart.)
#include <gtest/gtest.h>

#include "somasim/pps/ports.hpp"
#include "somasim/skin/ports.hpp"
#include "somasim/testing/harness.hpp"

TEST(HarnessExample, TheDocumentedExampleRuns) {
  // clang-format off
  somasim::testing::Harness h(R"(
    nodes:
      thrower: {plugin: taxel_thrower, params: {throws: 3}}
      pps:
        plugin: pps_learner
        params: {ttc_max: 3}
        inputs: {stimulus: harness.stim, taxels: thrower.taxels, contacts: thrower.contacts}
  )");
  h.input<somasim::pps::Stimulus>("stim").present = true;  // feed an input
  h.step(10);                                              // ten base ticks
  const auto& act = h.output<somasim::TaxelValues>("pps.activations");
  h.finish();
  const nlohmann::json events = h.metric("pps", "events");
  // clang-format on
  EXPECT_EQ(act.values.size(), 1u);  // the thrower's one taxel
  EXPECT_TRUE(events.is_number());
}
