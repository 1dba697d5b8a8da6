#pragma once
// camera: the robot's eyes. Renders the views of the robot model's cameras (default the iCub's
// left_eye and right_eye) from the world's link and object poses, with OSMesa or EGL. Only the
// images something reads are rendered and read back: an output port wired to another node or
// recorded, or what save_every and the contact sheet need; a view none of whose images is read
// is not rendered at all.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "contact_sheet.hpp"
#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/render/context.hpp"
#include "somasim/render/ports.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/render/scene_renderer.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::plugins {

class CameraPlugin : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    std::vector<std::string> cameras{"left_eye", "right_eye"};
    std::vector<std::string> outputs{"rgb", "depth", "mask"};
    std::string background = "0.35 0.45 0.55";
    int resolution = 24;
    render::RenderBackend backend = render::RenderBackend::kOsmesa;
    int save_every = 0;
    std::vector<double> sheet_times;
    template <class V>
    void visit(V& v);
  };
  struct Ports {
    In<LinkPoses> link_poses;
    OptionalIn<ObjectStates> objects;
    std::array<Out<RgbImage>, 2> rgb;  // per slot: left_eye_*, right_eye_*
    std::array<Out<DepthImage>, 2> depth;
    std::array<Out<LabelImage>, 2> mask;
    template <class V>
    void visit(V& v);
  };
  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;
  void finish(NodeContext& ctx) override;

  /// Port slots: the i-th camera of `cameras` feeds the ports `<slot>_rgb|depth|mask`.
  static constexpr std::array<const char*, 2> kSlots = {"left_eye", "right_eye"};
  /// What a view renders: the names in `outputs` and the ports' suffixes.
  static constexpr const char* kRgb = "rgb";
  static constexpr const char* kDepth = "depth";
  static constexpr const char* kMask = "mask";

 private:
  Config config_;
  Ports ports_;
  struct View {
    std::string camera;  // the model's camera name
    std::string slot;
    Image* rgb = nullptr;
    Image* depth = nullptr;
    Image* mask = nullptr;
    render::RenderOptions options;  // what this view reads back
    bool rendered = false;          // anything of this view is read
  };
  void parse_background(NodeContext& ctx);
  void choose_images(const NodeContext& ctx);
  void save_frames(NodeContext& ctx, const View& view);

  std::shared_ptr<const robot::RobotModel> model_;
  std::shared_ptr<render::RenderContext> context_;
  std::unique_ptr<render::SceneRenderer> renderer_;
  std::unique_ptr<render::RobotScene> scene_;
  std::vector<render::DrawItem> backdrop_;
  render::RenderOptions options_;
  bool want_rgb_ = false, want_depth_ = false, want_mask_ = false;
  std::uint64_t frame_ = 0;
  std::uint64_t views_rendered_ = 0;  // renders (one per view whose images are read, per frame)
  std::vector<View> views_;
  std::vector<SheetRow> sheet_;
  std::vector<render::DrawItem> items_;  // reused every frame

  const LinkPoses* link_poses_ = nullptr;
  const ObjectStates* objects_ = nullptr;
  std::vector<Eigen::Isometry3d> rest_poses_;  // link poses at q = 0
};

}  // namespace somasim::plugins
