#include "backdrop.hpp"

#include <cmath>

#include "somasim/render/tessellate.hpp"

namespace somasim::plugins {

std::vector<render::DrawItem> make_backdrop(render::SceneRenderer& renderer,
                                            const BackdropSpec& spec, std::mt19937_64& rng) {
  // Plane frame: z = the normal (towards the viewer), x horizontal, y completes it.
  const Eigen::Vector3d z = spec.normal_root.normalized();
  Eigen::Vector3d x = Eigen::Vector3d::UnitZ().cross(z);
  if (x.norm() < 1e-6) x = Eigen::Vector3d::UnitX();
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Isometry3d plane = Eigen::Isometry3d::Identity();
  plane.linear() << x, y, z;
  plane.translation() = spec.centre_root;

  std::vector<render::DrawItem> items;
  const double thickness = 0.002;
  render::DrawItem base;
  base.mesh = renderer.upload(render::tessellate_box({spec.size, spec.size, thickness}));
  base.pose_root = plane;
  base.colour = {0.55f, 0.55f, 0.52f};
  base.id = spec.id;
  items.push_back(base);

  // One unit box scaled per piece would need a scale in DrawItem; pieces are uploaded as they
  // are (a few dozen small meshes). Each piece sits a little further forward than the previous
  // one, so overlapping pieces never fight over depth.
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int pieces = spec.rectangles + spec.bars;
  for (int k = 0; k < pieces; ++k) {
    const bool bar = k >= spec.rectangles;
    const double w = bar ? 0.3 + 0.7 * unit(rng) : 0.05 + 0.30 * unit(rng);
    const double h = bar ? 0.01 + 0.02 * unit(rng) : 0.05 + 0.30 * unit(rng);
    const double angle = bar ? M_PI * unit(rng) : 0.0;
    const double u = (unit(rng) - 0.5) * spec.size, v = (unit(rng) - 0.5) * spec.size;
    render::DrawItem item;
    item.mesh = renderer.upload(render::tessellate_box({w, h, thickness}));
    Eigen::Isometry3d local = Eigen::Isometry3d::Identity();
    local.translation() = Eigen::Vector3d(u, v, thickness * (k + 1));
    local.linear() = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    item.pose_root = plane * local;
    // One draw per statement (argument evaluation order is unspecified), in g++'s order.
    const auto blue = static_cast<float>(unit(rng));
    const auto green = static_cast<float>(unit(rng));
    const auto red = static_cast<float>(unit(rng));
    item.colour = Eigen::Vector3f(red, green, blue);
    item.id = spec.id;
    items.push_back(item);
  }
  return items;
}

}  // namespace somasim::plugins
