// The iCub skin's contact lists: a recorded line decoded field by field; every malformed field
// refused at its column with what was expected.
#include <gtest/gtest.h>

#include "somasim/recordings/skin_contact_list.hpp"

using namespace somasim::recordings;

namespace {
// A line in the format of /skinManager/skin_events:o (two contacts; values made up here).
const char* kLine =
    "((1201 3 4 2) (0.0312 -0.0587 -0.0101) (-6.25 0.31 1.5) (0.0 0.0 0.0) "
    "(0.0315 -0.0590 -0.0098) (0.86 -0.04 -0.21) (250 261 263) 51.5) "
    "((1202 3 6 1) (0.0 0.0 0.0) (-0.0 -0.0 -0.0) (0.0 0.0 0.0) (0.0 0.0 0.0) (0.0 0.0 0.0) "
    "(48) 17.25)";

std::string error_of(const std::string& text, int& column) {
  try {
    decode_skin_contact_list(parse_bottle(text));
  } catch (const BottleSyntaxError& e) {
    column = e.column();
    return e.what();
  }
  return "";
}
}  // namespace

TEST(SkinContactList, DecodesARecordedLine) {
  const auto contacts = decode_skin_contact_list(parse_bottle(kLine));
  ASSERT_EQ(contacts.size(), 2u);
  const SkinContactRecord& c = contacts[0];
  EXPECT_EQ(c.contact_id, 1201);
  EXPECT_EQ(c.body_part, 3);
  EXPECT_EQ(c.link, 4);
  EXPECT_EQ(c.skin_part, 2);
  EXPECT_EQ(icub_skin_part_name(c.skin_part).value(), "left_forearm");
  EXPECT_DOUBLE_EQ(c.centre_of_pressure.y(), -0.0587);
  EXPECT_DOUBLE_EQ(c.force.x(), -6.25);
  EXPECT_DOUBLE_EQ(c.geometric_centre.z(), -0.0098);
  EXPECT_DOUBLE_EQ(c.normal.x(), 0.86);
  EXPECT_EQ(c.taxels, (std::vector<int>{250, 261, 263}));
  EXPECT_DOUBLE_EQ(c.pressure, 51.5);
  EXPECT_EQ(icub_skin_part_name(contacts[1].skin_part).value(), "left_hand");
  EXPECT_TRUE(decode_skin_contact_list(parse_bottle("")).empty());
}

TEST(SkinContactList, PartNamesRoundTrip) {
  for (int id = 1; id <= 13; ++id)
    EXPECT_EQ(icub_skin_part_id(icub_skin_part_name(id).value()), id);
  EXPECT_FALSE(icub_skin_part_name(0));
  EXPECT_FALSE(icub_skin_part_name(14));
  EXPECT_FALSE(icub_skin_part_id("left_elbow"));
}

TEST(SkinContactList, MalformedFieldsAreLocated) {
  const std::string layout =
      "; a contact is ((ID BODY_PART LINK SKIN_PART) (CoP) (force) (moment) (centre) (normal) "
      "(TAXELS) PRESSURE)";
  struct Case {
    std::string text;
    int column;
    std::string message;
  };
  const std::string ok_tail = "(0 0 0) (0 0 0) (0 0 0) (0 0 0) (0 0 0) (1 2) 3.5";
  const Case cases[] = {
      {"5", 1, "skin contact 1: expected a list, got an integer"},
      {"((1 2 3 4) (0 0 0))", 1, "skin contact 1: expected 8 fields, got 2"},
      {"((1 2 3) " + ok_tail + ")", 2,
       "skin contact 1: the first field must be the 4 integers (ID BODY_PART LINK SKIN_PART)"},
      {"((1 2 x 4) " + ok_tail + ")", 7,
       "skin contact 1: the link must be an integer, got a string"},
      {"((1 2 3 4) (0 0) (0 0 0) (0 0 0) (0 0 0) (0 0 0) (1) 3)", 12,
       "skin contact 1: the centre of pressure must be a list of 3 numbers, got a list of 2"},
      {"((1 2 3 4) (0 0 0) (0 nan 0) (0 0 0) (0 0 0) (0 0 0) (1) 3)", 23,
       "skin contact 1: the force must hold finite numbers"},
      {"((1 2 3 4) (0 0 0) (0 0 0) (0 0 0) (0 0 0) (0 0 0) (1 -2) 3)", 55,
       "skin contact 1: taxel id -2 is negative"},
      {"((1 2 3 4) (0 0 0) (0 0 0) (0 0 0) (0 0 0) (0 0 0) 7 3)", 52,
       "skin contact 1: the taxels must be a list of ids, got an integer"},
      {"((1 2 3 4) (0 0 0) (0 0 0) (0 0 0) (0 0 0) (0 0 0) (1) p)", 56,
       "skin contact 1: the pressure must be a finite number"},
      {"((1 2 3 4) " + ok_tail + ") ((1 2 3 99999999999) " + ok_tail + ")", 71,
       "skin contact 2: the skin part 99999999999 is out of range"},
  };
  for (const Case& c : cases) {
    int column = 0;
    EXPECT_EQ(error_of(c.text, column), c.message + layout) << c.text;
    EXPECT_EQ(column, c.column) << c.text;
  }
}
