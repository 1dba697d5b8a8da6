#include "somasim/render/robot_scene.hpp"

#include <fmt/format.h>

#include "somasim/error.hpp"
#include "somasim/robot/mesh_loader.hpp"

namespace somasim::render {
namespace {

bool has(const std::string& s, const char* word) {
  return s.find(word) != std::string::npos;
}

void check_pose_count(const robot::RobotModel& model, std::size_t got) {
  if (got != static_cast<std::size_t>(model.num_links()))
    throw RunError(fmt::format("link poses: expected {}, got {}", model.num_links(), got));
}

// Flat-shaded mesh (three vertices per triangle with the face normal) of a loaded mesh file.
TriangleMesh flat_mesh(const robot::TriangleMesh& loaded) {
  TriangleMesh m;
  m.positions.reserve(loaded.triangles.size() * 3);
  for (const auto& t : loaded.triangles) {
    const Eigen::Vector3d a = loaded.vertices[t[0]], b = loaded.vertices[t[1]],
                          c = loaded.vertices[t[2]];
    Eigen::Vector3d n = (b - a).cross(c - a);
    n = n.norm() > 0 ? n.normalized() : Eigen::Vector3d::UnitZ();
    for (const auto* p : {&a, &b, &c}) {
      m.indices.push_back(static_cast<std::uint32_t>(m.positions.size()));
      m.positions.push_back(p->cast<float>());
      m.normals.push_back(n.cast<float>());
    }
  }
  return m;
}

// The shapes a link is drawn with (kVisual) or its collision shapes, and their kind's name.
const std::vector<robot::Geometry>& shapes_of(const robot::Link& link, LinkShapes which,
                                              const char*& kind) {
  const bool visual = which == LinkShapes::kVisual && !link.visual.empty();
  kind = visual ? "visual" : "collision";
  return visual ? link.visual : link.collision;
}

// geometry_mesh() with its errors naming the robot, the link and the shape.
TriangleMesh shape_mesh(const robot::RobotModel& model, const robot::Link& link, const char* kind,
                        std::size_t index, const robot::Geometry& geometry, int segments) {
  try {
    return geometry_mesh(geometry, segments);
  } catch (const InputError& e) {
    throw InputError(fmt::format("robot '{}', link '{}', {} shape {}: {}", model.name(), link.name,
                                 kind, index, e.what()));
  }
}

}  // namespace

Eigen::Vector3f link_colour(const std::string& name) {
  if (has(name, "hand") || has(name, "palm") || has(name, "finger") || has(name, "thumb") ||
      has(name, "index") || has(name, "middle") || has(name, "ring") || has(name, "little"))
    return {0.93f, 0.74f, 0.60f};
  if (has(name, "eye")) return {0.12f, 0.12f, 0.14f};
  if (has(name, "head") || has(name, "neck")) return {0.92f, 0.92f, 0.90f};
  if (has(name, "forearm") || has(name, "elbow") || has(name, "wrist"))
    return {0.80f, 0.82f, 0.86f};
  if (has(name, "arm") || has(name, "shoulder")) return {0.68f, 0.70f, 0.75f};
  if (has(name, "torso") || has(name, "chest") || has(name, "waist")) return {0.50f, 0.52f, 0.58f};
  return {0.62f, 0.62f, 0.62f};
}

TriangleMesh geometry_mesh(const robot::Geometry& geometry, int segments) {
  if (geometry.type == robot::GeometryType::Mesh)
    return flat_mesh(robot::load_triangle_mesh(geometry.mesh_file, geometry.mesh_scale));
  return tessellate(geometry, segments);
}

TriangleMesh link_mesh(const robot::RobotModel& model, const std::string& link_name, int segments,
                       LinkShapes which) {
  const robot::Link& link = model.link(model.link_index(link_name));
  const char* kind = nullptr;
  const std::vector<robot::Geometry>& shapes = shapes_of(link, which, kind);
  if (shapes.empty())
    throw InputError(
        fmt::format("robot '{}', link '{}': no {}geometry", model.name(), link.name,
                    which == LinkShapes::kVisual ? "visual or collision " : "collision "));
  TriangleMesh merged;
  for (std::size_t s = 0; s < shapes.size(); ++s) {
    const TriangleMesh mesh = shape_mesh(model, link, kind, s, shapes[s], segments);
    const Eigen::Isometry3f origin = shapes[s].origin.cast<float>();
    const auto base = static_cast<std::uint32_t>(merged.positions.size());
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      merged.positions.push_back(origin * mesh.positions[v]);
      merged.normals.push_back(origin.linear() * mesh.normals[v]);
    }
    for (const std::uint32_t i : mesh.indices) merged.indices.push_back(base + i);
  }
  return merged;
}

RobotScene::RobotScene(SceneRenderer& renderer, std::shared_ptr<const robot::RobotModel> model,
                       const RobotSceneOptions& options)
    : renderer_(&renderer), model_(std::move(model)), options_(options) {
  if (options_.segments < 3)
    throw InputError(fmt::format("segments: expected >= 3, got {}", options_.segments));
  for (int i = 0; i < model_->num_links(); ++i) {
    const robot::Link& link = model_->link(i);
    const Eigen::Vector3f colour = link_colour(link.name);
    const char* kind = nullptr;
    const std::vector<robot::Geometry>& shapes = shapes_of(link, LinkShapes::kVisual, kind);
    for (std::size_t s = 0; s < shapes.size(); ++s) {
      const TriangleMesh mesh = shape_mesh(*model_, link, kind, s, shapes[s], options_.segments);
      triangles_ += mesh.triangle_count();
      const Eigen::Vector3f albedo =
          shapes[s].colour ? Eigen::Vector3f(shapes[s].colour->cast<float>()) : colour;
      parts_.push_back({i, renderer_->upload(mesh), shapes[s].origin, bounds(mesh), albedo});
    }
  }
}

void RobotScene::add_robot(const std::vector<Eigen::Isometry3d>& link_poses,
                           std::vector<DrawItem>& items,
                           const Eigen::Vector3d* viewpoint_root) const {
  check_pose_count(*model_, link_poses.size());
  for (const LinkPart& p : parts_) {
    DrawItem item;
    item.mesh = p.mesh;
    item.pose_root = link_poses[static_cast<std::size_t>(p.link)] * p.origin;
    if (viewpoint_root) {
      const Eigen::Vector3d v = item.pose_root.inverse(Eigen::Isometry) * *viewpoint_root;
      if ((v.array() >= p.bounds.min.array()).all() && (v.array() <= p.bounds.max.array()).all())
        continue;
    }
    item.colour = p.colour;
    item.id = link_id(p.link);
    items.push_back(item);
  }
}

void RobotScene::add_objects(const ObjectStates& objects, std::vector<DrawItem>& items) {
  for (std::size_t k = 0; k < objects.poses.size(); ++k) {
    if (k < objects.present.size() && !objects.present[k]) continue;
    const ObjectShape shape = k < objects.shape.size() ? objects.shape[k] : ObjectShape::kSphere;
    Eigen::Vector3d size = k < objects.size.size() ? objects.size[k] : Eigen::Vector3d::Zero();
    if (k >= objects.size.size() && k < objects.radius.size()) size.x() = objects.radius[k];
    const std::string mesh_file = k < objects.mesh.size() ? objects.mesh[k] : "";
    const std::string key = fmt::format("{} {} {} {} {}", static_cast<int>(shape), size.x(),
                                        size.y(), size.z(), mesh_file);
    auto it = object_meshes_.find(key);
    if (it == object_meshes_.end()) {
      TriangleMesh mesh;
      switch (shape) {
        case ObjectShape::kSphere:
          mesh = tessellate_sphere(size.x(), options_.segments);
          break;
        case ObjectShape::kBox:
          mesh = tessellate_box(2.0 * size);
          break;
        case ObjectShape::kCylinder:
          mesh = tessellate_cylinder(size.x(), 2.0 * size.y(), options_.segments);
          break;
        case ObjectShape::kMesh:
          try {
            mesh = flat_mesh(robot::load_triangle_mesh(mesh_file, size));
          } catch (const InputError& e) {
            throw RunError(fmt::format("object '{}': {}", objects.names.at(k), e.what()));
          }
          break;
      }
      it = object_meshes_.emplace(key, renderer_->upload(mesh)).first;
    }
    DrawItem item;
    item.mesh = it->second;
    item.pose_root = objects.poses[k];
    item.id = object_id(k);
    switch (shape) {
      case ObjectShape::kSphere:
        item.colour = {0.85f, 0.15f, 0.10f};
        break;
      case ObjectShape::kBox:
        item.colour = {0.15f, 0.30f, 0.85f};
        break;
      case ObjectShape::kCylinder:
        item.colour = {0.15f, 0.70f, 0.25f};
        break;
      case ObjectShape::kMesh:
        item.colour = {0.55f, 0.55f, 0.55f};
        break;
    }
    items.push_back(item);
  }
}

Camera camera_for(const robot::RobotModel& model, const std::string& camera_name,
                  const std::vector<Eigen::Isometry3d>& link_poses) {
  const int index = model.find_camera(camera_name);
  if (index < 0) {
    std::string names;
    for (const robot::Camera& c : model.cameras()) names += (names.empty() ? "" : ", ") + c.name;
    throw InputError(fmt::format("camera '{}' is not in robot '{}' (cameras: {})", camera_name,
                                 model.name(), names.empty() ? "none" : names));
  }
  check_pose_count(model, link_poses.size());
  const robot::Camera& c = model.cameras()[static_cast<std::size_t>(index)];
  Camera cam;
  cam.name = camera_name;
  cam.intrinsics = {c.width, c.height, c.fx, c.fy, c.cx, c.cy, c.near, c.far};
  // Same axes in both conventions (see the file comment of robot_scene.hpp).
  cam.pose_root = link_poses[static_cast<std::size_t>(c.link)] * c.pose;
  return cam;
}

}  // namespace somasim::render
