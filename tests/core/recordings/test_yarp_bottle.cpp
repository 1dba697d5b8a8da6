// YARP Bottle text: values of every kind, generated bottles read back equal, located errors.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "somasim/recordings/yarp_bottle.hpp"

using namespace somasim::recordings;

namespace {

BottleValue random_value(std::mt19937_64& rng, int depth) {
  BottleValue v;
  const int kind = std::uniform_int_distribution<int>(0, depth < 4 ? 3 : 2)(rng);
  if (kind == 0) {
    v.kind = BottleValue::Kind::kInt;
    v.integer =
        std::uniform_int_distribution<std::int64_t>(-1'000'000'000'000, 1'000'000'000'000)(rng);
  } else if (kind == 1) {
    v.kind = BottleValue::Kind::kFloat;
    const double e = std::uniform_real_distribution<double>(-12, 12)(rng);
    v.real = std::uniform_real_distribution<double>(-1, 1)(rng) * std::pow(10.0, e);
  } else if (kind == 2) {
    v.kind = BottleValue::Kind::kString;
    static const std::string alphabet = "abc XYZ_/:.()\"\\[]{}-+0123456789e";
    const int n = std::uniform_int_distribution<int>(0, 8)(rng);
    for (int i = 0; i < n; ++i)
      v.text += alphabet[std::uniform_int_distribution<std::size_t>(0, alphabet.size() - 1)(rng)];
  } else {
    v.kind = BottleValue::Kind::kList;
    const int n = std::uniform_int_distribution<int>(0, 4)(rng);
    for (int i = 0; i < n; ++i) v.list.push_back(random_value(rng, depth + 1));
  }
  return v;
}

bool same(const BottleList& a, const BottleList& b);
bool same(const BottleValue& a, const BottleValue& b) {
  if (a.kind != b.kind) return false;
  switch (a.kind) {
    case BottleValue::Kind::kInt:
      return a.integer == b.integer;
    case BottleValue::Kind::kFloat:
      return a.real == b.real;
    case BottleValue::Kind::kString:
      return a.text == b.text;
    case BottleValue::Kind::kList:
      return same(a.list, b.list);
  }
  return false;
}
bool same(const BottleList& a, const BottleList& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!same(a[i], b[i])) return false;
  return true;
}

std::string error_of(const std::string& text, int& column) {
  try {
    parse_bottle(text);
  } catch (const BottleSyntaxError& e) {
    column = e.column();
    return e.what();
  }
  return "";
}

}  // namespace

TEST(YarpBottle, ReadsEveryKindWithColumns) {
  const BottleList b = parse_bottle(R"(12 -3 0.5 1e-3 inf left_arm "two words" [ok] (1 (2 3)))", 5);
  ASSERT_EQ(b.size(), 9u);
  EXPECT_EQ(b[0].kind, BottleValue::Kind::kInt);
  EXPECT_EQ(b[0].integer, 12);
  EXPECT_EQ(b[0].column, 5);
  EXPECT_EQ(b[1].integer, -3);
  EXPECT_EQ(b[2].kind, BottleValue::Kind::kFloat);
  EXPECT_DOUBLE_EQ(b[2].real, 0.5);
  EXPECT_DOUBLE_EQ(b[3].real, 1e-3);
  EXPECT_TRUE(std::isinf(b[4].real));
  EXPECT_EQ(b[5].kind, BottleValue::Kind::kString);
  EXPECT_EQ(b[5].text, "left_arm");
  EXPECT_EQ(b[6].text, "two words");
  EXPECT_EQ(b[7].text, "[ok]");
  ASSERT_EQ(b[8].kind, BottleValue::Kind::kList);
  EXPECT_EQ(b[8].column, 5 + 45);
  ASSERT_EQ(b[8].list.size(), 2u);
  EXPECT_EQ(b[8].list[1].list[1].integer, 3);
  EXPECT_TRUE(parse_bottle("").empty());
  EXPECT_TRUE(parse_bottle("   ").empty());
}

TEST(YarpBottle, GeneratedBottlesReadBackEqual) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 2000; ++trial) {
    BottleList b;
    const int n = std::uniform_int_distribution<int>(0, 6)(rng);
    for (int i = 0; i < n; ++i) b.push_back(random_value(rng, 0));
    const std::string text = to_text(b);
    BottleList back;
    ASSERT_NO_THROW(back = parse_bottle(text)) << text;
    ASSERT_TRUE(same(b, back)) << "trial " << trial << ": " << text << " -> " << to_text(back);
  }
}

TEST(YarpBottle, SyntaxErrorsNameTheirColumn) {
  struct Case {
    std::string text;
    int column;
    std::string message;
  };
  const Case cases[] = {
      {"1 (2 3", 3, "unbalanced '(': the list is never closed"},
      {"1 2) 3", 4, "unbalanced ')': no list is open here"},
      {"a \"open", 3, "unterminated string: no closing '\"'"},
      {"1 {0 1}", 3, "binary blobs ('{...}') are not supported"},
      {"[ok", 1, "unterminated vocabulary: no ']'"},
      {std::string(65, '(') + std::string(65, ')'), 65, "lists nested deeper than 64"},
  };
  for (const Case& c : cases) {
    int column = 0;
    EXPECT_EQ(error_of(c.text, column), c.message) << c.text;
    EXPECT_EQ(column, c.column) << c.text;
  }
}
