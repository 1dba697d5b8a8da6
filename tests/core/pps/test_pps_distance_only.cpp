// The distance-only model (the paper's S2 ablation): learning, activation, file format.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "somasim/error.hpp"
#include "somasim/pps/body_part_learner.hpp"
#include "somasim/pps/learned_state.hpp"
#include "somasim/pps/map_io.hpp"
#include "temp_dir.hpp"

using namespace somasim::pps;

namespace {

std::vector<TaxelInfo> two_taxels() {
  return {TaxelInfo{10, TaxelPose{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d::UnitZ()}},
          TaxelInfo{11, TaxelPose{Eigen::Vector3d(0.05, 0, 0), Eigen::Vector3d::UnitZ()}}};
}

LearnerParams params(PpsModel model) {
  LearnerParams p = LearnerParams::paper();
  p.model = model;
  return p;
}

// Two approaches along -z onto taxel 10 at 0.1 m/s from 0.15 m, each ending in a touch.
void learn(BodyPartLearner& l) {
  const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  const std::vector<int> touched = {10};
  for (int rep = 0; rep < 2; ++rep) {
    for (int i = 0; i < 30; ++i)
      l.push_stimulus(StimulusSample{
          10.0 * rep + 0.05 * i,
          Stimulus{Eigen::Vector3d(0, 0, 0.15 - 0.005 * i), Eigen::Vector3d(0, 0, -0.1), 0.0}});
    l.on_contact(pose, touched);
  }
}

const TaxelPose kTaxel10{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d::UnitZ()};

}  // namespace

TEST(PpsDistanceOnly, MapsHaveTheDAxisAndOneTtcBin) {
  BodyPartLearner l("patch", two_taxels(), params(PpsModel::kDistanceOnly));
  EXPECT_EQ(l.map_grid().d_bins, 8);
  EXPECT_EQ(l.map_grid().ttc_bins, 1);
  EXPECT_EQ(l.maps()[0].pos().size(), 8u);
  learn(l);
  std::uint32_t pos = 0;
  for (auto c : l.maps()[0].pos()) pos += c;
  EXPECT_EQ(pos, 60u);
  EXPECT_EQ(l.totals().invalid_ttc, 0u);
}

TEST(PpsDistanceOnly, StaticObjectNearTheSkinActivatesDistanceOnlyButNotDTtc) {
  BodyPartLearner dist("patch", two_taxels(), params(PpsModel::kDistanceOnly));
  BodyPartLearner dttc("patch", two_taxels(), params(PpsModel::kDTtc));
  learn(dist);
  learn(dttc);
  const Stimulus approaching{Eigen::Vector3d(0, 0, 0.06), Eigen::Vector3d(0, 0, -0.1), 0.0};
  const Stimulus still{Eigen::Vector3d(0, 0, 0.06), Eigen::Vector3d::Zero(), 0.0};
  EXPECT_GT(dttc.activation(0, kTaxel10, approaching), 0.5);
  EXPECT_GT(dist.activation(0, kTaxel10, approaching), 0.5);
  EXPECT_EQ(dttc.activation(0, kTaxel10, still), 0.0);
  EXPECT_GT(dist.activation(0, kTaxel10, still), 0.5);
  EXPECT_DOUBLE_EQ(dist.activation(0, kTaxel10, still), dist.activation(0, kTaxel10, approaching));
}

TEST(PpsDistanceOnly, RecedingObjectActivatesDistanceOnlyButNotDTtc) {
  BodyPartLearner dist("patch", two_taxels(), params(PpsModel::kDistanceOnly));
  BodyPartLearner dttc("patch", two_taxels(), params(PpsModel::kDTtc));
  learn(dist);
  learn(dttc);
  const Stimulus receding{Eigen::Vector3d(0, 0, 0.06), Eigen::Vector3d(0, 0, 0.1), 0.0};
  EXPECT_EQ(dttc.activation(0, kTaxel10, receding), 0.0);
  EXPECT_GT(dist.activation(0, kTaxel10, receding), 0.5);
  // Far away (beyond the learned D) and outside the RF both models stay silent.
  const Stimulus far{Eigen::Vector3d(0, 0, 0.19), Eigen::Vector3d::Zero(), 0.0};
  EXPECT_LT(dist.activation(0, kTaxel10, far), dist.activation(0, kTaxel10, receding));
  const Stimulus aside{Eigen::Vector3d(0.2, 0, 0.01), Eigen::Vector3d::Zero(), 0.0};
  EXPECT_EQ(dist.activation(0, kTaxel10, aside), 0.0);
}

TEST(PpsDistanceOnly, ActivationIsTheMaxNormalisedParzenSumOverD) {
  BodyPartLearner l("patch", two_taxels(), params(PpsModel::kDistanceOnly));
  learn(l);
  const TaxelMap& m = l.maps()[0];
  const GridSpec& g = l.map_grid();
  const double sd = g.d_width();  // paper: sigma = 1 bin, kernels at bin centres
  auto f = [&](double d) {
    double s = 0;
    for (int i = 0; i < g.d_bins; ++i) {
      const double c = g.d_min + (i + 0.5) * g.d_width();
      s += m.ratio(i, 0) * std::exp(-0.5 * (d - c) * (d - c) / (sd * sd));
    }
    return s;
  };
  double mx = 0;
  for (int i = 0; i < g.d_bins; ++i) mx = std::max(mx, f(g.d_min + (i + 0.5) * g.d_width()));
  for (double d : {-0.05, 0.0, 0.03, 0.1, 0.15}) {
    const Stimulus s{Eigen::Vector3d(0, 0, d), Eigen::Vector3d::Zero(), 0.0};
    const double expected = d < 0 ? 0.0 : std::min(1.0, f(d) / mx);  // cone RF: nothing behind
    EXPECT_NEAR(l.activation(0, kTaxel10, s), expected, 1e-12) << d;
  }
}

TEST(PpsDistanceOnly, SaveLoadRoundTripAsVersion2) {
  TempDir dir;
  BodyPartLearner l("patch", two_taxels(), params(PpsModel::kDistanceOnly));
  learn(l);
  const std::string p = dir.path("d.json");
  save_learned_state(learned_state(l), p);
  std::ifstream in(p);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["version"], 2);
  EXPECT_EQ(j["model"], "distance_only");
  EXPECT_FALSE(j["grid"].contains("ttc_bins"));
  EXPECT_EQ(j["taxels"][0]["pos"].size(), 8u);
  LoadExpectations ex;
  ex.model = PpsModel::kDistanceOnly;
  const LearnedState s = load_learned_state(p, ex);
  EXPECT_EQ(s.model, PpsModel::kDistanceOnly);
  const BodyPartLearner back = make_learner(s, LearnerParams::paper());
  EXPECT_EQ(back.params().model, PpsModel::kDistanceOnly);
  EXPECT_EQ(back.maps()[0].pos(), l.maps()[0].pos());
  const Stimulus still{Eigen::Vector3d(0, 0, 0.06), Eigen::Vector3d::Zero(), 0.0};
  EXPECT_DOUBLE_EQ(back.activation(0, kTaxel10, still), l.activation(0, kTaxel10, still));
  ex.model = PpsModel::kDTtc;
  try {
    load_learned_state(p, ex);
    FAIL() << "expected an InputError";
  } catch (const somasim::InputError& e) {
    EXPECT_EQ(std::string(e.what()), p + ": model is \"distance_only\", expected \"d_ttc\"");
  }
}

TEST(PpsDistanceOnly, DTtcMapsStayVersion1AndVersion1FilesStillLoad) {
  TempDir dir;
  BodyPartLearner l("patch", two_taxels(), params(PpsModel::kDTtc));
  learn(l);
  const nlohmann::json j = to_json(learned_state(l));
  EXPECT_EQ(j["version"], 1);
  EXPECT_FALSE(j.contains("model"));
  LoadExpectations ex;
  ex.model = PpsModel::kDTtc;
  const LearnedState s = from_json(j, "mem", ex);
  EXPECT_EQ(s.model, PpsModel::kDTtc);
  EXPECT_EQ(s.grid.ttc_bins, 4);
  // A version-2 file may name the (D, TTC) model explicitly.
  nlohmann::json j2 = j;
  j2["version"] = 2;
  j2["model"] = "d_ttc";
  EXPECT_EQ(from_json(j2, "mem").taxels[0].pos, s.taxels[0].pos);
  ex.model = PpsModel::kDistanceOnly;
  EXPECT_THROW(from_json(j, "mem", ex), somasim::InputError);
}
