#pragma once
// Helpers shared by the core tests: temporary directories and whole-file reads.
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace somasim::test {

/// A fresh directory under the system temp dir, removed on destruction.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("somasim-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

inline std::string read_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_file(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
}

inline const std::string kTestPluginDir = SOMASIM_TEST_PLUGIN_DIR;
inline const std::string kBadPluginDir = SOMASIM_BAD_PLUGIN_DIR;
inline const std::string kTestPluginLib = kTestPluginDir + "/libsomasim_test_plugins.so";
inline const std::string kNoEntryLib = kBadPluginDir + "/libsomasim_test_no_entry.so";
inline const std::string kOldApiLib = kBadPluginDir + "/libsomasim_test_old_api.so";

}  // namespace somasim::test
