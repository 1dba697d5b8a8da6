#pragma once
/// @file
/// Skin layouts: physical taxels (positions and outward normals in the link frame) grouped into
/// virtual taxels (one per module of neighbouring taxels, like the iCub's triangles of 10-12
/// taxels; the PPS learner uses one virtual taxel per module).
///
/// A layout is generated from a robot's skin patch (robot::SkinPatch, see
/// assets/robots/README.md) or loaded from a file (layout_file.hpp).
///
/// Generated layouts place taxels on a regular grid of the patch surface, exactly `spacing`
/// apart along the surface (cylinders: arc length around the axis, length along it; box faces:
/// x and y), centred in the patch extent. Physical ids are 0..N-1 in grid order (rows along the
/// length / y, columns around / along x). Modules are rectangular blocks of about `group_size`
/// neighbouring taxels (block counts chosen so that blocks are about square); virtual ids are
/// 0..M-1 in block order, and each virtual taxel takes the position and normal of its centre
/// taxel (the member nearest the module's centroid).
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "somasim/robot/robot_model.hpp"

namespace somasim::skin {

/// One module of physical taxels, represented by its centre taxel.
struct VirtualTaxel {
  int id = 0;                ///< virtual taxel id (as published on the skin's ports)
  int centre = 0;            ///< index (not id) of the centre physical taxel
  std::vector<int> members;  ///< indices (not ids) of the physical taxels of the module
};

/// The taxels of one body part, fixed to one link.
struct SkinLayout {
  std::string body_part;
  int link = -1;  ///< link index in the robot model
  // Physical taxels (parallel arrays, size N).
  std::vector<int> ids;                    ///< physical taxel ids (unique)
  std::vector<Eigen::Vector3d> positions;  ///< taxel centres [m], link frame
  std::vector<Eigen::Vector3d> normals;    ///< outward unit normals, link frame
  std::vector<int> module;                 ///< index into `virtual_taxels` of each taxel
  // Virtual taxels (size M); every physical taxel is a member of exactly one.
  std::vector<VirtualTaxel> virtual_taxels;

  std::size_t size() const { return ids.size(); }
  const Eigen::Vector3d& virtual_position(std::size_t v) const {
    return positions[static_cast<std::size_t>(virtual_taxels[v].centre)];
  }
  const Eigen::Vector3d& virtual_normal(std::size_t v) const {
    return normals[static_cast<std::size_t>(virtual_taxels[v].centre)];
  }
};

/// Overrides of a patch's own generator parameters (0 = use the patch's value).
struct LayoutOptions {
  double spacing = 0.0;  ///< distance between neighbouring taxel centres [m]
  int group_size = 0;    ///< physical taxels per virtual taxel (module)
};

/// Generates the layout of `patch`. Throws InputError "skin patch 'P': ..." when a parameter is
/// missing or out of range (the robot loader validates descriptions; this guards hand-built
/// patches and overrides) or when the spacing leaves no taxel on the patch.
SkinLayout generate_layout(const robot::SkinPatch& patch, const LayoutOptions& options = {});

/// Unrolled 2-D coordinates [m] of link-frame points on the patch surface, for figures:
/// cylinder: (arc length r·angle from angle 0 toward +y of the patch frame, position along the
/// axis); box face: (x, y) in the face frame. Points off the surface are projected onto it.
std::vector<Eigen::Vector2d> surface_coordinates(const robot::SkinPatch& patch,
                                                 const std::vector<Eigen::Vector3d>& positions);

/// Axis labels of surface_coordinates() for `patch`, e.g. {"around the forearm [m]", ...}.
std::pair<std::string, std::string> surface_axis_labels(const robot::SkinPatch& patch);

/// Makes every physical taxel its own virtual taxel with the same id.
void one_module_per_taxel(SkinLayout& layout);

/// Groups taxels by a module key per taxel (virtual id = key; centre = member nearest the
/// members' mean position). Virtual taxels are ordered by key.
void group_by_key(SkinLayout& layout, const std::vector<int>& keys);

}  // namespace somasim::skin
