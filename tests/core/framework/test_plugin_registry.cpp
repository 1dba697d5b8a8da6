// PluginRegistry: libraries with an index are opened only when one of their plugins is needed;
// libraries without one only when no index names the plugin looked up, or when all are listed;
// nothing that lacks the entry point in its dynamic symbols is ever loaded (constructors never
// run). The ELF reader that decides it, on real, truncated and corrupted files.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <random>

#include <dlfcn.h>
#include <sys/stat.h>

#include "cli_support.hpp"
#include "somasim/elf_symbols.hpp"
#include "somasim/plugin.hpp"
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
  EXPECT_FALSE(cands[1].opened);  // opened when a plugin is looked up that no index names
  EXPECT_EQ(cands[1].index_note, "index older than the library");
  EXPECT_NE(registry.find("counter"), nullptr);
  EXPECT_TRUE(cands[1].opened);
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
  EXPECT_EQ(index.rfind("somasim-plugin-index 1\ninterface somasim-plugin-api/6\n", 0), 0u)
      << index;
  EXPECT_NE(index.find("plugin counter Counts its own steps (test plugin).\n"), std::string::npos);
  const CliResult bad = cli({"plugins", "index", kNoEntryLib}, dir, false);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("rejected: no entry point"), std::string::npos) << bad.err;
}

}  // namespace
// The reader finds the entry point in a real plugin, not in the library without one, and says
// what is wrong with what is no shared library at all.
TEST(ElfSymbols, EntryPointOfRealLibraries) {
  std::string why;
  EXPECT_TRUE(elf_exports_function(kTestPluginLib, SOMASIM_PLUGIN_ENTRY_SYMBOL, why)) << why;
  EXPECT_FALSE(elf_exports_function(kNoEntryLib, SOMASIM_PLUGIN_ENTRY_SYMBOL, why));
  EXPECT_EQ(why,
            "no entry point 'somasim_plugin_entry' among its dynamic symbols (is "
            "SOMASIM_PLUGIN_LIBRARY missing?)");
  EXPECT_TRUE(elf_exports_function(kNoEntryLib, "somasim_test_not_a_plugin", why)) << why;
  TempDir dir;
  write_file(dir / "text.so", "not a library\n");
  EXPECT_FALSE(elf_exports_function(dir / "text.so", "x", why));
  EXPECT_EQ(why, "not an ELF file");
  EXPECT_FALSE(elf_exports_function("/dev/zero", "x", why));
  EXPECT_EQ(why, "not a regular file");
  EXPECT_FALSE(elf_exports_function(dir.path(), "x", why));
  ASSERT_EQ(mkfifo((dir / "fifo.so").c_str(), 0600), 0);
  EXPECT_FALSE(elf_exports_function(dir / "fifo.so", "x", why));  // never blocks on the FIFO
  EXPECT_EQ(why, "not a regular file");
}

// Every prefix of a real plugin library (cut every 256 bytes) and 400 copies with random bytes
// changed: the reader answers (true only where the entry point is really there), never crashes
// or reads out of bounds (the sanitizer build runs this too).
TEST(ElfSymbols, TruncatedAndCorruptedFilesAreAnsweredSafely) {
  std::ifstream in(kTestPluginLib, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 4096u);
  TempDir dir;
  const fs::path f = dir / "lib.so";
  std::string why;
  int refused = 0;
  for (std::size_t n = 0; n < bytes.size(); n += 256) {
    write_file(f, bytes.substr(0, n));
    refused += elf_exports_function(f, SOMASIM_PLUGIN_ENTRY_SYMBOL, why) ? 0 : 1;
  }
  EXPECT_GT(refused, 0);
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<std::size_t> at(0, bytes.size() - 1);
  std::uniform_int_distribution<int> byte(0, 255), changes(1, 64);
  int found = 0;
  for (int k = 0; k < 400; ++k) {
    std::string copy = bytes;
    // The ELF header and section headers are where a change matters most: half the changes
    // land in the first 64 bytes or the last 4 KiB.
    for (int c = changes(rng); c > 0; --c) {
      std::size_t i = at(rng);
      if (c % 2 == 0) i = c % 4 == 0 ? i % 64 : bytes.size() - 1 - i % 4096;
      copy[i] = static_cast<char>(byte(rng));
    }
    write_file(f, copy);
    found += elf_exports_function(f, SOMASIM_PLUGIN_ENTRY_SYMBOL, why) ? 1 : 0;
  }
  std::printf("corrupted libraries: entry point still found in %d of 400\n", found);
}

// A library without the entry point is never loaded — on the search path (listed, looked up,
// validated) or named explicitly — so its constructor never runs. (The constructor does run
// when the library is loaded: checked last, so the test can fail.)
TEST(PluginRegistry, ALibraryWithoutTheEntryPointIsNeverLoaded) {
  TempDir dir;
  const fs::path marker = dir / "constructor_ran";
  ASSERT_EQ(setenv("SOMASIM_TEST_CONSTRUCTOR_MARKER", marker.c_str(), 1), 0);
  {
    PluginRegistry registry({kBadPluginDir, kTestPluginDir});
    registry.list();
    EXPECT_EQ(registry.find("no_such_plugin"), nullptr);
    EXPECT_NE(registry.find("counter"), nullptr);
    EXPECT_THROW(registry.load_library(kNoEntryLib), InputError);
    for (const auto& lib : registry.opened_libraries()) EXPECT_NE(lib, fs::path(kNoEntryLib));
  }
  write_file(dir / "exp.yaml",
             "experiment: t\nduration_s: 0.005\nnodes:\n  c: {plugin: counter, params: {start: "
             "0}}\n");
  const CliResult r =
      cli({"--plugin-path", kBadPluginDir, "--plugin-path", kTestPluginDir, "validate", "exp.yaml"},
          dir);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("plugin library loaded: " + kTestPluginLib), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(marker));
  void* handle = dlopen(kNoEntryLib.c_str(), RTLD_NOW | RTLD_LOCAL);
  ASSERT_NE(handle, nullptr);
  EXPECT_TRUE(fs::exists(marker)) << "the marker library's constructor did not run";
  dlclose(handle);
  unsetenv("SOMASIM_TEST_CONSTRUCTOR_MARKER");
}

}  // namespace somasim::test
