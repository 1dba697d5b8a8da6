// The `spectator` plugin through the public harness: a third-person view whose taxels show
// their values, deterministic, and its bad-input errors.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <opencv2/core.hpp>

#include "render_worker.hpp"
#include "somasim/error.hpp"
#include "somasim/render/camera.hpp"
#include "somasim/render/ports.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/skin/ports.hpp"
#include "somasim/testing/harness.hpp"
#include "spectator.hpp"

using somasim::LinkPoses;
using somasim::RgbImage;
using somasim::SkinTaxels;
using somasim::TaxelValues;
using somasim::testing::Harness;

namespace {

const std::string kRobot = SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml";

std::string graph(const std::string& params = "") {
  return "base_rate_hz: 10\nrobots: {icub: " + kRobot +
         "}\nnodes:\n  view:\n    plugin: spectator\n    params: {" + params +
         "}\n    inputs: {link_poses: harness.links, taxels: harness.taxels, taxel_values: "
         "harness.values}\n";
}

// Two taxels in front of the robot, well apart, one at value 0 and one at 1.
void feed(Harness& h) {
  SkinTaxels& taxels = h.input<SkinTaxels>("taxels");
  somasim::SkinPart part;
  part.name = "test_part";
  part.taxel_ids = {3, 7};
  part.positions = {Eigen::Vector3d(-0.45, -0.15, 0.25), Eigen::Vector3d(-0.45, 0.15, 0.25)};
  part.normals = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()};
  taxels.parts = {part};
  TaxelValues& values = h.input<TaxelValues>("values");
  values.labels = {"test_part/3", "test_part/7"};
  values.values = {0.0, 1.0};
}

// The colour at the image of root-frame point p, as the spectator's camera sees it.
cv::Vec3b colour_at(const cv::Mat& rgb, const somasim::render::Camera& camera,
                    const Eigen::Vector3d& p) {
  const auto uv = camera.project(p);
  EXPECT_TRUE(uv.has_value());
  return rgb.at<cv::Vec3b>(static_cast<int>(std::lround((*uv)[1])),
                           static_cast<int>(std::lround((*uv)[0])));
}

}  // namespace

class SpectatorTaxels : public ::testing::TestWithParam<std::string> {};

// Default spheres and the coarsest ones (taxel_segments 4: octahedra).
TEST_P(SpectatorTaxels, DrawsTaxelsInTheColourOfTheirValuesAndIsDeterministic) {
  const std::string params =
      "position: [-0.9, 0, 0.3], look_at: [-0.45, 0, 0.25], fov_deg: 60, width: 320, height: "
      "240, taxel_radius: 0.02" +
      GetParam();
  auto render = [&] {
    Harness h(graph(params));
    feed(h);
    h.step(2);
    const auto& image = h.output<RgbImage>("view.rgb");
    EXPECT_EQ(image.encoding, somasim::ImageEncoding::kRgb8);
    EXPECT_EQ(image.frame, 2u);
    EXPECT_EQ(h.finish(), "");
    return image.data.clone();
  };
  const cv::Mat a = render(), b = render();
  ASSERT_EQ(a.cols, 320);
  ASSERT_EQ(a.rows, 240);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  // The same camera, built here from the same numbers: x right, y down, z forward.
  somasim::render::Camera camera;
  const Eigen::Vector3d eye(-0.9, 0, 0.3), target(-0.45, 0, 0.25);
  const Eigen::Vector3d z = (target - eye).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  camera.pose_root.linear() << x, z.cross(x), z;
  camera.pose_root.translation() = eye;
  camera.intrinsics = {
      320,  240, 0.5 * 320 / std::tan(M_PI / 6), 0.5 * 320 / std::tan(M_PI / 6), 159.5, 119.5,
      0.02, 50.0};
  // The spheres' centres: half a radius (0.01 m) out along the taxels' normals (+z).
  const cv::Vec3b cold = colour_at(a, camera, {-0.45, -0.15, 0.26});
  const cv::Vec3b hot = colour_at(a, camera, {-0.45, 0.15, 0.26});
  // Value 1: yellow (red and green high, blue low); value 0: dark grey-blue.
  EXPECT_GT(hot[0], 150) << hot;
  EXPECT_GT(hot[1], 120) << hot;
  EXPECT_LT(hot[2], 80) << hot;
  EXPECT_LT(cold[0], 110) << cold;
  EXPECT_LT(cold[1], 110) << cold;
}

INSTANTIATE_TEST_SUITE_P(Segments, SpectatorTaxels,
                         ::testing::Values(std::string(""), std::string(", taxel_segments: 4")));

TEST(Spectator, AsynchronousPublishesEachFrameOneStepLaterPixelForPixel) {
  const std::string params =
      "position: [-0.9, 0, 0.3], look_at: [-0.45, 0, 0.25], fov_deg: 60, width: 160, height: "
      "120, taxel_radius: 0.02";
  using Frame = std::tuple<std::uint64_t, double, cv::Mat>;
  auto frames = [&](bool asynchronous) {
    Harness h(graph(params + (asynchronous ? ", asynchronous: true" : "")));
    feed(h);
    std::vector<Frame> out;
    for (int k = 0; k < 5; ++k) {
      // The two taxels swap colours at every step, so that each frame differs from the last.
      h.input<TaxelValues>("values").values = {k % 2 == 0 ? 0.0 : 1.0, k % 2 == 0 ? 1.0 : 0.0};
      h.step(1);
      const auto& image = h.output<RgbImage>("view.rgb");
      out.emplace_back(image.frame, image.time_s, image.data.clone());
    }
    EXPECT_EQ(h.finish(), "");
    return out;
  };
  const std::vector<Frame> now = frames(false), later = frames(true);
  EXPECT_EQ(std::get<0>(later[0]), 0u);  // nothing published yet
  EXPECT_TRUE(std::get<2>(later[0]).empty());
  EXPECT_GT(cv::norm(std::get<2>(now[0]), std::get<2>(now[1]), cv::NORM_INF), 50.0);
  for (std::size_t k = 1; k < now.size(); ++k) {
    EXPECT_EQ(std::get<0>(later[k]), k);
    EXPECT_EQ(std::get<1>(later[k]), std::get<1>(now[k - 1])) << k;
    ASSERT_EQ(std::get<2>(later[k]).size(), std::get<2>(now[k - 1]).size());
    EXPECT_EQ(cv::norm(std::get<2>(later[k]), std::get<2>(now[k - 1]), cv::NORM_INF), 0.0) << k;
  }
}

// `resolution` tessellates the robot's curved primitives: a coarse robot differs from the
// default one along the outlines of its cylinders and spheres only.
TEST(Spectator, ResolutionTessellatesTheRobotsCurvedPrimitives) {
  auto render = [&](const std::string& resolution) {
    Harness h(graph("width: 320, height: 240" + resolution));
    feed(h);
    h.step(1);
    cv::Mat rgb = h.output<RgbImage>("view.rgb").data.clone();
    EXPECT_EQ(h.finish(), "");
    return rgb;
  };
  const cv::Mat fine = render(""), coarse = render(", resolution: 6"),
                same = render(", resolution: 24");
  EXPECT_EQ(cv::norm(fine, same, cv::NORM_INF), 0.0);  // 24 is the default
  int changed = 0, robot = 0;  // pixels that differ; pixels of the robot (not background)
  const cv::Vec3b background = fine.at<cv::Vec3b>(0, 0);
  for (int r = 0; r < fine.rows; ++r)
    for (int c = 0; c < fine.cols; ++c) {
      changed += fine.at<cv::Vec3b>(r, c) != coarse.at<cv::Vec3b>(r, c) ? 1 : 0;
      robot += fine.at<cv::Vec3b>(r, c) != background ? 1 : 0;
    }
  EXPECT_GT(changed, 50);
  EXPECT_LT(changed, robot / 2) << "changed " << changed << " of the robot's " << robot << " px";
}

TEST(RenderWorker, AJobsErrorReachesWaitOnceAndTheWorkerGoesOn) {
  somasim::plugins::RenderWorker worker(somasim::render::RenderBackend::kOsmesa);
  int ran = 0;
  worker.submit([&](somasim::render::RenderContext&) { ++ran; });
  worker.submit([](somasim::render::RenderContext&) { throw std::runtime_error("frame 2"); });
  worker.submit([&](somasim::render::RenderContext&) { ++ran; });  // dropped: after the failure
  try {
    worker.wait();
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "frame 2");
  }
  EXPECT_NO_THROW(worker.wait());
  std::string renderer;
  worker.submit([&](somasim::render::RenderContext& context) { renderer = context.renderer(); });
  worker.wait();
  EXPECT_EQ(ran, 1);
  EXPECT_FALSE(renderer.empty());
}

TEST(Spectator, TaxelColoursRunFromGreyThroughRedToYellow) {
  using somasim::plugins::Spectator;
  EXPECT_TRUE(Spectator::taxel_colour(0.0).isApprox(Eigen::Vector3f(0.25f, 0.25f, 0.3f)));
  EXPECT_TRUE(Spectator::taxel_colour(1.0).isApprox(Eigen::Vector3f(1.0f, 0.9f, 0.1f)));
  EXPECT_TRUE(Spectator::taxel_colour(7.0).isApprox(Spectator::taxel_colour(1.0)));
  EXPECT_TRUE(Spectator::taxel_colour(-1.0).isApprox(Spectator::taxel_colour(0.0)));
  EXPECT_TRUE(Spectator::taxel_colour(std::nan("")).isApprox(Eigen::Vector3f::Constant(0.5f)));
}

TEST(Spectator, AViewThatCannotBeMadeIsRefusedWhereItIsWritten) {
  auto error = [](const std::string& params) -> std::string {
    try {
      Harness h(graph(params));
    } catch (const somasim::InputError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(error("position: [0, 0, 1], look_at: [0, 0, 1]").find("is the viewpoint itself"),
            std::string::npos);
  EXPECT_NE(error("position: [0, 0, 1], look_at: [0, 0, 0]").find("straight above or below"),
            std::string::npos);
  EXPECT_NE(error("fov_deg: 200").find("'params.fov_deg'"), std::string::npos);
  EXPECT_NE(error("position: [0, 1]").find("'params.position'"), std::string::npos);
  EXPECT_NE(error("resolution: 2").find("'params.resolution'"), std::string::npos);
}
