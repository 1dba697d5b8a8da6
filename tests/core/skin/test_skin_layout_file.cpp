// Skin layout files: reading, modules, round trip, and every error message in full.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "somasim/error.hpp"
#include "somasim/skin/layout_file.hpp"

namespace fs = std::filesystem;
using somasim::skin::load_layout_file;
using somasim::skin::SkinLayout;

namespace {

class LayoutFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() /
        ("somasim_skin_file_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& text) {
    const fs::path p = dir_ / "layout.txt";
    std::ofstream(p) << text;
    return p.string();
  }
  std::string error_of(const std::string& text) {
    const std::string path = write(text);
    try {
      load_layout_file(path, "palm", 2);
    } catch (const somasim::InputError& e) {
      std::string m = e.what();
      if (m.rfind(path, 0) == 0) m = "FILE" + m.substr(path.size());
      return m;
    }
    return "no error";
  }
  fs::path dir_;
};

}  // namespace

TEST_F(LayoutFile, ReadsTaxelsWithoutModules) {
  const SkinLayout l = load_layout_file(write("# id x y z nx ny nz\n"
                                              "7 0.01 0.02 0.03 0 0 2\n"
                                              "\n"
                                              "3, -0.01, 0, 0, -1, 0, 0   # a comment\n"),
                                        "palm", 2);
  EXPECT_EQ(l.body_part, "palm");
  EXPECT_EQ(l.link, 2);
  ASSERT_EQ(l.size(), 2u);
  EXPECT_EQ(l.ids, (std::vector<int>{7, 3}));
  EXPECT_TRUE(l.positions[0].isApprox(Eigen::Vector3d(0.01, 0.02, 0.03)));
  EXPECT_TRUE(l.normals[0].isApprox(Eigen::Vector3d(0, 0, 1))) << "normalised";
  ASSERT_EQ(l.virtual_taxels.size(), 2u);
  EXPECT_EQ(l.virtual_taxels[0].id, 7);
  EXPECT_EQ(l.virtual_taxels[1].id, 3);
}

TEST_F(LayoutFile, ModuleColumnGroupsTaxels) {
  const SkinLayout l = load_layout_file(write("0 0.000 0 0 0 0 1 5\n"
                                              "1 0.004 0 0 0 0 1 5\n"
                                              "2 0.008 0 0 0 0 1 5\n"
                                              "3 0.100 0 0 0 0 1 2\n"),
                                        "palm", 2);
  ASSERT_EQ(l.virtual_taxels.size(), 2u);
  EXPECT_EQ(l.virtual_taxels[0].id, 2);
  EXPECT_EQ(l.virtual_taxels[1].id, 5);
  EXPECT_EQ(l.virtual_taxels[1].centre, 1) << "the member nearest the module's mean";
  EXPECT_EQ(l.virtual_taxels[1].members, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(l.module, (std::vector<int>{1, 1, 1, 0}));
}

TEST_F(LayoutFile, SaveThenLoadRoundTrips) {
  SkinLayout a = load_layout_file(write("0 0.000 0 0 0 0 1 1\n"
                                        "1 0.004 0.001 0 0 1 0 1\n"
                                        "2 0.123456789 0 0 1 0 0 4\n"),
                                  "palm", 2);
  const fs::path p = dir_ / "out.txt";
  somasim::skin::save_layout_file(a, p);
  const SkinLayout b = load_layout_file(p, "palm", 2);
  EXPECT_EQ(a.ids, b.ids);
  EXPECT_EQ(a.module, b.module);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(a.positions[i].isApprox(b.positions[i], 1e-9));
    EXPECT_TRUE(a.normals[i].isApprox(b.normals[i], 1e-9));
  }
}

TEST_F(LayoutFile, ErrorMessages) {
  EXPECT_EQ(error_of("0 0 0 0 0 0 1\n1 0 0\n"),
            "FILE:2: expected 7 or 8 fields (id x y z nx ny nz [module]), got 3");
  EXPECT_EQ(error_of("0 0 0 0 0 0 1\n1 0 0 0 0 0 1 3\n"),
            "FILE:2: expected 7 fields like line 1, got 8");
  EXPECT_EQ(error_of("0 0 0 0.x 0 0 1\n"), "FILE:1: z '0.x' is not a finite number");
  EXPECT_EQ(error_of("0 0 nan 0 0 0 1\n"), "FILE:1: y 'nan' is not a finite number");
  EXPECT_EQ(error_of("-1 0 0 0 0 0 1\n"), "FILE:1: id '-1' is not an integer >= 0");
  EXPECT_EQ(error_of("1.5 0 0 0 0 0 1\n"), "FILE:1: id '1.5' is not an integer >= 0");
  EXPECT_EQ(error_of("0 0 0 0 0 0 1 a\n"), "FILE:1: module 'a' is not an integer >= 0");
  EXPECT_EQ(error_of("# header\n4 0 0 0 0 0 1\n\n4 0 0 0 0 0 1\n"),
            "FILE:4: taxel id 4 already used on line 2");
  EXPECT_EQ(error_of("4 0 0 0 0 0 0\n"),
            "FILE:1: the normal of taxel 4 is zero; expected an outward direction");
  EXPECT_EQ(error_of("# nothing\n\n"),
            "FILE: no taxels; expected lines 'id x y z nx ny nz [module]'");
}

TEST_F(LayoutFile, MissingFile) {
  const fs::path p = dir_ / "missing.txt";
  try {
    load_layout_file(p, "palm", 2);
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              p.string() + ": cannot open the skin layout file (no such file)");
  }
}

// The iCub's skinGui positions files: row k is taxel k, all-zero rows are no taxel, modules
// from taxel2Repr (-1: the taxel is its own module).
TEST_F(LayoutFile, ReadsIcubPositionsFiles) {
  const std::string path = write(
      "name    l_forearm\n"
      "spatial_sampling    taxel\n"
      "taxel2Repr (3 3 -1 3\n 3 -1)\n"
      "[calibration]\n"
      "0.01 0 0 0 0 1\n"
      "0.02 0 0 0 0 2\n"
      "0 0 0 0 0 0\n"
      "0.03 0 0 0 0 1\n"
      "0.04 0 0 0 1 0\n"
      "0.05 0 0 1 0 0\n");
  const SkinLayout l = load_layout_file(path, "left_forearm", 4);
  EXPECT_EQ(l.body_part, "left_forearm");
  EXPECT_EQ(l.link, 4);
  EXPECT_EQ(l.ids, (std::vector<int>{0, 1, 3, 4, 5}));
  EXPECT_DOUBLE_EQ(l.positions[2].x(), 0.03);
  EXPECT_DOUBLE_EQ(l.normals[1].z(), 1.0);  // normalised
  ASSERT_EQ(l.virtual_taxels.size(), 2u);
  EXPECT_EQ(l.virtual_taxels[0].id, 3);
  EXPECT_EQ(l.virtual_taxels[0].members.size(), 4u);
  EXPECT_EQ(l.virtual_taxels[1].id, 5);  // -1: its own module
}

TEST_F(LayoutFile, IcubPositionsFileErrors) {
  const std::string head = "name l_hand\ntaxel2Repr (0 0)\n[calibration]\n";
  EXPECT_EQ(error_of(head + "0.01 0 0 0 0 1\n0.02 0 0\n"),
            "FILE:5: expected 6 numbers (x y z nx ny nz) for taxel 1, got 3 fields");
  EXPECT_EQ(error_of(head + "0.01 0 0 0 0 x\n"), "FILE:4: 'x' is not a finite number (taxel 0)");
  EXPECT_EQ(error_of(head + "0.01 0 0 0 0 0\n"),
            "FILE:4: taxel 0 has a position but a zero normal");
  EXPECT_EQ(error_of(head + "0 0 0 0 0 0\n"),
            "FILE: no taxels (expected rows 'x y z nx ny nz' after [calibration])");
  EXPECT_EQ(error_of("name l_hand\ntaxel2Repr (0 -2)\n[calibration]\n0.01 0 0 0 0 1\n"),
            "FILE:2: taxel2Repr entry '-2' is not an integer >= -1");
  EXPECT_EQ(error_of("name l_hand\ntaxel2Repr (0 0\n"),
            "FILE:2: the taxel2Repr list is never closed (expected ')')");
}
