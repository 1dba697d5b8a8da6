// write_file_atomically: generated texts (empty to megabytes, any bytes) read back exactly, over
// a file that was there or not; where the file cannot be written, the error names it, the old
// file is left as it was and no temporary file is left behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <stdexcept>
#include <string>

#include "somasim/atomic_file.hpp"

namespace fs = std::filesystem;

namespace {

struct Folder {
  Folder() {
    path = fs::temp_directory_path() /
           ("somasim-atomic-" + std::to_string(std::random_device{}()) + "-" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
    fs::create_directories(path);
  }
  ~Folder() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  fs::path path;
};

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t entries(const fs::path& folder) {
  return static_cast<std::size_t>(
      std::distance(fs::directory_iterator(folder), fs::directory_iterator{}));
}

}  // namespace

TEST(AtomicFile, GeneratedTextsReadBackExactly) {
  Folder folder;
  const fs::path file = folder.path / "out.csv";
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int trial = 0; trial < 40; ++trial) {
    const std::size_t size = trial == 0 ? 0 : std::size_t{1} << (trial % 22);
    std::string text(size, '\0');
    for (char& c : text) c = static_cast<char>(byte(rng));
    somasim::write_file_atomically(file, text);
    ASSERT_EQ(read(file), text) << "trial " << trial << ", " << size << " bytes";
    EXPECT_EQ(entries(folder.path), 1u) << "a temporary file was left beside it";
  }
}

TEST(AtomicFile, AFileThatCannotBeWrittenIsNamedAndNothingIsLeft) {
  Folder folder;
  // The folder does not exist: nothing is created.
  const fs::path missing = folder.path / "no_such_folder" / "out.csv";
  try {
    somasim::write_file_atomically(missing, "x");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(entries(folder.path), 0u);
  // A folder where the file would go: the folder stays, no temporary file is left.
  const fs::path taken = folder.path / "taken";
  fs::create_directories(taken / "inside");
  EXPECT_THROW(somasim::write_file_atomically(taken, "x"), std::runtime_error);
  EXPECT_TRUE(fs::is_directory(taken / "inside"));
  EXPECT_EQ(entries(folder.path), 1u);
}
