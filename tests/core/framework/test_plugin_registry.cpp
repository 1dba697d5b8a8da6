// PluginRegistry: libraries with an index are opened only when one of their plugins is needed;
// libraries without a usable index are opened to see what they provide.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>

#include "cli_support.hpp"
#include "somasim/plugin_index.hpp"
#include "somasim/plugin_registry.hpp"
#include "test_support.hpp"

namespace somasim::test {
namespace {
namespace fs = std::filesystem;

// A plugin folder with a copy of the test plugins (indexed) and of the no-entry library with an
// index that claims a plugin "ghost" (the library is rejected only if it is ever opened).
struct IndexedFolder {
  TempDir dir;
  fs::path plugins = dir / "libsomasim_test_plugins.so";
  fs::path broken = dir / "libsomasim_test_no_entry.so";
  IndexedFolder() {
    fs::copy_file(kTestPluginLib, plugins);
    fs::copy_file(kNoEntryLib, broken);
    index_plugin_library(plugins);
    write_plugin_index(broken, {{"ghost", "Claimed by an index, provided by nothing."}});
  }
};

TEST(PluginRegistry, IndexedLibrariesAreOpenedOnlyWhenNeeded) {
  IndexedFolder f;
  PluginRegistry registry({f.dir.path()});
  const auto names = registry.names();
  EXPECT_NE(std::find(names.begin(), names.end(), "counter"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "ghost"), names.end());
  EXPECT_TRUE(registry.opened_libraries().empty()) << "listing names must not dlopen anything";

  const PluginSpec* counter = registry.find("counter");
  ASSERT_NE(counter, nullptr);
  EXPECT_EQ(counter->library_path, f.plugins.string());
  EXPECT_EQ(registry.opened_libraries(), std::vector<fs::path>{f.plugins});

  // Looking up the plugin that only the broken library's index names opens it, and finds that it
  // is rejected: not found, and the reason is in the search report.
  EXPECT_EQ(registry.find("ghost"), nullptr);
  EXPECT_NE(registry.search_report().find("libsomasim_test_no_entry.so [rejected: no entry point"),
            std::string::npos)
      << registry.search_report();
}

TEST(PluginRegistry, IndexListsSummariesWithoutOpening) {
  IndexedFolder f;
  PluginRegistry registry({f.dir.path()});
  bool found = false;
  for (const auto& l : registry.list())
    if (l.plugin.name == "adder") {
      found = true;
      EXPECT_EQ(l.plugin.summary, "Adds its inputs (test plugin).");
      EXPECT_EQ(l.library->path, f.plugins);
      EXPECT_TRUE(l.library->indexed);
      EXPECT_FALSE(l.library->opened);
    }
  EXPECT_TRUE(found);
  EXPECT_TRUE(registry.opened_libraries().empty());
}

TEST(PluginRegistry, StaleOrForeignIndexFallsBackToOpening) {
  IndexedFolder f;
  // Rebuilt library, old index: the index is not trusted.
  fs::last_write_time(f.plugins,
                      fs::last_write_time(plugin_index_path(f.plugins)) + std::chrono::seconds(5));
  write_file(plugin_index_path(f.broken),
             "somasim-plugin-index 1\ninterface somasim-plugin-api/0\n");
  PluginRegistry registry({f.dir.path()});
  const auto& cands = registry.candidates();
  ASSERT_EQ(cands.size(), 2u);  // in file-name order
  EXPECT_EQ(cands[0].path, f.broken);
  EXPECT_EQ(cands[0].index_note, "index written for another plugin interface");
  EXPECT_TRUE(cands[0].rejected());
  EXPECT_EQ(cands[1].path, f.plugins);
  EXPECT_TRUE(cands[1].opened);
  EXPECT_EQ(cands[1].index_note, "index older than the library");
  EXPECT_NE(registry.find("counter"), nullptr);
}

TEST(PluginRegistry, FirstLibraryOnThePathWinsWithOrWithoutIndex) {
  IndexedFolder first;
  TempDir second;
  fs::copy_file(kTestPluginLib, second / "libsomasim_test_plugins.so");  // no index
  PluginRegistry registry({first.dir.path(), second.path()});
  const PluginSpec* counter = registry.find("counter");
  ASSERT_NE(counter, nullptr);
  EXPECT_EQ(counter->library_path, first.plugins.string());
}

TEST(PluginRegistry, ExplicitLibraryComesFirst) {
  IndexedFolder f;
  PluginRegistry registry({f.dir.path()});
  registry.load_library(kTestPluginLib);
  EXPECT_EQ(registry.find("counter")->library_path, kTestPluginLib);
}

TEST(PluginsCommand, SaysWhatItLoaded) {
  TempDir dir;
  // The built-in plugins are indexed by the build: listing them opens none of them.
  const CliResult r = cli({"plugins"}, dir, /*with_plugin_path=*/false);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("bullet_world "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("libsomasim_bullet_world.so: index read, not loaded\n"), std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("loaded (dlopen'ed)"), std::string::npos) << r.out;
  // The test plugins have no index: they are opened to list them, and it says so.
  const CliResult t = cli({"plugins"}, dir);
  EXPECT_NE(t.out.find("libsomasim_test_plugins.so: loaded (dlopen'ed): no index\n"),
            std::string::npos)
      << t.out;
}

TEST(PluginsCommand, IndexSubcommandWritesTheIndex) {
  TempDir dir;
  const fs::path lib = dir / "libsomasim_test_plugins.so";
  fs::copy_file(kTestPluginLib, lib);
  const CliResult r = cli({"plugins", "index", lib.string()}, dir, false);
  EXPECT_EQ(r.code, 0) << r.err;
  const std::string index = read_file(plugin_index_path(lib));
  EXPECT_EQ(index.rfind("somasim-plugin-index 1\ninterface somasim-plugin-api/5\n", 0), 0u)
      << index;
  EXPECT_NE(index.find("plugin counter Counts its own steps (test plugin).\n"), std::string::npos);
  const CliResult bad = cli({"plugins", "index", kNoEntryLib}, dir, false);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("rejected: no entry point"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace somasim::test
