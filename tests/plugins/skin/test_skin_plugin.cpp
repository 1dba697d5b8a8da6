// skin plugin: contacts on the iCub's left forearm -> contact events, pressures, taxel poses.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/skin/ports.hpp"
#include "somasim/skin/skin_layout.hpp"
#include "somasim/testing/harness.hpp"

using somasim::ContactEvents;
using somasim::Contacts;
using somasim::LinkPoses;
using somasim::SkinTaxels;
using somasim::TaxelValues;
using somasim::testing::Harness;

namespace {

const std::string kRobot = SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml";

// The skin node with the test's defaults; `params` ("key: value, ...") adds or overrides.
std::string graph(const std::string& params = "") {
  std::map<std::string, std::string> p = {{"robot", "icub"},
                                          {"spacing", "0.005"},
                                          {"group_size", "10"},
                                          {"contact_radius", "0.008"},
                                          {"pressure_threshold", "0.01"}};
  std::string rest = params;
  while (!rest.empty()) {  // "k: v, k: 'a, b'" (values with commas are quoted)
    const auto colon = rest.find(':');
    std::string key = rest.substr(0, colon);
    key.erase(0, key.find_first_not_of(' '));
    std::size_t start = rest.find_first_not_of(' ', colon + 1);
    std::size_t end = rest[start] == '\'' ? rest.find('\'', start + 1) + 1 : rest.find(',', start);
    p[key] = rest.substr(start, end == std::string::npos ? end : end - start);
    rest = end == std::string::npos || end >= rest.size() ? "" : rest.substr(end + 1);
    if (!rest.empty() && rest[0] == ',') rest = rest.substr(1);
  }
  std::string list;
  for (const auto& [k, v] : p) list += (list.empty() ? "" : ", ") + k + ": " + v;
  return "base_rate_hz: 50\nrobots: {icub: " + kRobot +
         "}\nnodes:\n  skin:\n    plugin: skin\n    params: {" + list +
         "}\n    inputs: {link_poses: harness.links, contacts: harness.contacts}\n";
}

const somasim::robot::RobotModel& model() {
  static const auto m = somasim::robot::load_robot_model_shared(kRobot);
  return *m;
}

// Link poses at q = 0 from the model's kinematics.
std::vector<Eigen::Isometry3d> rest_poses() {
  somasim::robot::RobotData data(model());
  somasim::robot::forward_kinematics(model(), data, Eigen::VectorXd::Zero(model().num_dofs()));
  return data.link_poses;
}

const somasim::robot::SkinPatch& patch(const std::string& part) {
  for (const auto& p : model().skin_patches())
    if (p.body_part == part) return p;
  throw std::runtime_error("no patch " + part);
}

// The layout the plugin generates for the graph's parameters.
somasim::skin::SkinLayout forearm_layout() {
  somasim::skin::LayoutOptions o;
  o.spacing = 0.005;
  o.group_size = 10;
  return somasim::skin::generate_layout(patch("left_forearm"), o);
}

// A contact on the left forearm's skin at `point_link` (link frame), pressed by object 0.
somasim::Contact forearm_contact(const Eigen::Vector3d& point_link, double force) {
  somasim::Contact c;
  c.link_a = model().find_link("l_forearm");
  c.object_b = 0;
  c.point_in_a = point_link;
  c.point = rest_poses()[static_cast<std::size_t>(c.link_a)] * point_link;
  c.normal_force = force;
  return c;
}

// Virtual ids with a physical taxel within `radius` of `p` (all are over threshold for 1 N).
std::vector<int> modules_within(const somasim::skin::SkinLayout& l, const Eigen::Vector3d& p,
                                double radius) {
  std::set<int> ids;
  for (std::size_t i = 0; i < l.size(); ++i)
    if ((l.positions[i] - p).norm() <= radius)
      ids.insert(l.virtual_taxels[static_cast<std::size_t>(l.module[i])].id);
  return {ids.begin(), ids.end()};
}

}  // namespace

TEST(SkinPlugin, ContactOnTheForearmFiresOneEventWithTheTouchedVirtualTaxels) {
  Harness h(graph());
  h.input<LinkPoses>("links").poses = rest_poses();
  const auto layout = forearm_layout();
  const std::size_t v = layout.virtual_taxels.size() / 2;
  const Eigen::Vector3d p = layout.virtual_position(v);
  h.input<Contacts>("contacts").points = {forearm_contact(p, 1.0)};
  h.step();
  const auto& events = h.output<ContactEvents>("skin.contacts").recent;
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].id, 1u);
  EXPECT_EQ(events[0].body_part, "left_forearm");
  EXPECT_EQ(events[0].time_s, 0.0);
  const std::vector<int> expected = modules_within(layout, p, 0.008);
  EXPECT_EQ(events[0].touched_taxels, expected);
  EXPECT_NE(std::find(expected.begin(), expected.end(), layout.virtual_taxels[v].id),
            expected.end());

  // Pressures: per virtual taxel, in the order of the 'taxels' output.
  const auto& skin = h.output<SkinTaxels>("skin.taxels");
  const auto& pressures = h.output<TaxelValues>("skin.pressures");
  ASSERT_EQ(skin.parts.size(), 2u);
  EXPECT_EQ(skin.parts[0].name, "left_forearm");
  EXPECT_EQ(skin.parts[0].link, "l_forearm");
  ASSERT_EQ(pressures.values.size(),
            skin.parts[0].taxel_ids.size() + skin.parts[1].taxel_ids.size());
  EXPECT_EQ(pressures.labels[v], "left_forearm/" + std::to_string(layout.virtual_taxels[v].id));
  EXPECT_GT(pressures.values[v], 0.01);

  // The contact persists: no new event. It ends, then a new one: a second event.
  h.step(10);
  EXPECT_EQ(h.output<ContactEvents>("skin.contacts").recent.size(), 1u);
  h.input<Contacts>("contacts").points.clear();
  h.step(10);
  h.input<Contacts>("contacts").points = {forearm_contact(p, 1.0)};
  h.step();
  ASSERT_EQ(h.output<ContactEvents>("skin.contacts").recent.size(), 2u);
  EXPECT_EQ(h.output<ContactEvents>("skin.contacts").recent[1].id, 2u);
  EXPECT_EQ(h.finish(), "");
  EXPECT_EQ(h.metric("skin", "events_per_part")["left_forearm"], 2);
  EXPECT_EQ(h.metric("skin", "events_per_part")["right_palm"], 0);
  EXPECT_EQ(h.metric("skin", "events_total"), 2);
  EXPECT_EQ(h.metric("skin", "taxels_fired")["left_forearm"]["virtual"], expected);
  EXPECT_TRUE(std::filesystem::exists(h.out_dir() / "figures" / "skin_layout.png"));
}

TEST(SkinPlugin, SkinLinkOnSideBCounts) {
  Harness h(graph());
  const auto poses = rest_poses();
  h.input<LinkPoses>("links").poses = poses;
  const auto layout = forearm_layout();
  somasim::Contact c = forearm_contact(layout.virtual_position(3), 1.0);
  std::swap(c.link_a, c.link_b);
  std::swap(c.object_a, c.object_b);
  c.point_in_a = Eigen::Vector3d(0.01, 0, 0);  // in the object's frame: not used for side b
  h.input<Contacts>("contacts").points = {c};
  h.step();
  const auto& events = h.output<ContactEvents>("skin.contacts").recent;
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].touched_taxels, modules_within(layout, layout.virtual_position(3), 0.008));
}

TEST(SkinPlugin, NoEventBelowThresholdOnTooFewTaxelsOrOffTheSkin) {
  const auto layout = forearm_layout();
  const Eigen::Vector3d p = layout.virtual_position(layout.virtual_taxels.size() / 2);
  {
    Harness h(graph("pressure_threshold: 0.5"));  // 1 N over ~9 taxels: ~0.11 N each
    h.input<LinkPoses>("links").poses = rest_poses();
    h.input<Contacts>("contacts").points = {forearm_contact(p, 1.0)};
    h.step(5);
    EXPECT_TRUE(h.output<ContactEvents>("skin.contacts").recent.empty());
  }
  {
    Harness h(graph("contact_radius: 0.004"));  // 1 taxel (spacing 5 mm) in the radius
    h.input<LinkPoses>("links").poses = rest_poses();
    h.input<Contacts>("contacts").points = {forearm_contact(layout.positions[40], 1.0)};
    h.step(5);
    EXPECT_TRUE(h.output<ContactEvents>("skin.contacts").recent.empty());
  }
  {
    Harness h(graph());
    h.input<LinkPoses>("links").poses = rest_poses();
    somasim::Contact c = forearm_contact(p, 1.0);
    c.link_a = model().find_link("l_upper_arm");  // no skin there
    h.input<Contacts>("contacts").points = {c};
    h.step(5);
    EXPECT_TRUE(h.output<ContactEvents>("skin.contacts").recent.empty());
  }
}

TEST(SkinPlugin, TaxelPosesInTheRootFrameFollowTheLinks) {
  Harness h(graph());
  std::vector<Eigen::Isometry3d> poses = rest_poses();
  // Any rigid motion of the links: the taxels move with them.
  for (auto& pose : poses)
    pose = Eigen::Translation3d(0.1, -0.2, 0.3) *
           Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) * pose;
  h.input<LinkPoses>("links").poses = poses;
  h.step();
  const auto& skin = h.output<SkinTaxels>("skin.taxels");
  ASSERT_EQ(skin.parts.size(), 2u);
  for (const auto& part : skin.parts) {
    const auto& pose = poses[static_cast<std::size_t>(model().find_link(part.link))];
    ASSERT_FALSE(part.taxel_ids.empty());
    ASSERT_EQ(part.positions.size(), part.taxel_ids.size());
    for (std::size_t k = 0; k < part.taxel_ids.size(); ++k) {
      EXPECT_TRUE(part.positions[k].isApprox(pose * part.positions_link[k], 1e-12));
      EXPECT_TRUE(part.normals[k].isApprox(pose.linear() * part.normals_link[k], 1e-12));
      EXPECT_NEAR(part.normals[k].norm(), 1.0, 1e-12);
    }
  }
  const auto layout = forearm_layout();
  EXPECT_EQ(skin.parts[0].taxel_ids.size(), layout.virtual_taxels.size());
  EXPECT_TRUE(skin.parts[0].positions_link[0].isApprox(layout.virtual_position(0)));
}

TEST(SkinPlugin, LayoutFromAFile) {
  const auto dir = std::filesystem::temp_directory_path() / "somasim_skin_plugin_layout";
  std::filesystem::create_directories(dir);
  const auto file = dir / "palm.txt";
  {
    std::ofstream out(file);
    out << "# id x y z nx ny nz module\n";
    for (int i = 0; i < 6; ++i)
      out << i << " " << -0.03 + 0.004 * i << " 0 0 0 0 1 " << i / 3 << "\n";
  }
  Harness h(graph("parts: right_palm, layout_files: right_palm=" + file.string()));
  const auto& skin = h.output<SkinTaxels>("skin.taxels");
  ASSERT_EQ(skin.parts.size(), 1u);
  EXPECT_EQ(skin.parts[0].name, "right_palm");
  EXPECT_EQ(skin.parts[0].taxel_ids, (std::vector<int>{0, 1}));
  EXPECT_TRUE(skin.parts[0].positions_link[0].isApprox(Eigen::Vector3d(-0.026, 0, 0)));
  std::filesystem::remove_all(dir);
}

TEST(SkinPlugin, UnknownBodyPartIsAClearError) {
  try {
    Harness h(graph("parts: 'left_forarm, right_palm'"));
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "<inline>:6:60: node 'skin', key 'params.parts': unknown body part "
                 "'left_forarm' (did you mean 'left_forearm'?); robot 'icub_v1' has skin on: "
                 "left_forearm, right_palm");
  }
}

TEST(SkinPlugin, BadLayoutFilesParameter) {
  try {
    Harness h(graph("layout_files: right_palm"));
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "<inline>:6:67: node 'skin', key 'params.layout_files': expected 'part=file' "
                 "items separated by commas, got 'right_palm'");
  }
}

// Skipped work must not change outputs: taxels still follow a link that moves after standing
// still, and pressures fall back to zero (and rise again) when contacts come and go.
TEST(SkinPlugin, PosesAndPressuresFollowChangesAfterQuietSteps) {
  Harness h(graph());
  std::vector<Eigen::Isometry3d> poses = rest_poses();
  h.input<LinkPoses>("links").poses = poses;
  h.step(3);  // the links stand still
  const int forearm = model().find_link("l_forearm");
  poses[static_cast<std::size_t>(forearm)].translate(Eigen::Vector3d(0.01, 0.02, -0.03));
  h.input<LinkPoses>("links").poses = poses;
  h.step();
  const auto& skin = h.output<SkinTaxels>("skin.taxels");
  const auto& pose = poses[static_cast<std::size_t>(forearm)];
  for (std::size_t k = 0; k < skin.parts[0].positions.size(); ++k)
    ASSERT_TRUE(skin.parts[0].positions[k].isApprox(pose * skin.parts[0].positions_link[k], 1e-12));

  const auto layout = forearm_layout();
  const Eigen::Vector3d p = layout.positions[layout.virtual_taxels[5].centre];
  auto& contacts = h.input<Contacts>("contacts").points;
  const auto& pressures = h.output<TaxelValues>("skin.pressures");
  const auto peak = [&] {
    return *std::max_element(pressures.values.begin(), pressures.values.end());
  };
  for (int round = 0; round < 2; ++round) {
    contacts = {forearm_contact(p, 1.0)};
    h.step();
    EXPECT_GT(pressures.values[5], 0.01) << round;
    contacts.clear();
    h.step();
    EXPECT_EQ(peak(), 0.0) << round;
    h.step(2);
    EXPECT_EQ(peak(), 0.0) << round;
  }
}
