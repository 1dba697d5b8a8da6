// The EGL back end against the OSMesa one: a core context on EGL's surfaceless platform, scenes
// and hypothesis batches identical pixel for pixel to OSMesa's, one context per thread across
// back ends, and the errors users can meet (back-end names, EGL failures).
//
// EGL contexts that cannot be created fail these tests with the EGL error (no skipping): CI
// machines have Mesa's EGL driver (libegl-mesa0, scripts/setup.sh).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>
#include <thread>

#include "somasim/error.hpp"
#include "somasim/render/context.hpp"
#include "somasim/render/egl_context.hpp"
#include "somasim/render/hypothesis_batch.hpp"
#include "somasim/render/scene_renderer.hpp"

using namespace somasim;
using namespace somasim::render;

namespace {

// Pixel equality with OSMesa needs the same rasteriser: on a node with a GPU, Mesa's EGL would
// pick the GPU's driver; LIBGL_ALWAYS_SOFTWARE makes it llvmpipe. Set before any EGL call.
const bool kSoftwareEgl = setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1) == 0;

template <typename E>
std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "no error";
}

bool same_bytes(const cv::Mat& a, const cv::Mat& b) {
  return a.type() == b.type() && a.size() == b.size() && a.isContinuous() && b.isContinuous() &&
         std::equal(a.datastart, a.dataend, b.datastart);
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// 320 x 240 camera at `position` [m] looking along root +x (root z up), turned by `yaw` [rad]
// about root z.
Camera camera_at(const std::string& name, const Eigen::Vector3d& position, double yaw) {
  Camera c;
  c.name = name;
  c.intrinsics = {320, 240, 257.34, 257.34, 160.0, 120.0, 0.02, 5.0};
  Eigen::Matrix3d r;
  r.col(0) = -Eigen::Vector3d::UnitY();
  r.col(1) = -Eigen::Vector3d::UnitZ();
  r.col(2) = Eigen::Vector3d::UnitX();
  c.pose_root.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * r;
  c.pose_root.translation() = position;
  return c;
}

Eigen::Isometry3d pose(double x, double y, double z, double angle, const Eigen::Vector3d& axis) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.translation() = Eigen::Vector3d(x, y, z);
  p.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  return p;
}

// A sphere, a tilted box and a cylinder that partly hide each other, lit from the side; all
// three outputs read back.
RenderedImages render_scene(const RenderContext& context) {
  SceneRenderer renderer(context.gl());
  const MeshHandle sphere = renderer.upload(tessellate_sphere(0.08, 48));
  const MeshHandle box = renderer.upload(tessellate_box(Eigen::Vector3d(0.2, 0.1, 0.15)));
  const MeshHandle cylinder = renderer.upload(tessellate_cylinder(0.04, 0.3, 32));
  const std::vector<DrawItem> items = {
      {sphere, pose(0.6, 0.05, 0.02, 0.0, Eigen::Vector3d::UnitZ()), {0.9f, 0.2f, 0.1f}, 1},
      {box, pose(0.8, -0.05, -0.03, 0.7, Eigen::Vector3d(1, 2, 3)), {0.2f, 0.3f, 0.9f}, 2},
      {cylinder, pose(0.7, 0.12, 0.0, 1.1, Eigen::Vector3d(1, 0, 1)), {0.3f, 0.8f, 0.3f}, 3}};
  RenderOptions options;
  options.background = {0.35f, 0.45f, 0.55f};
  options.light_direction_root = {0.3, -1.0, 0.8};
  return renderer.render(items, camera_at("probe", Eigen::Vector3d::Zero(), 0.05), options);
}

// Forearm + hand proxy (cylinder, palm box, thumb box) and N hypotheses of it that vary with k.
std::vector<TriangleMesh> arm_meshes() {
  return {tessellate_cylinder(0.025, 0.16, 16), tessellate_box(Eigen::Vector3d(0.07, 0.025, 0.08)),
          tessellate_box(Eigen::Vector3d(0.015, 0.015, 0.04))};
}

HypothesisBatch arm_batch(int n) {
  HypothesisBatch batch;
  batch.meshes = {0, 1, 2};
  for (int k = 0; k < n; ++k) {
    const double a = 0.37 * k, b = 0.23 * k;
    Eigen::Isometry3d forearm =
        pose(0.45 + 0.01 * std::sin(a), 0.03 * std::cos(b), 0.02 * std::sin(a + b),
             0.6 + 0.2 * std::sin(b), Eigen::Vector3d(0.3 * std::cos(a), 1.0, 0.0));
    Eigen::Isometry3d hand = forearm;
    hand.translate(Eigen::Vector3d(0.0, 0.0, 0.12));
    hand.rotate(Eigen::AngleAxisd(0.5 * std::sin(a), Eigen::Vector3d::UnitX()));
    Eigen::Isometry3d thumb = hand;
    thumb.translate(Eigen::Vector3d(0.04, 0.0, 0.0));
    batch.hypotheses.push_back({forearm, hand, thumb});
  }
  batch.cameras = {camera_at("left_eye", Eigen::Vector3d(0.0, 0.034, 0.0), 0.05),
                   camera_at("right_eye", Eigen::Vector3d(0.0, -0.034, 0.0), -0.05)};
  return batch;
}

void expect_same_batches(const HypothesisBatchResult& egl, const HypothesisBatchResult& osmesa) {
  ASSERT_EQ(egl.cameras.size(), osmesa.cameras.size());
  for (std::size_t c = 0; c < egl.cameras.size(); ++c) {
    EXPECT_EQ(egl.cameras[c].roi, osmesa.cameras[c].roi) << "camera " << c;
    ASSERT_EQ(egl.cameras[c].tiles.size(), osmesa.cameras[c].tiles.size());
    for (std::size_t h = 0; h < egl.cameras[c].tiles.size(); ++h) {
      EXPECT_TRUE(same_bytes(egl.cameras[c].tiles[h], osmesa.cameras[c].tiles[h]))
          << "camera " << c << " hypothesis " << h;
      EXPECT_GT(cv::countNonZero(egl.cameras[c].tiles[h]), 20) << "camera " << c << " " << h;
    }
  }
}

}  // namespace

TEST(EglContext, GivesACoreProfileOfAtLeast33OnLlvmpipe) {
  ASSERT_TRUE(kSoftwareEgl);
  EglContext context;
  std::cout << "EGL renderer: " << context.renderer() << "\nEGL version: " << context.version()
            << "\n";
  EXPECT_EQ(context.backend(), RenderBackend::kEgl);
  EXPECT_TRUE(contains(context.version(), "Core Profile")) << context.version();
  EXPECT_TRUE(contains(context.renderer(), "llvmpipe")) << context.renderer();
  GLint major = 0, minor = 0;
  context.gl().GetIntegerv(GL_MAJOR_VERSION, &major);
  context.gl().GetIntegerv(GL_MINOR_VERSION, &minor);
  EXPECT_GE(major * 10 + minor, 33);
  GLint profile = 0;
  context.gl().GetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_EQ(profile & GL_CONTEXT_CORE_PROFILE_BIT, GL_CONTEXT_CORE_PROFILE_BIT);
  EXPECT_NO_THROW(check_gl(context.gl(), "querying the version"));
}

TEST(EglContext, MakeRenderContextGivesTheRequestedBackend) {
  for (const RenderBackend backend : {RenderBackend::kOsmesa, RenderBackend::kEgl}) {
    const std::unique_ptr<RenderContext> context = make_render_context(backend);
    EXPECT_EQ(context->backend(), backend);
    EXPECT_TRUE(contains(context->version(), "Core Profile")) << context->version();
  }
}

TEST(EglContext, SceneEqualsTheOsmesaRenderPixelForPixel) {
  RenderedImages osmesa, egl;
  {
    OsmesaContext context;
    osmesa = render_scene(context);
  }
  {
    EglContext context;
    egl = render_scene(context);
  }
  EXPECT_TRUE(same_bytes(egl.rgb, osmesa.rgb));
  EXPECT_TRUE(same_bytes(egl.depth, osmesa.depth));
  EXPECT_TRUE(same_bytes(egl.ids, osmesa.ids));
  // The scene is not trivially empty: every item shows, and the depth covers them.
  for (int id = 1; id <= 3; ++id) EXPECT_GT(cv::countNonZero(egl.ids == id), 500) << id;
  EXPECT_EQ(cv::countNonZero(egl.depth > 0), cv::countNonZero(egl.ids > 0));
}

TEST(EglContext, HypothesisBatchEqualsTheOsmesaBatchByteForByte) {
  const std::vector<TriangleMesh> meshes = arm_meshes();
  const HypothesisBatch batch = arm_batch(40);
  HypothesisRenderer osmesa(meshes, 2, RenderBackend::kOsmesa);
  HypothesisRenderer egl(meshes, 2, RenderBackend::kEgl);
  EXPECT_EQ(osmesa.backend(), RenderBackend::kOsmesa);
  EXPECT_EQ(egl.backend(), RenderBackend::kEgl);
  expect_same_batches(egl.render(batch), osmesa.render(batch));
  HypothesisBatchOptions contour;
  contour.contour = true;
  contour.contour_width = 2;
  expect_same_batches(egl.render(batch, contour), osmesa.render(batch, contour));
}

TEST(EglContext, OneContextPerThreadWhateverTheBackend) {
  {
    EglContext context;
    EXPECT_EQ(error_of<RunError>([] { OsmesaContext second; }),
              "render: this thread already has an EGL context (one context per thread; create "
              "one context per rendering thread)");
    EXPECT_EQ(error_of<RunError>([] { EglContext second; }),
              "render: this thread already has an EGL context (one context per thread; create "
              "one context per rendering thread)");
    // Other threads may have their own EGL contexts at the same time (one shared display).
    std::string renderer_a, renderer_b;
    std::thread a([&] { renderer_a = EglContext().renderer(); });
    std::thread b([&] { renderer_b = EglContext().renderer(); });
    a.join();
    b.join();
    EXPECT_EQ(renderer_a, context.renderer());
    EXPECT_EQ(renderer_b, context.renderer());
  }
  {
    OsmesaContext context;
    EXPECT_EQ(error_of<RunError>([] { EglContext second; }),
              "render: this thread already has an OSMesa context (one context per thread; "
              "create one context per rendering thread)");
  }
  // With every context gone, a new one is made on the same display.
  EglContext again;
  EXPECT_NO_THROW(check_gl(again.gl(), "a context after the display was terminated"));
}

TEST(EglContext, AnImpossibleVersionNamesTheEglCallAndError) {
  EXPECT_EQ(error_of<RunError>([] { EglContext context(9, 9); }),
            "render: eglCreateContext failed for an OpenGL 9.9 core-profile context: "
            "EGL_BAD_MATCH");
  // The failed attempt left the thread free.
  EXPECT_NO_THROW(EglContext context);
}

TEST(EglContext, ErrorCodesHaveTheirNames) {
  EXPECT_EQ(egl_error_name(0x3000), "EGL_SUCCESS");
  EXPECT_EQ(egl_error_name(0x3001), "EGL_NOT_INITIALIZED");
  EXPECT_EQ(egl_error_name(0x3009), "EGL_BAD_MATCH");
  EXPECT_EQ(egl_error_name(0x300E), "EGL_CONTEXT_LOST");
  EXPECT_EQ(egl_error_name(0x1234), "unknown EGL error 0x1234");
}

// The EGL display is chosen once per process: each SOMASIM_EGL_PLATFORM is tried in a fresh one
// (threadsafe death tests re-run this binary), which prints what it got and exits 0.
[[noreturn]] void report_platform_outcome(const char* platform) {
  setenv("SOMASIM_EGL_PLATFORM", platform, 1);
  try {
    EglContext context;
    const bool software =
        contains(context.renderer(), "llvmpipe") || contains(context.renderer(), "softpipe");
    std::cerr << (software ? "software renderer: " : "hardware renderer: ") << context.renderer()
              << "\n";
  } catch (const RunError& e) {
    std::cerr << "error: " << e.what() << "\n";
  }
  std::exit(0);
}

TEST(EglPlatform, AnUnknownChoiceIsAClearError) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(report_platform_outcome("gpu"), testing::ExitedWithCode(0),
              "error: render: SOMASIM_EGL_PLATFORM is 'gpu'; expected auto, device or "
              "surfaceless");
}

TEST(EglPlatform, SurfacelessIsMesaSoftwareWhenSoftwareIsAsked) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  ASSERT_TRUE(kSoftwareEgl);
  EXPECT_EXIT(report_platform_outcome("surfaceless"), testing::ExitedWithCode(0),
              "software renderer: llvmpipe");
}

TEST(EglPlatform, DeviceGivesAHardwareRendererOrSaysWhatItTried) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  // A machine with a GPU driver's EGL renders on it; one without says which devices it found.
  EXPECT_EXIT(report_platform_outcome("device"), testing::ExitedWithCode(0),
              "hardware renderer: |error: render: no EGL display renders without a window .device "
              "platform: ");
}

TEST(RenderBackend, NamesParseAndUnknownNamesAreClearErrors) {
  EXPECT_EQ(parse_render_backend("osmesa"), RenderBackend::kOsmesa);
  EXPECT_EQ(parse_render_backend("egl"), RenderBackend::kEgl);
  for (const std::string& name : render_backend_names())
    EXPECT_EQ(render_backend_name(parse_render_backend(name)), name);
  EXPECT_EQ(render_backend_names(), (std::vector<std::string>{"osmesa", "egl"}));
  EXPECT_EQ(error_of<InputError>([] { parse_render_backend("vulkan"); }),
            "unknown render backend 'vulkan'; expected 'osmesa' or 'egl'");
  EXPECT_EQ(error_of<InputError>([] { parse_render_backend("osmesa6"); }),
            "unknown render backend 'osmesa6'; expected 'osmesa' or 'egl' (did you mean "
            "'osmesa'?)");
  EXPECT_EQ(error_of<InputError>([] { parse_render_backend("elg"); }),
            "unknown render backend 'elg'; expected 'osmesa' or 'egl' (did you mean 'egl'?)");
  EXPECT_EQ(error_of<InputError>([] { parse_render_backend(""); }),
            "unknown render backend ''; expected 'osmesa' or 'egl'");
}
