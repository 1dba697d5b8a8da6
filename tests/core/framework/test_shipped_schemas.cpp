// The shipped plugins' schemas, generated from their config structs: every integer parameter
// carries the width of the member it fills, so a value the member cannot hold is refused at
// validation for every plugin, not only where someone thought of it.
#include <sys/stat.h>

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
                       "range; expected an integer in [1, 20000] (the parameter holds integers in "
                       "[-2147483648, 2147483647])"),
            std::string::npos)
      << r.err;
}

// Every parameter that names a file to read refuses what is not a regular file before opening it
// (a device would be read forever, a FIFO block).
TEST(ShippedSchemas, InputFileParametersRefuseFoldersFifosAndDevices) {
  TempDir dir;
  const std::string fifo = (dir / "fifo").string();
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string config = std::string(SOMASIM_SOURCE_DIR) + "/configs/pps_avoidance.yaml";
  struct Case {
    std::string set_path, file, what;
  };
  for (const std::string key : {"nodes.pps.params.load", "nodes.world.params.scene"})
    for (const Case& c : {Case{key, "/dev/zero", "a device"}, Case{key, "/dev/urandom", "a device"},
                          Case{key, dir.path().string(), "a folder"}, Case{key, fifo, "a FIFO"}}) {
      const CliResult r = cli({"validate", config, "--set", c.set_path + "=" + c.file}, dir, false);
      EXPECT_EQ(r.code, 2) << c.set_path << "=" << c.file;
      EXPECT_NE(r.err.find("input file '" + c.file + "' is not a regular file (" + c.file + " is " +
                           c.what + ")"),
                std::string::npos)
          << r.err;
    }
}

}  // namespace
}  // namespace somasim::test
