#pragma once
// spectator: a third-person view of a run. Renders the robot, the world's objects and the skin's
// taxels (coloured by a per-taxel value such as the PPS activation) from a fixed viewpoint, for
// watching or recording a run (`record: [{port: NODE.rgb, as: video}]`). Positions are in the
// robot's root frame (iCub: x backward, y to the robot's right, z up) [m]. With `asynchronous`,
// it renders on a thread of its own while the simulation goes on and publishes each frame one
// spectator step later.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render_worker.hpp"
#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/render/context.hpp"
#include "somasim/render/ports.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/render/scene_renderer.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/skin/ports.hpp"

namespace somasim::plugins {

class Spectator : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    std::vector<double> position{-1.1, -0.45, 0.55};  // [m], root frame
    std::vector<double> look_at{-0.2, 0.0, 0.2};      // [m], root frame
    double fov_deg = 55.0;                            // horizontal field of view [deg]
    int width = 640;                                  // [px]
    int height = 480;                                 // [px]
    double taxel_radius = 0.004;                      // [m]
    int taxel_segments = 8;  // around each taxel's sphere (its triangles: segments² / 2)
    int resolution = 24;     // segments of the robot's curved primitives
    render::RenderBackend backend = render::RenderBackend::kOsmesa;
    bool asynchronous = false;
    template <class V>
    void visit(V& v);
  };
  struct Ports {
    In<LinkPoses> link_poses;
    OptionalIn<ObjectStates> objects;
    OptionalIn<SkinTaxels> taxels;
    OptionalIn<TaxelValues> taxel_values;
    Out<RgbImage> rgb;
    template <class V>
    void visit(V& v);
  };
  Spectator() = default;
  ~Spectator() override;
  Spectator(const Spectator&) = delete;
  Spectator& operator=(const Spectator&) = delete;
  Spectator(Spectator&&) = delete;
  Spectator& operator=(Spectator&&) = delete;

  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;
  void finish(NodeContext& ctx) override;

  /// The colour of a taxel of value `value` in [0, 1]: dark grey at 0 through red to yellow at 1
  /// (values outside are clamped; NaN is grey).
  static Eigen::Vector3f taxel_colour(double value);

 private:
  // What a frame shows, copied from the input ports.
  struct Inputs {
    std::vector<Eigen::Isometry3d> link_poses;
    std::optional<ObjectStates> objects;
    std::optional<SkinTaxels> taxels;
    std::optional<TaxelValues> taxel_values;
  };
  Inputs copy_inputs() const;
  void add_taxels(const SkinTaxels* taxels, const TaxelValues* values,
                  std::vector<render::DrawItem>& items) const;
  // The renderer, the robot's meshes and the taxel sphere, on `context`'s thread.
  void make_gl_objects(render::RenderContext& context);
  // The robot, objects and taxels as draw items (on the renderer's thread: new object shapes
  // upload meshes).
  std::vector<render::DrawItem> draw_items(const Inputs& in);
  void publish(cv::Mat rgb, double time_s, NodeContext& ctx);
  // Waits for the render thread, ends its GL objects there and the thread; throws a frame's
  // rendering error after that.
  void end_worker();

  Config config_;
  Ports ports_;
  std::shared_ptr<const robot::RobotModel> model_;
  std::shared_ptr<render::RenderContext> context_;
  std::unique_ptr<render::SceneRenderer> renderer_;
  std::unique_ptr<render::RobotScene> scene_;
  render::MeshHandle taxel_mesh_;
  render::Camera camera_;
  render::RenderOptions options_;
  std::vector<Eigen::Isometry3d> rest_poses_;
  std::uint64_t frame_ = 0;
  // asynchronous: the render thread and the frame it is rendering (or has rendered).
  std::unique_ptr<RenderWorker> worker_;
  cv::Mat pending_rgb_;
  double pending_time_s_ = 0.0;
  bool pending_ = false;
};

}  // namespace somasim::plugins
