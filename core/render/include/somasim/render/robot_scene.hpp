#pragma once
/// @file
/// The scene of a robot and its world for the SceneRenderer: one uploaded mesh per link
/// geometry (the link's visual geometry, or its collision geometry when it has no visual one)
/// and per object shape, posed every frame from link poses and object states.
///
/// Ids in the id mask: link i -> link_id(i) = i + 1; object k of ObjectStates ->
/// object_id(k) = 1000 + k; 0 = background. Ids >= kFirstSceneExtraId are free for callers
/// (e.g. a backdrop); ids up to 65535 survive the 16-bit PNG of a recorded mask.
///
/// Cameras: the robot model's camera frame (robot_model.hpp: z optical axis, x image-right,
/// y image-down) is the render camera frame (camera.hpp: x right, y down, z forward), so
/// camera_for() poses the render camera at root <- link * camera.pose with no extra rotation.
///
/// Threads: a RobotScene uploads into a SceneRenderer and lives on its context's thread.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "somasim/render/camera.hpp"
#include "somasim/render/scene_renderer.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::render {

inline std::int32_t link_id(int link) {
  return static_cast<std::int32_t>(link) + 1;
}
inline std::int32_t object_id(std::size_t object) {
  return 1000 + static_cast<std::int32_t>(object);
}
inline constexpr std::int32_t kFirstSceneExtraId = 60000;

/// Albedo (R, G, B in [0, 1]) of a link, from its name: hands and fingers skin-coloured, eyes
/// dark, head white, arms light grey, torso darker grey. A visual shape with a `colour`
/// (robot::Geometry::colour, e.g. the iCub's green fingertip marker) is drawn with that instead.
Eigen::Vector3f link_colour(const std::string& link_name);

/// Mesh of a robot::Geometry in its own frame: primitives through tessellate() with
/// `segments`, mesh files through robot::load_triangle_mesh (flat normals). Throws
/// somasim::InputError when a mesh file cannot be read ("mesh file 'F': why").
TriangleMesh geometry_mesh(const robot::Geometry& geometry, int segments);

/// Which shapes of a link make its mesh.
enum class LinkShapes {
  kVisual,     ///< as RobotScene draws it: the visual geometry, else the collision geometry
  kCollision,  ///< the collision primitives: a low-poly proxy with a small `segments`
};

/// All shapes of the link `link_name` merged into one mesh in the link frame (each shape's
/// origin applied), e.g. a hypothesis-batch mesh posed by the link's pose (root <- link).
/// Throws somasim::InputError "robot 'R': unknown link 'X' (did you mean 'Y'?)" for an unknown
/// name, "robot 'R', link 'X': no visual or collision geometry" (or "no collision geometry")
/// when there is nothing to mesh, and as RobotScene for a mesh file that does not load.
TriangleMesh link_mesh(const robot::RobotModel& model, const std::string& link_name, int segments,
                       LinkShapes shapes = LinkShapes::kVisual);

struct RobotSceneOptions {
  int segments = 24;  ///< tessellation of curved primitives (>= 3)
};

class RobotScene {
 public:
  /// Uploads one mesh per link geometry into `renderer`. Throws somasim::InputError for
  /// segments < 3 and for a mesh file that cannot be loaded, naming the robot, the link, the
  /// shape, the file and assimp's reason: "robot 'R', link 'L', visual shape 0: mesh file 'F':
  /// cannot be read (<assimp's message>)" (or "...: holds no triangles").
  RobotScene(SceneRenderer& renderer, std::shared_ptr<const robot::RobotModel> model,
             const RobotSceneOptions& options = {});

  /// Appends the robot's draw items posed by `link_poses` (root <- link, one per link of the
  /// model). With a `viewpoint_root` (a camera's optical centre [m], root frame), shapes whose
  /// bounding box contains it are left out: an eye sits inside the head's collision sphere and
  /// would otherwise see only the inside of it. Throws somasim::RunError "link poses: expected
  /// N, got M" on a size mismatch.
  void add_robot(const std::vector<Eigen::Isometry3d>& link_poses, std::vector<DrawItem>& items,
                 const Eigen::Vector3d* viewpoint_root = nullptr) const;
  /// Appends one item per present object (spheres red, boxes blue, cylinders green, meshes
  /// grey); an object shape seen for the first time is tessellated and uploaded.
  void add_objects(const ObjectStates& objects, std::vector<DrawItem>& items);

  const robot::RobotModel& model() const { return *model_; }
  std::size_t triangle_count() const { return triangles_; }  ///< of the robot's meshes

 private:
  struct LinkPart {
    int link = 0;
    MeshHandle mesh;
    Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  ///< link <- geometry
    Bounds bounds;                                             ///< in the geometry frame
    Eigen::Vector3f colour;  ///< the shape's colour, else its link's (link_colour)
  };
  SceneRenderer* renderer_;
  std::shared_ptr<const robot::RobotModel> model_;
  RobotSceneOptions options_;
  std::vector<LinkPart> parts_;
  std::map<std::string, MeshHandle> object_meshes_;  // by shape and size
  std::size_t triangles_ = 0;
};

/// The render camera of the model's camera `camera_name` posed by `link_poses` (root <- link).
/// Throws somasim::InputError "camera 'X' is not in robot 'R' (cameras: a, b)" for an unknown
/// name and RunError "link poses: expected N, got M" on a size mismatch.
Camera camera_for(const robot::RobotModel& model, const std::string& camera_name,
                  const std::vector<Eigen::Isometry3d>& link_poses);

}  // namespace somasim::render
