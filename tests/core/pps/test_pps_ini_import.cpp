#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "somasim/error.hpp"
#include "somasim/pps/ini_export.hpp"
#include "somasim/pps/ini_import.hpp"
#include "temp_dir.hpp"

using namespace somasim::pps;

namespace {

std::string counts(int first) {
  std::string s = "(";
  for (int k = 0; k < 32; ++k) s += std::to_string(first + k) + (k < 31 ? " " : ")");
  return s;
}

const std::string kGood =
    "[r_hand]\n"
    "modality\t2D\n"
    "size    \t192\n"
    "nTaxels \t2\n"
    "ext     \t(-0.1 0.2 0.0 1.2)\n"
    "binsNum \t(8\t4)\n"
    "Mapping (-1 -1 101 101 103)\n"
    "101      " +
    counts(0) + "   " + counts(100) +
    "\n"
    "103 " +
    counts(5) + " " + counts(7) +
    "\n"
    "[l_hand]\n"
    "modality\t1D\n"
    "nTaxels 1\n"
    "ext (-0.05 0.45)\n"
    "binsNum (20 1)\n"
    "99 (0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0) (0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0)\n"
    "[l_forearm]\n"
    "modality 2D\n"
    "nTaxels 1\n"
    "extX (-0.1 0.2)\n"
    "extY (0.0 3.0)\n"
    "binsNum (8 4)\n"
    "3 " +
    counts(1) + " " + counts(2) + "\n";

std::string import_error(const TempDir& dir, const std::string& text) {
  const std::string p = dir.file("bad.ini", text);
  try {
    import_taxels2d_ini(p);
  } catch (const somasim::InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(p + ":", 0), 0u) << msg;
    return msg.substr(p.size() + 1);
  }
  ADD_FAILURE() << "no InputError";
  return {};
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  s.replace(s.find(from), from.size(), to);
  return s;
}

}  // namespace

TEST(PpsIniImport, ImportsTwoDSectionsAndSkipsOneD) {
  TempDir dir;
  const auto states = import_taxels2d_ini(dir.file("t.ini", kGood));
  ASSERT_EQ(states.size(), 2u);
  EXPECT_EQ(states[0].body_part, "r_hand");
  EXPECT_EQ(states[0].grid, GridSpec::code());
  EXPECT_EQ(states[0].parzen, ParzenSpec::code());
  ASSERT_EQ(states[0].taxels.size(), 2u);
  EXPECT_EQ(states[0].taxels[0].id, 101);
  EXPECT_EQ(states[0].taxels[0].pos[0], 0u);
  EXPECT_EQ(states[0].taxels[0].pos[9], 9u);  // d_bin 2, ttc_bin 1
  EXPECT_EQ(states[0].taxels[0].neg[31], 131u);
  EXPECT_EQ(states[0].taxels[1].id, 103);
  EXPECT_EQ(states[1].body_part, "l_forearm");  // older extX/extY form
  EXPECT_EQ(states[1].grid, GridSpec::paper());
  EXPECT_EQ(states[1].taxels[0].pos[31], 32u);
  const TaxelMap m = make_map(states[1], states[1].taxels[0]);
  EXPECT_GT(m.activation(0.0, 1.0), 0.0);
}

TEST(PpsIniImport, BadFiles) {
  TempDir dir;
  EXPECT_EQ(import_error(dir, replace(kGood, "nTaxels \t2", "nTaxels \t3")),
            "1: section [r_hand] declares nTaxels 3 but lists 2 taxel lines");
  EXPECT_EQ(import_error(dir, replace(kGood, counts(100), "(1 2 3)")),
            "8: negative counts: 3 values, expected 32 (8 D bins x 4 TTC bins)");
  EXPECT_EQ(import_error(dir, replace(kGood, "(5 6 7", "(5 -6 7")),
            "9: positive count '-6' is not a non-negative integer");
  EXPECT_EQ(import_error(dir, replace(kGood, "(-0.1 0.2 0.0 1.2)", "(-0.1 0.2 0.0)")),
            "5: 'ext' has 3 numbers, expected 4");
  EXPECT_EQ(import_error(dir, replace(kGood, "binsNum \t(8\t4)", "binsNum \t8 4")),
            "6: 'binsNum' is '8 4', expected (2 numbers) in parentheses");
  EXPECT_EQ(import_error(dir, replace(kGood, "extY (0.0 3.0)\n", "")),
            "16: section [l_forearm] has no 'ext' (or 'extX' and 'extY') line");
  EXPECT_EQ(import_error(dir, replace(kGood, "\n103 ", "\n103 (1 2)")),
            "9: taxel line must be 'ID (32 positive counts) (32 negative counts)'");
  EXPECT_EQ(import_error(dir, replace(kGood, "Mapping", "Mappping")), "7: unknown key 'Mappping'");
  EXPECT_EQ(import_error(dir, "modality 2D\n"), "1: 'modality 2D' before the first [section]");
  EXPECT_EQ(import_error(dir, replace(kGood, "modality 2D", "modality 3D")),
            "16: section [l_forearm] has modality '3D', expected 2D (1D sections are skipped)");
  const std::string p = dir.file("empty.ini", "[l_hand]\nmodality 1D\n");
  try {
    import_taxels2d_ini(p);
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_EQ(std::string(e.what()), p + ": no 2D section found, expected at least one");
  }
}

// What write_taxels2d_ini writes, import_taxels2d_ini reads back exactly (grid, ids, counts).
TEST(PpsIniExport, RoundTrip) {
  TempDir dir;
  const auto parts = import_taxels2d_ini(dir.file("good.ini", kGood));
  std::ostringstream text;
  write_taxels2d_ini(parts, text);
  const auto again = import_taxels2d_ini(dir.file("again.ini", text.str()));
  ASSERT_EQ(again.size(), parts.size());
  for (std::size_t i = 0; i < parts.size(); ++i) {
    EXPECT_EQ(again[i].body_part, parts[i].body_part);
    EXPECT_EQ(again[i].grid, parts[i].grid);
    ASSERT_EQ(again[i].taxels.size(), parts[i].taxels.size());
    for (std::size_t k = 0; k < parts[i].taxels.size(); ++k) {
      EXPECT_EQ(again[i].taxels[k].id, parts[i].taxels[k].id);
      EXPECT_EQ(again[i].taxels[k].pos, parts[i].taxels[k].pos);
      EXPECT_EQ(again[i].taxels[k].neg, parts[i].taxels[k].neg);
    }
  }
  EXPECT_EQ(
      text.str().rfind(
          "[r_hand]\nmodality 2D\nnTaxels 2\next (-0.1 0.2 0 1.2)\nbinsNum (8 4)\n101 (0 1 2 ", 0),
      0u)
      << text.str();
}

TEST(PpsIniImport, SectionsWithoutModalityAre2D) {
  TempDir dir;
  const auto parts =
      import_taxels2d_ini(dir.file("old.ini",
                                   "[right_hand]\nnTaxels 1\nextX ( -0.1 0.2 )\nextY ( 0 1.2 )\n"
                                   "binsNum ( 2 1 )\n101 (1 2) (3 4)\n"));
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts[0].taxels[0].neg, (std::vector<somasim::pps::TaxelMap::Count>{3, 4}));
}

// Found by fuzz_ini_import: an 'ext' of 2 numbers read before the section said 'modality 2D'
// was indexed as 4 (heap overflow). Now a located error.
TEST(PpsIniImport, AnExtReadAs1DInA2DSectionIsAnError) {
  TempDir dir;
  const std::string text =
      "[hand]\nmodality 1D\next (0.0 0.2)\nmodality 2D\nbinsNum (2 1)\nnTaxels 1\n3 (1 2) (3 "
      "4)\n";
  EXPECT_EQ(import_error(dir, text),
            "1: section [hand]: 'ext' has 2 numbers, expected 4 (dmin dmax tmin tmax) for a 2D "
            "section");
}
