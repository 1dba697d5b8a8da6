#pragma once
// The `textured` background of the camera plugin: clutter (rectangles and bars of random
// colours) on a grey plane behind the scene, generated from the node's random stream, so that
// edge detection has edges to find that are not the robot's.
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "somasim/render/scene_renderer.hpp"

namespace somasim::plugins {

struct BackdropSpec {
  Eigen::Vector3d centre_root = Eigen::Vector3d::Zero();   ///< centre of the plane [m]
  Eigen::Vector3d normal_root = Eigen::Vector3d::UnitX();  ///< unit, towards the viewer
  double size = 3.0;                                       ///< side of the square plane [m]
  int rectangles = 40;                                     ///< clutter rectangles
  int bars = 25;                                           ///< long thin bars
  std::int32_t id = 1;  ///< id of every backdrop item in the id mask
};

/// Uploads the backdrop's meshes into `renderer` and returns its draw items (static).
std::vector<render::DrawItem> make_backdrop(render::SceneRenderer& renderer,
                                            const BackdropSpec& spec, std::mt19937_64& rng);

}  // namespace somasim::plugins
