#include <fstream>
#include <functional>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "somasim/error.hpp"
#include "somasim/pps/map_io.hpp"
#include "temp_dir.hpp"

using namespace somasim::pps;
using nlohmann::json;

namespace {

LearnedState sample_state() {
  LearnedState s;
  s.body_part = "l_forearm";
  s.grid = GridSpec::code();
  s.parzen = ParzenSpec::code();
  for (int id : {3, 15}) {
    LearnedTaxel t;
    t.id = id;
    t.pose_link = TaxelPose{Eigen::Vector3d(0.01 * id, -0.02, 0.03), Eigen::Vector3d(0, 1, 0)};
    t.pos.assign(32, 0);
    t.neg.assign(32, 0);
    for (int k = 0; k < 32; ++k) {
      t.pos[k] = static_cast<TaxelMap::Count>(k * id % 7);
      t.neg[k] = static_cast<TaxelMap::Count>(k + id);
    }
    s.taxels.push_back(t);
  }
  return s;
}

// Two body parts: the sample's forearm and a one-taxel palm with other counts.
std::vector<LearnedState> two_parts() {
  LearnedState palm = sample_state();
  palm.body_part = "r_palm";
  palm.taxels.resize(1);
  palm.taxels[0].id = 7;
  palm.taxels[0].pos.assign(32, 2);
  return {sample_state(), palm};
}

std::string load_error(const TempDir& dir, const std::string& text,
                       const LoadExpectations& ex = {}) {
  const std::string p = dir.file("bad.json", text);
  try {
    load_learned_state(p, ex);
  } catch (const somasim::InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(p + ": ", 0), 0u) << msg;  // names the file
    return msg.substr(p.size() + 2);
  }
  ADD_FAILURE() << "no InputError";
  return {};
}

std::string mutated(const std::function<void(json&)>& f) {
  json j = to_json(sample_state());
  f(j);
  return j.dump();
}

std::string mutated_parts(const std::function<void(json&)>& f) {
  json j = to_json(two_parts());
  f(j);
  return j.dump();
}

// The message of load_learned_parts() on `text`, without the "<file>: " prefix.
std::string parts_error(const TempDir& dir, const std::string& text,
                        const PartsExpectations& ex = {}) {
  const std::string p = dir.file("bad_parts.json", text);
  try {
    load_learned_parts(p, ex);
  } catch (const somasim::InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(p + ": ", 0), 0u) << msg;
    return msg.substr(p.size() + 2);
  }
  ADD_FAILURE() << "no InputError";
  return {};
}

}  // namespace

TEST(PpsMapIo, SaveLoadRoundTrip) {
  TempDir dir;
  const LearnedState s = sample_state();
  const std::string p = dir.path("map.json");
  save_learned_state(s, p);
  const LearnedState r = load_learned_state(p, LoadExpectations{"l_forearm", 2, {}});
  EXPECT_EQ(r.body_part, s.body_part);
  EXPECT_EQ(r.grid, s.grid);
  EXPECT_EQ(r.parzen, s.parzen);
  ASSERT_EQ(r.taxels.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(r.taxels[k].id, s.taxels[k].id);
    EXPECT_EQ(r.taxels[k].pose_link.position, s.taxels[k].pose_link.position);
    EXPECT_EQ(r.taxels[k].pose_link.normal, s.taxels[k].pose_link.normal);
    EXPECT_EQ(r.taxels[k].pos, s.taxels[k].pos);
    EXPECT_EQ(r.taxels[k].neg, s.taxels[k].neg);
  }
  // Through a learner and back.
  const BodyPartLearner l = make_learner(r, LearnerParams::paper());
  EXPECT_EQ(l.params().grid, GridSpec::code());
  EXPECT_EQ(learned_state(l).taxels[1].neg, s.taxels[1].neg);
}

TEST(PpsMapIo, CorruptedFiles) {
  TempDir dir;
  EXPECT_EQ(load_error(dir, "{\"format\": ").substr(0, 16), "not valid JSON (");
  // Found by fuzz_learned_map: a number too large for a double is nlohmann's out_of_range, not
  // a parse_error; it escaped as an uncaught exception.
  EXPECT_EQ(load_error(dir, "{\"version\": 1e99999}").substr(0, 16), "not valid JSON (");
  EXPECT_EQ(load_error(dir, "[1, 2]"), "top level is array, expected a JSON object");
  EXPECT_EQ(load_error(dir, mutated([](json& j) { j["format"] = "other"; })),
            "'format' is \"other\", expected \"somasim-pps-map\"");
  EXPECT_EQ(load_error(dir, mutated([](json& j) { j["version"] = 4; })),
            "'version' is 4, expected 1, 2 or 3");
  EXPECT_EQ(load_error(dir, mutated([](json& j) { j["version"] = 2; })), "missing key 'model'");
  EXPECT_EQ(load_error(dir, mutated([](json& j) {
                         j["version"] = 2;
                         j["model"] = "ttc_only";
                       })),
            "'model' is \"ttc_only\", expected \"d_ttc\" or \"distance_only\"");
  EXPECT_EQ(load_error(dir, mutated([](json& j) { j.erase("grid"); })), "missing key 'grid'");
  EXPECT_EQ(load_error(dir, mutated([](json& j) { j["grid"]["d_bins"] = 8.5; })),
            "'grid.d_bins' is 8.5, expected an integer in [-2147483648, 2147483647]");
  // 2^32 + 8 must not be read as 8.
  EXPECT_EQ(load_error(dir, mutated([](json& j) { j["grid"]["d_bins"] = 4294967304LL; })),
            "'grid.d_bins' is 4294967304, expected an integer in [-2147483648, 2147483647]");
  EXPECT_EQ(load_error(dir, mutated([](json& j) { j["grid"]["d_max"] = -0.2; })),
            "invalid grid: D range [-0.1, -0.2] m must be finite with d_min < d_max");
  EXPECT_EQ(load_error(dir, mutated([](json& j) { j["parzen"]["anchor"] = "middle"; })),
            "'parzen.anchor' is \"middle\", expected \"centre\" or \"lower_edge\"");
  EXPECT_EQ(load_error(dir, mutated([](json& j) { j["taxels"][1]["pos"].erase(0); })),
            "'taxels[1].pos' has 31 entries, expected 32 (8 D bins x 4 TTC bins)");
  EXPECT_EQ(load_error(dir, mutated([](json& j) { j["taxels"][0]["neg"][5] = -1; })),
            "'taxels[0].neg[5]' is -1, expected a non-negative integer count");
  EXPECT_EQ(load_error(dir, mutated([](json& j) {
                         j["taxels"][0]["normal"] = {0, 1};
                       })),
            "'taxels[0].normal' is [0,1], expected an array of 3 numbers");
  EXPECT_EQ(load_error(dir, mutated([](json& j) {
                         j["taxels"][0]["normal"] = {0, 0, 0};
                       })),
            "'taxels[0].normal' is zero, expected a non-zero vector");
  EXPECT_EQ(load_error(dir, mutated([](json& j) { j["taxels"][1]["id"] = 3; })),
            "'taxels[1].id' is 3, which taxels[0] already uses; expected unique ids");
  EXPECT_EQ(load_error(dir, to_json(sample_state()).dump(), LoadExpectations{"r_hand", {}, {}}),
            "body part is \"l_forearm\", expected \"r_hand\"");
  EXPECT_EQ(load_error(dir, to_json(sample_state()).dump(), LoadExpectations{{}, 24, {}}),
            "has 2 taxels, expected 24");
}

TEST(PpsMapIo, MissingFile) {
  TempDir dir;
  const std::string p = dir.path("nope.json");
  try {
    load_learned_state(p);
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_EQ(std::string(e.what()), p + ": cannot open for reading");
  }
}

TEST(PpsMapIo, SeveralBodyPartsRoundTripAsVersion3) {
  TempDir dir;
  const std::vector<LearnedState> parts = two_parts();
  const std::string p = dir.path("parts.json");
  save_learned_parts(parts, p);
  std::ifstream in(p);
  const json j = json::parse(in);
  EXPECT_EQ(j["version"], 3);
  ASSERT_EQ(j["parts"].size(), 2u);
  EXPECT_EQ(j["parts"][1]["body_part"], "r_palm");
  EXPECT_EQ(j["parts"][1]["model"], "d_ttc");
  // All parts in file order, or the wanted ones in the wanted order.
  const auto all = load_learned_parts(p);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].body_part, "l_forearm");
  EXPECT_EQ(all[0].taxels[1].neg, parts[0].taxels[1].neg);
  EXPECT_EQ(all[1].grid, parts[1].grid);
  const auto wanted = load_learned_parts(p, PartsExpectations{{"r_palm", "l_forearm"}, {}});
  ASSERT_EQ(wanted.size(), 2u);
  EXPECT_EQ(wanted[0].body_part, "r_palm");
  EXPECT_EQ(wanted[0].taxels[0].pos, parts[1].taxels[0].pos);
  EXPECT_EQ(load_learned_parts(p, PartsExpectations{{"r_palm"}, {}}).size(), 1u);
  // One part of a version-3 file, by name.
  const LearnedState palm = load_learned_state(p, LoadExpectations{"r_palm", 1, PpsModel::kDTtc});
  EXPECT_EQ(palm.taxels[0].id, 7);
  // One part is still written as version 1.
  EXPECT_EQ(to_json(std::vector<LearnedState>{sample_state()})["version"], 1);
}

TEST(PpsMapIo, Version1And2FilesLoadAsOneBodyPart) {
  TempDir dir;
  const std::string p = dir.path("one.json");
  save_learned_state(sample_state(), p);
  const auto parts = load_learned_parts(p, PartsExpectations{{"l_forearm"}, PpsModel::kDTtc});
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts[0].taxels[0].pos, sample_state().taxels[0].pos);
  json j = to_json(sample_state());
  j["version"] = 2;
  j["model"] = "distance_only";
  j["grid"].erase("ttc_bins");
  for (auto& t : j["taxels"]) {
    t["pos"] = std::vector<int>(8, 1);
    t["neg"] = std::vector<int>(8, 0);
  }
  EXPECT_EQ(load_learned_parts(dir.file("v2.json", j.dump()))[0].model, PpsModel::kDistanceOnly);
}

TEST(PpsMapIo, SeveralBodyPartsErrors) {
  TempDir dir;
  const std::string text = to_json(two_parts()).dump();
  EXPECT_EQ(parts_error(dir, text, PartsExpectations{{"l_forearm", "l_hand"}, {}}),
            "has no body part \"l_hand\" (it has: l_forearm r_palm), expected every body part "
            "of \"l_forearm l_hand\"");
  // A one-part file missing one of several wanted parts.
  EXPECT_EQ(parts_error(dir, to_json(sample_state()).dump(),
                        PartsExpectations{{"l_forearm", "r_palm"}, {}}),
            "has no body part \"r_palm\" (it has: l_forearm), expected every body part of "
            "\"l_forearm r_palm\"");
  // One part wanted from a one-part file: the single-part message.
  EXPECT_EQ(parts_error(dir, to_json(sample_state()).dump(), PartsExpectations{{"r_palm"}, {}}),
            "body part is \"l_forearm\", expected \"r_palm\"");
  EXPECT_EQ(parts_error(dir, text, PartsExpectations{{}, PpsModel::kDistanceOnly}),
            "body part \"l_forearm\": model is \"d_ttc\", expected \"distance_only\"");
  EXPECT_EQ(
      parts_error(dir, mutated_parts([](json& j) { j["parts"][1]["body_part"] = "l_forearm"; })),
      "'parts[1].body_part' is \"l_forearm\", which parts[0] already uses; expected unique "
      "body parts");
  EXPECT_EQ(parts_error(dir, mutated_parts([](json& j) { j["parts"] = json::array(); })),
            "'parts' is empty, expected at least one body part");
  EXPECT_EQ(parts_error(dir, mutated_parts([](json& j) { j["parts"] = 3; })),
            "'parts' is number, expected an array of body parts");
  EXPECT_EQ(parts_error(dir, mutated_parts([](json& j) { j["parts"][1].erase("model"); })),
            "missing key 'parts[1].model'");
  EXPECT_EQ(parts_error(dir, mutated_parts([](json& j) { j["parts"][1]["grid"]["d_bins"] = 8.5; })),
            "'parts[1].grid.d_bins' is 8.5, expected an integer in [-2147483648, 2147483647]");
  EXPECT_EQ(
      parts_error(dir, mutated_parts([](json& j) { j["parts"][0]["taxels"][1]["pos"].erase(0); })),
      "'parts[0].taxels[1].pos' has 31 entries, expected 32 (8 D bins x 4 TTC bins)");
  EXPECT_EQ(parts_error(dir, mutated_parts([](json& j) { j["parts"][0]["taxels"][1]["id"] = 3; })),
            "'parts[0].taxels[1].id' is 3, which parts[0].taxels[0] already uses; expected unique "
            "ids");
  // load_learned_state on a version-3 file.
  EXPECT_EQ(load_error(dir, text),
            "has 2 body parts (l_forearm r_palm), expected one (name the "
            "body part to load)");
  EXPECT_EQ(load_error(dir, text, LoadExpectations{"l_hand", {}, {}}),
            "has no body part \"l_hand\" (it has: l_forearm r_palm), expected \"l_hand\"");
  EXPECT_EQ(load_error(dir, text, LoadExpectations{"r_palm", 3, {}}),
            "body part \"r_palm\" has 1 taxels, expected 3");
}
