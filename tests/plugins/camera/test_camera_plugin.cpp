// The `camera` plugin through the public harness: output sizes and encodings, determinism,
// recording and saving PNGs, the EGL back end, and its bad-input errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>

#include <opencv2/imgcodecs.hpp>

#include "somasim/error.hpp"
#include "somasim/render/ports.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/testing/harness.hpp"
#include "somasim/units.hpp"

using somasim::DepthImage;
using somasim::Image;
using somasim::ImageEncoding;
using somasim::LabelImage;
using somasim::LinkPoses;
using somasim::RgbImage;
using somasim::testing::Harness;
namespace fs = std::filesystem;

namespace {

// The image on a camera output port, whichever of the three image types the port has.
const Image& camera_image(Harness& h, const std::string& port) {
  if (port.ends_with("_rgb")) return h.output<RgbImage>(port);
  if (port.ends_with("_depth")) return h.output<DepthImage>(port);
  return h.output<LabelImage>(port);
}

const std::string kRobot = SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml";

std::string graph(const std::string& params = "", const std::string& extra = "", int seed = 1) {
  return "seed: " + std::to_string(seed) + "\nbase_rate_hz: 10\nrobots: {icub: " + kRobot +
         "}\nnodes:\n  cam:\n    plugin: camera\n    params: {" + params +
         "}\n    inputs: {link_poses: harness.links}\n" + extra;
}

const somasim::robot::RobotModel& model() {
  static const auto m = somasim::robot::load_robot_model_shared(kRobot);
  return *m;
}

// The right hand in front of the eyes.
std::vector<Eigen::Isometry3d> hand_before_eyes() {
  const std::map<std::string, double> posture = {
      {"r_shoulder_pitch", -90}, {"r_shoulder_roll", 5}, {"r_shoulder_yaw", 25}, {"r_elbow", 40}};
  somasim::robot::RobotData data(model());
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model().num_dofs());
  for (const auto& [joint, deg] : posture) q[model().dof_index(joint)] = somasim::deg_to_rad(deg);
  somasim::robot::forward_kinematics(model(), data, q);
  return data.link_poses;
}

std::string input_error(const std::string& yaml) {
  try {
    Harness h(yaml);
  } catch (const somasim::InputError& e) {
    return e.what();
  }
  return "no error";
}

bool same_bytes(const cv::Mat& a, const cv::Mat& b) {
  return a.type() == b.type() && a.size() == b.size() &&
         std::equal(a.datastart, a.dataend, b.datastart);
}

}  // namespace

TEST(CameraPlugin, OutputsHaveTheCamerasSizeAndEncodings) {
  Harness h(graph());
  h.input<LinkPoses>("links").poses = hand_before_eyes();
  h.step();
  const int hand_id = somasim::render::link_id(model().link_index("r_hand"));
  for (const std::string eye : {"left_eye", "right_eye"}) {
    const auto& rgb = h.output<RgbImage>("cam." + eye + "_rgb");
    const auto& depth = h.output<DepthImage>("cam." + eye + "_depth");
    const auto& mask = h.output<LabelImage>("cam." + eye + "_mask");
    EXPECT_EQ(rgb.encoding, ImageEncoding::kRgb8);
    EXPECT_EQ(rgb.data.type(), CV_8UC3);
    EXPECT_EQ(depth.encoding, ImageEncoding::kDepth32f);
    EXPECT_EQ(depth.data.type(), CV_32F);
    EXPECT_EQ(mask.encoding, ImageEncoding::kId32s);
    EXPECT_EQ(mask.data.type(), CV_32S);
    for (const Image* i : std::initializer_list<const Image*>{&rgb, &depth, &mask}) {
      EXPECT_EQ(i->data.cols, 320);
      EXPECT_EQ(i->data.rows, 240);
      EXPECT_EQ(i->camera, eye);
      EXPECT_EQ(i->frame, 1u);
    }
    EXPECT_GT(cv::countNonZero(mask.data == hand_id), 1000) << eye;
    // Depth where the hand is: a few decimetres away.
    double lo = 0, hi = 0;
    cv::minMaxLoc(depth.data, &lo, &hi, nullptr, nullptr, mask.data == hand_id);
    EXPECT_GT(lo, 0.1);
    EXPECT_LT(hi, 0.5);
  }
  h.finish();
  EXPECT_EQ(h.metric("cam", "frames"), 1);
}

TEST(CameraPlugin, OnlyTheRequestedOutputs) {
  Harness h(graph("outputs: rgb, cameras: right_eye"));
  h.input<LinkPoses>("links").poses = hand_before_eyes();
  h.step();
  EXPECT_EQ(h.output<RgbImage>("cam.left_eye_rgb").camera, "right_eye");
  EXPECT_TRUE(h.output<DepthImage>("cam.left_eye_depth").data.empty());
  EXPECT_TRUE(h.output<RgbImage>("cam.right_eye_rgb").data.empty());
}

TEST(CameraPlugin, SameSeedGivesIdenticalImages) {
  auto render = [](int seed) {
    Harness h(graph("background: textured", "", seed));
    h.input<LinkPoses>("links").poses = hand_before_eyes();
    h.step(2);
    std::vector<cv::Mat> out;
    for (const char* port :
         {"cam.left_eye_rgb", "cam.right_eye_rgb", "cam.left_eye_depth", "cam.right_eye_mask"})
      out.push_back(camera_image(h, port).data.clone());
    return out;
  };
  const auto a = render(1), b = render(1), c = render(2);
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_TRUE(same_bytes(a[k], b[k])) << k;
  EXPECT_FALSE(same_bytes(a[0], c[0]));  // another seed, another backdrop
}

TEST(CameraPlugin, RecordingAndSaveEveryWritePngs) {
  Harness h(graph("save_every: 2",
                  "record: [cam.left_eye_rgb, cam.left_eye_depth, cam.right_eye_mask]\n"));
  h.input<LinkPoses>("links").poses = hand_before_eyes();
  h.step(3);
  const cv::Mat depth = h.output<DepthImage>("cam.left_eye_depth").data.clone();
  const cv::Mat mask = h.output<LabelImage>("cam.right_eye_mask").data.clone();
  h.finish();
  const fs::path dir = h.out_dir();
  for (const char* f :
       {"cam.left_eye_rgb/000001.png", "cam.left_eye_rgb/000003.png",
        "cam.left_eye_depth/000002.png", "cam.right_eye_mask/000003.png",
        "frames/cam.left_eye_rgb/000001.png", "frames/cam.right_eye_depth/000003.png",
        "frames/cam.right_eye_mask/000001.png"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  EXPECT_FALSE(fs::exists(dir / "frames/cam.left_eye_rgb/000002.png"));
  EXPECT_FALSE(fs::exists(dir / "cam.left_eye_rgb.csv"));
  std::ifstream index(dir / "cam.left_eye_rgb/index.csv");
  std::string line, all;
  while (std::getline(index, line)) all += line + "\n";
  EXPECT_EQ(all, "time [s],frame,file\n0,1,000001.png\n0.1,2,000002.png\n0.2,3,000003.png\n");
  // Depth PNG: 16-bit millimetres; mask PNG: 16-bit ids.
  const cv::Mat depth_png =
      cv::imread((dir / "cam.left_eye_depth/000003.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(depth_png.type(), CV_16U);
  cv::Mat mm;
  depth.convertTo(mm, CV_64F, 1000.0);
  cv::Mat png_mm;
  depth_png.convertTo(png_mm, CV_64F);
  EXPECT_LE(cv::norm(png_mm, mm, cv::NORM_INF), 0.5);  // rounded to whole millimetres
  EXPECT_GT(cv::countNonZero(depth_png), 1000);
  const cv::Mat mask_png =
      cv::imread((dir / "cam.right_eye_mask/000003.png").string(), cv::IMREAD_UNCHANGED);
  cv::Mat ids;
  mask.convertTo(ids, CV_16U);
  EXPECT_TRUE(same_bytes(mask_png, ids));
}

TEST(CameraPlugin, SavedFramesHaveAnIndexOfTheirTimes) {
  Harness h(graph("save_every: 2"));
  h.input<LinkPoses>("links").poses = hand_before_eyes();
  h.step(5);
  h.finish();
  std::ifstream index(h.out_dir() / "frames/cam.left_eye_rgb/index.csv");
  std::string line, all;
  while (std::getline(index, line)) all += line + "\n";
  EXPECT_EQ(all, "time [s],frame,file\n0,1,000001.png\n0.2,3,000003.png\n0.4,5,000005.png\n");
}

// `as: video`: one MP4 per port, every frame, the same bytes for the same frames; any image
// encoding (depth as grey).
TEST(CameraPlugin, RecordingAsVideoWritesOneDeterministicMp4PerPort) {
  auto record = [](const std::string& tag) {
    Harness h(graph("",
                    "record: [{port: cam.left_eye_rgb, as: video}, "
                    "{port: cam.left_eye_depth, as: video}, cam.right_eye_rgb]\n"));
    h.input<LinkPoses>("links").poses = hand_before_eyes();
    h.step(6);
    EXPECT_EQ(h.finish(), "");
    const fs::path dir = h.out_dir();
    EXPECT_FALSE(fs::exists(dir / "cam.left_eye_rgb"));  // no PNG folder for a video port
    EXPECT_TRUE(fs::exists(dir / "cam.right_eye_rgb/000006.png"));
    std::vector<std::string> bytes;
    for (const char* f : {"cam.left_eye_rgb.mp4", "cam.left_eye_depth.mp4"}) {
      std::ifstream in(dir / f, std::ios::binary);
      bytes.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      EXPECT_GT(bytes.back().size(), 1000u) << f << " " << tag;
      // MP4: an 'ftyp' box first.
      EXPECT_EQ(bytes.back().substr(4, 4), "ftyp") << f;
    }
    return bytes;
  };
  EXPECT_EQ(record("a"), record("b"));
}

TEST(CameraPlugin, UnknownCameraIsAClearError) {
  EXPECT_EQ(input_error(graph("cameras: 'left_eye, nose'")),
            "<inline>:7:23: node 'cam', key 'params.cameras': camera 'nose' is not in robot "
            "'icub_v1' (cameras: left_eye, right_eye)");
}

TEST(CameraPlugin, BadBackgroundIsAClearError) {
  EXPECT_EQ(input_error(graph("background: '0.2 0.3'")),
            "<inline>:7:26: node 'cam', key 'params.background': expected 'R G B' (three "
            "numbers in [0, 1]), black, white, grey, blue or textured, got '0.2 0.3'");
}

TEST(CameraPlugin, UnknownOutputIsAClearError) {
  EXPECT_EQ(input_error(graph("outputs: 'rgb, edges'")),
            "<inline>:7:23: node 'cam', key 'params.outputs': expected a list of words: one of "
            "rgb, depth, mask, got an element 'edges'");
}

// The EGL back end (surfaceless, llvmpipe here) renders the same images as OSMesa. Failing to
// create the EGL context fails this test with the EGL error: CI machines have Mesa's EGL.
TEST(CameraPlugin, EglBackendRendersTheSameImagesAsOsmesa) {
  // Same rasteriser as OSMesa even on a node with a GPU (set before any EGL call).
  ASSERT_EQ(setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1), 0);
  auto render = [](const std::string& backend) {
    Harness h(graph("background: textured, backend: " + backend));
    h.input<LinkPoses>("links").poses = hand_before_eyes();
    h.step();
    std::vector<cv::Mat> out;
    for (const char* port : {"cam.left_eye_rgb", "cam.right_eye_rgb", "cam.left_eye_depth",
                             "cam.right_eye_depth", "cam.left_eye_mask", "cam.right_eye_mask"})
      out.push_back(camera_image(h, port).data.clone());
    return out;
  };
  const auto osmesa = render("osmesa"), egl = render("egl");
  for (std::size_t k = 0; k < osmesa.size(); ++k) {
    EXPECT_TRUE(same_bytes(egl[k], osmesa[k])) << k;
    EXPECT_GT(cv::countNonZero(egl[k].reshape(1)), 1000) << k;
  }
}

TEST(CameraPlugin, UnknownBackendIsAClearError) {
  EXPECT_EQ(input_error(graph("backend: vulkan")),
            "<inline>:7:23: node 'cam', key 'params.backend': expected a string: one of osmesa, "
            "egl, got 'vulkan'");
}

TEST(CameraPlugin, CameraNodesOfOneThreadMustShareTheBackend) {
  const std::string yaml = graph("backend: osmesa") +
                           "  cam2:\n    plugin: camera\n    params: {backend: egl}\n"
                           "    inputs: {link_poses: harness.links}\n";
  EXPECT_EQ(input_error(yaml),
            "<inline>:11:23: node 'cam2', key 'params.backend': 'egl', but another camera node on "
            "this thread already renders with 'osmesa' (one OpenGL context per thread: give the "
            "camera nodes of a thread the same backend)");
}
