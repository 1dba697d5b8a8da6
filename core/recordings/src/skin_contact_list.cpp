#include "somasim/recordings/skin_contact_list.hpp"

#include <array>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace somasim::recordings {

namespace {

constexpr std::array<std::string_view, 14> kSkinPartNames = {
    "unknown",       "left_hand",       "left_forearm",    "left_upper_arm", "right_hand",
    "right_forearm", "right_upper_arm", "front_torso",     "left_upper_leg", "left_lower_leg",
    "left_foot",     "right_upper_leg", "right_lower_leg", "right_foot"};

constexpr const char* kLayout =
    "((ID BODY_PART LINK SKIN_PART) (CoP) (force) (moment) (centre) (normal) (TAXELS) PRESSURE)";

[[noreturn]] void fail(int column, std::size_t contact, const std::string& what) {
  throw BottleSyntaxError(
      column, fmt::format("skin contact {}: {}; a contact is {}", contact, what, kLayout));
}

std::int64_t integer_at(const BottleValue& v, std::size_t contact, const char* field) {
  if (v.kind != BottleValue::Kind::kInt)
    fail(v.column, contact, fmt::format("{} must be an integer, got {}", field, kind_name(v.kind)));
  return v.integer;
}

int small_integer_at(const BottleValue& v, std::size_t contact, const char* field) {
  const std::int64_t i = integer_at(v, contact, field);
  if (i < std::numeric_limits<int>::min() || i > std::numeric_limits<int>::max())
    fail(v.column, contact, fmt::format("{} {} is out of range", field, i));
  return static_cast<int>(i);
}

Eigen::Vector3d vector_at(const BottleValue& v, std::size_t contact, const char* field) {
  if (v.kind != BottleValue::Kind::kList || v.list.size() != 3)
    fail(v.column, contact,
         fmt::format("{} must be a list of 3 numbers, got {}", field,
                     v.kind == BottleValue::Kind::kList ? fmt::format("a list of {}", v.list.size())
                                                        : std::string(kind_name(v.kind))));
  Eigen::Vector3d out;
  for (int k = 0; k < 3; ++k) {
    const BottleValue& x = v.list[static_cast<std::size_t>(k)];
    if (!x.is_number() || !std::isfinite(x.number()))
      fail(x.column, contact, fmt::format("{} must hold finite numbers", field));
    out[k] = x.number();
  }
  return out;
}

SkinContactRecord decode_contact(const BottleValue& v, std::size_t contact) {
  if (v.kind != BottleValue::Kind::kList)
    fail(v.column, contact, fmt::format("expected a list, got {}", kind_name(v.kind)));
  const BottleList& f = v.list;
  if (f.size() != 8) fail(v.column, contact, fmt::format("expected 8 fields, got {}", f.size()));
  SkinContactRecord r;
  if (f[0].kind != BottleValue::Kind::kList || f[0].list.size() != 4)
    fail(f[0].column, contact,
         "the first field must be the 4 integers (ID BODY_PART LINK SKIN_PART)");
  r.contact_id = integer_at(f[0].list[0], contact, "the contact id");
  r.body_part = small_integer_at(f[0].list[1], contact, "the body part");
  r.link = small_integer_at(f[0].list[2], contact, "the link");
  r.skin_part = small_integer_at(f[0].list[3], contact, "the skin part");
  r.centre_of_pressure = vector_at(f[1], contact, "the centre of pressure");
  r.force = vector_at(f[2], contact, "the force");
  r.moment = vector_at(f[3], contact, "the moment");
  r.geometric_centre = vector_at(f[4], contact, "the geometric centre");
  r.normal = vector_at(f[5], contact, "the normal");
  if (f[6].kind != BottleValue::Kind::kList)
    fail(f[6].column, contact,
         fmt::format("the taxels must be a list of ids, got {}", kind_name(f[6].kind)));
  for (const BottleValue& t : f[6].list) {
    const int id = small_integer_at(t, contact, "a taxel id");
    if (id < 0) fail(t.column, contact, fmt::format("taxel id {} is negative", id));
    r.taxels.push_back(id);
  }
  if (!f[7].is_number() || !std::isfinite(f[7].number()))
    fail(f[7].column, contact, "the pressure must be a finite number");
  r.pressure = f[7].number();
  return r;
}

}  // namespace

std::vector<SkinContactRecord> decode_skin_contact_list(const BottleList& bottle) {
  std::vector<SkinContactRecord> out;
  out.reserve(bottle.size());
  for (std::size_t i = 0; i < bottle.size(); ++i) out.push_back(decode_contact(bottle[i], i + 1));
  return out;
}

std::optional<std::string_view> icub_skin_part_name(int skin_part) {
  if (skin_part < 1 || skin_part >= static_cast<int>(kSkinPartNames.size())) return std::nullopt;
  return kSkinPartNames[static_cast<std::size_t>(skin_part)];
}

std::optional<int> icub_skin_part_id(std::string_view name) {
  for (std::size_t i = 1; i < kSkinPartNames.size(); ++i)
    if (kSkinPartNames[i] == name) return static_cast<int>(i);
  return std::nullopt;
}

}  // namespace somasim::recordings
