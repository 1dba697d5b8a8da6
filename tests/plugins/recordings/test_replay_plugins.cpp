// The replay plugins through the harness: messages arrive at their recorded times, encoders
// drive joints (interpolated), skin contacts become events on mapped parts (modules through a
// layout), images arrive in order; bad logs and parameters are refused naming node and key.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "somasim/render/ports.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/skin/ports.hpp"
#include "somasim/testing/harness.hpp"

using somasim::testing::Harness;
namespace fs = std::filesystem;

namespace {

class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    dir_ = fs::temp_directory_path() /
           ("somasim_replay_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::create_directories(dir_);
  }
  ~TempDir() { fs::remove_all(dir_); }
  fs::path write_log(const std::string& name, const std::string& type, const std::string& data) {
    fs::create_directories(dir_ / name);
    std::ofstream(dir_ / name / "info.log") << "Type: " << type << ";\n";
    std::ofstream(dir_ / name / "data.log") << data;
    return dir_ / name / "data.log";
  }
  const fs::path& path() const { return dir_; }

 private:
  fs::path dir_;
};

std::string robot_line() {
  return std::string("robots: {icub: ") + SOMASIM_SOURCE_DIR + "/assets/robots/icub_v1.yaml}\n";
}

std::string error_of(const std::string& yaml) {
  try {
    Harness h(yaml);
  } catch (const somasim::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(YarpEncoderReplay, DrivesJointsAtTheRecordedTimes) {
  TempDir dir;
  // Stamps 1000.0, 1000.1, 1000.3 (replayed from t = 0.5 s): elbow 10, 20, 40 deg.
  const fs::path log = dir.write_log("arm", "Bottle",
                                     "1 1000.0 -30 30 0 10 0 0 0\n"
                                     "2 1000.1 -30 30 0 20 0 0 0\n"
                                     "3 1000.3 -30 30 0 40 0 0 0\n");
  Harness h(robot_line() +
            "duration_s: 2\nbase_rate_hz: 100\nnodes:\n  arm:\n"
            "    plugin: yarp_encoder_replay\n    params:\n      log: " +
            log.string() +
            "\n      offset_s: 0.5\n      joints: [l_shoulder_pitch, l_shoulder_roll, "
            "l_shoulder_yaw, l_elbow, '-', '-', '-']\n");
  const auto& state = h.output<somasim::JointState>("arm.state");
  const auto& command = h.output<somasim::JointCommand>("arm.command");
  h.step(1);  // t = 0: before the first message, its values
  // Find the elbow's dof from the command: the one mapped joint commanded at 10 deg.
  int elbow_dof = -1;
  for (int d = 0; d < command.position.size(); ++d)
    if (command.mode[static_cast<std::size_t>(d)] == somasim::JointCommandMode::kPosition &&
        std::abs(command.position[d] * 180.0 / M_PI - 10.0) < 1e-9)
      elbow_dof = d;
  ASSERT_GE(elbow_dof, 0);
  int mapped = 0;
  for (auto m : command.mode) mapped += m == somasim::JointCommandMode::kPosition;
  EXPECT_EQ(mapped, 4);
  h.step(55);  // t = 0.55: halfway between the first two messages
  EXPECT_NEAR(state.position[elbow_dof] * 180.0 / M_PI, 15.0, 1e-6);
  EXPECT_NEAR(state.velocity[elbow_dof] * 180.0 / M_PI, 100.0, 1e-6);  // 10 deg in 0.1 s
  h.step(15);  // t = 0.70: between the second and third
  EXPECT_NEAR(state.position[elbow_dof] * 180.0 / M_PI, 30.0, 1e-6);
  h.step(50);  // after the last: held
  EXPECT_NEAR(state.position[elbow_dof] * 180.0 / M_PI, 40.0, 1e-6);
  EXPECT_NEAR(state.velocity[elbow_dof], 0.0, 1e-12);
  h.finish();
  EXPECT_EQ(h.metric("arm", "messages"), 3);
  EXPECT_EQ(h.metric("arm", "delivered"), 3);
}

TEST(YarpEncoderReplay, RefusesBadLogsAndMappings) {
  TempDir dir;
  const auto yaml = [&](const fs::path& log, const std::string& joints) {
    return robot_line() +
           "duration_s: 1\nnodes:\n  arm: {plugin: yarp_encoder_replay, params: "
           "{log: " +
           log.string() + ", joints: " + joints + "}}\n";
  };
  const fs::path short_log = dir.write_log("short", "Bottle", "1 5.0 1 2\n");
  EXPECT_NE(error_of(yaml(short_log, "[l_elbow, '-', l_wrist_pitch]"))
                .find("node 'arm', key 'params.log': " + short_log.string() +
                      ":1:7: expected at least 3 values (one per entry of 'joints'), got 2"),
            std::string::npos)
      << error_of(yaml(short_log, "[l_elbow, '-', l_wrist_pitch]"));
  const fs::path text_log = dir.write_log("text", "Bottle", "1 5.0 1 two\n");
  EXPECT_NE(
      error_of(yaml(text_log, "[l_elbow, l_wrist_pitch]"))
          .find(text_log.string() +
                ":1:9: value 2 (joint 'l_wrist_pitch') must be a finite number, got a string"),
      std::string::npos)
      << error_of(yaml(text_log, "[l_elbow, l_wrist_pitch]"));
  const fs::path ok = dir.write_log("ok", "Bottle", "1 5.0 1 2\n");
  EXPECT_NE(error_of(yaml(ok, "[l_elbow, l_elbo]")).find("key 'params.joints'"), std::string::npos);
  EXPECT_NE(error_of(yaml(ok, "[l_elbow, l_elbow]")).find("joint 'l_elbow' is listed twice"),
            std::string::npos);
  const fs::path images = dir.write_log("images", "Image", "1 5.0 a.ppm\n");
  std::ofstream(dir.path() / "images" / "a.ppm") << "P6\n1 1\n255\nabc";
  EXPECT_NE(error_of(yaml(images, "[l_elbow]"))
                .find(": the log holds images (info.log: 'Type: Image'); this node replays "
                      "Bottles"),
            std::string::npos)
      << error_of(yaml(images, "[l_elbow]"));
}

TEST(YarpSkinReplay, ContactsBecomeEventsOnMappedParts) {
  TempDir dir;
  const std::string contact =
      "((7 3 4 2) (0.01 0.02 0.03) (0 0 -1) (0 0 0) (0.01 0.02 0.03) (0 0 2) (0 1 5) 30)";
  const std::string palm = "((8 4 6 4) (0.0 0.0 0.0) (0 0 0) (0 0 0) (0 0 0) (0 0 0) (4) 30)";
  // 50 Hz; the forearm touched on lines 2-4 (one episode) and again on line 9 (a new one); a
  // one-taxel palm contact (dropped by min_taxels) on line 3.
  std::string data;
  for (int i = 0; i < 10; ++i) {
    data += std::to_string(i) + " " + std::to_string(50.0 + 0.02 * i) + " ";
    if ((i >= 1 && i <= 3) || i == 8) data += contact;
    if (i == 2) data += " " + palm;
    data += "\n";
  }
  const fs::path log = dir.write_log("skin", "Bottle", data);
  std::ofstream(dir.path() / "layout.txt") << "0 0 0 0 0 0 1 100\n1 0.01 0 0 0 0 1 100\n"
                                              "5 0.02 0 0 0 0 1 200\n";
  Harness h(
      "duration_s: 1\nbase_rate_hz: 100\nnodes:\n  skin:\n    plugin: yarp_skin_replay\n"
      "    params:\n      log: " +
      log.string() +
      "\n      parts: [left_forearm=forearm, 4=palm]\n      min_taxels: 2\n"
      "      new_event_after_s: 0.05\n      layout_files: [forearm=" +
      (dir.path() / "layout.txt").string() + "]\n");
  const auto& events = h.output<somasim::ContactEvents>("skin.events");
  h.step(2);  // t = 0.01: line 1 is due (t = 0.0), nothing touched
  EXPECT_TRUE(events.recent.empty());
  h.step(2);  // t = 0.03: line 2 (t = 0.02) starts an episode
  ASSERT_EQ(events.recent.size(), 1u);
  const somasim::ContactEvent& e = events.recent[0];
  EXPECT_EQ(e.body_part, "forearm");
  EXPECT_NEAR(e.time_s, 0.02, 1e-9);
  EXPECT_EQ(e.touched_taxels, (std::vector<int>{100, 200}));  // taxels 0, 1, 5 -> modules
  EXPECT_NEAR(e.contact_point_link.y(), 0.02, 1e-12);
  EXPECT_NEAR(e.contact_normal_link.z(), 1.0, 1e-12);
  h.step(10);  // t = 0.13: lines 3-4 continue it
  EXPECT_EQ(events.recent.size(), 1u);
  h.step(5);  // t = 0.18: line 9 (t = 0.16), untouched since 0.06: a new event
  ASSERT_EQ(events.recent.size(), 2u);
  EXPECT_NEAR(events.recent[1].time_s, 0.16, 1e-9);
  h.finish();
  EXPECT_EQ(h.metric("skin", "parts")["forearm"]["contacts"], 4);
  EXPECT_EQ(h.metric("skin", "parts")["forearm"]["events"], 2);
  EXPECT_EQ(h.metric("skin", "small_contacts"), 1);
}

TEST(YarpSkinReplay, RefusesMalformedContactsAndMappings) {
  TempDir dir;
  const fs::path log = dir.write_log("skin", "Bottle", "1 5.0 ((1 2 3) (0 0 0))\n");
  const auto yaml = [&](const std::string& params) {
    return "duration_s: 1\nnodes:\n  skin: {plugin: yarp_skin_replay, params: {log: " +
           log.string() + params + "}}\n";
  };
  EXPECT_NE(error_of(yaml("")).find("node 'skin', key 'params.log': " + log.string() +
                                    ":1:7: skin contact 1: expected 8 fields, got 2"),
            std::string::npos)
      << error_of(yaml(""));
  EXPECT_NE(error_of(yaml(", parts: [left_elbow=x]"))
                .find("'left_elbow' is not an iCub skin part; expected one of: left_hand (1), "
                      "left_forearm (2),"),
            std::string::npos)
      << error_of(yaml(", parts: [left_elbow=x]"));
  EXPECT_NE(error_of(yaml(", parts: [2=x, left_forearm=y]"))
                .find("iCub skin part 'left_forearm' is mapped twice"),
            std::string::npos);
  EXPECT_NE(error_of(yaml(", parts: [2=x], layout_files: [y=z.txt]"))
                .find("body part 'y' is not among the replayed parts (see 'parts')"),
            std::string::npos);
}

TEST(YarpImageReplay, ImagesArriveInOrder) {
  TempDir dir;
  std::string data;
  for (int i = 0; i < 4; ++i) {
    const std::string name = "0000000" + std::to_string(i) + ".ppm";
    data += std::to_string(i) + " " + std::to_string(7.0 + 0.01 * i) + " " + name + " [rgb]\n";
  }
  fs::create_directories(dir.path() / "cam");
  for (int i = 0; i < 4; ++i)
    cv::imwrite((dir.path() / "cam" / ("0000000" + std::to_string(i) + ".ppm")).string(),
                cv::Mat(6, 8, CV_8UC3, cv::Scalar(10 * i, 20, 200)));  // B G R
  const fs::path log = dir.write_log("cam", "Image:ppm", data);
  Harness h(
      "duration_s: 1\nbase_rate_hz: 20\nnodes:\n  cam: {plugin: yarp_image_replay, params: "
      "{log: " +
      log.string() + ", camera: left_eye}}\n");
  const auto& image = h.output<somasim::RgbImage>("cam.image");
  h.step(1);  // t = 0
  ASSERT_EQ(image.frame, 1u);
  EXPECT_EQ(image.data.cols, 8);
  EXPECT_EQ(image.camera, "left_eye");
  EXPECT_EQ(image.data.at<cv::Vec3b>(0, 0)[0], 200);  // R first
  h.step(1);  // t = 0.05: images 1, 2 and 3 due, the latest shown, two skipped
  EXPECT_EQ(image.frame, 2u);
  EXPECT_EQ(image.data.at<cv::Vec3b>(0, 0)[2], 30);  // B of image 3
  EXPECT_NEAR(image.time_s, 0.03, 1e-6);
  h.step(2);
  h.finish();
  EXPECT_EQ(h.metric("cam", "delivered"), 4);
  EXPECT_EQ(h.metric("cam", "skipped"), 2);
}
