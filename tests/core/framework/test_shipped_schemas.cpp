// The shipped plugins' schemas, generated from their config structs: every integer parameter
// carries the width of the member it fills, so a value the member cannot hold is refused at
// validation for every plugin, not only where someone thought of it.
#include <gtest/gtest.h>

#include "cli_support.hpp"
#include "somasim/plugin_registry.hpp"

namespace somasim::test {
namespace {

TEST(ShippedSchemas, EveryIntegerParameterKnowsItsWidth) {
  PluginRegistry registry({std::string(SOMASIM_BUILD_DIR) + "/lib/somasim/plugins"});
  int plugins = 0, integers = 0;
  for (const std::string& name : registry.names()) {
    const PluginSpec* spec = registry.find(name);
    ASSERT_NE(spec, nullptr) << name;
    ++plugins;
    for (const ParamSpec& p : spec->params()) {
      if (p.type != ParamType::Int) continue;
      ++integers;
      EXPECT_TRUE(p.int_min && p.int_max) << name << "." << p.name;
    }
  }
  EXPECT_GE(plugins, 20);
  EXPECT_GE(integers, 30);
}

TEST(ShippedSchemas, AnIntegerBeyondTheMembersWidthIsALocatedError) {
  TempDir dir;
  const CliResult r =
      cli({"validate", std::string(SOMASIM_SOURCE_DIR) + "/configs/body_schema_particles.yaml",
           "--set", "nodes.filter.params.particles=4294967297"},
          dir, /*with_plugin_path=*/false);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("node 'filter', key 'params.particles': value 4294967297 is out of "
                       "range; expected an integer >= 1 (the parameter holds integers in "
                       "[-2147483648, 2147483647])"),
            std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace somasim::test
