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

}  // namespace

TEST(PpsMapIo, SaveLoadRoundTrip) {
  TempDir dir;
  const LearnedState s = sample_state();
  const std::string p = dir.path("map.json");
  save_learned_state(s, p);
  const LearnedState r = load_learned_state(p, LoadExpectations{"l_forearm", 2});
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
  EXPECT_EQ(load_error(dir, "[1, 2]"), "top level is array, expected a JSON object");
  EXPECT_EQ(load_error(dir, mutated([](json& j) { j["format"] = "other"; })),
            "'format' is \"other\", expected \"somasim-pps-map\"");
  EXPECT_EQ(load_error(dir, mutated([](json& j) { j["version"] = 3; })),
            "'version' is 3, expected 1 or 2");
  EXPECT_EQ(load_error(dir, mutated([](json& j) { j["version"] = 2; })), "missing key 'model'");
  EXPECT_EQ(load_error(dir, mutated([](json& j) {
                         j["version"] = 2;
                         j["model"] = "ttc_only";
                       })),
            "'model' is \"ttc_only\", expected \"d_ttc\" or \"distance_only\"");
  EXPECT_EQ(load_error(dir, mutated([](json& j) { j.erase("grid"); })), "missing key 'grid'");
  EXPECT_EQ(load_error(dir, mutated([](json& j) { j["grid"]["d_bins"] = 8.5; })),
            "'grid.d_bins' is 8.5, expected an integer");
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
  EXPECT_EQ(load_error(dir, to_json(sample_state()).dump(), LoadExpectations{"r_hand", {}}),
            "body part is \"l_forearm\", expected \"r_hand\"");
  EXPECT_EQ(load_error(dir, to_json(sample_state()).dump(), LoadExpectations{{}, 24}),
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
