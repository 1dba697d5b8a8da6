#pragma once
// Where one presented object starts and how it moves, relative to the taxel it is aimed at
// (object_thrower). All vectors in the root frame; [m], [m/s], [s].
//
// The object's centre is referred to the TARGET, one contact distance (`size`: sphere radius,
// half edge of a cube facing the taxel with a face, radius of a cylinder facing it with its side)
// above the taxel along its outward normal n; a direction `dir` is drawn within `cone_deg` of n.
//   approach: starts at target + d·dir, d in distance_min..max, moves at −speed·dir and reaches
//             the target (the surface touches the taxel) after d / speed; removed `linger` later.
//   static:   placed at target + d·dir, d in distance_min..max, still for static_duration.
//   receding: starts at target + s·dir, s in receding_start_min..max, moves at +speed·dir and is
//             removed after travelling distance_max.
#include <functional>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "somasim/name_table.hpp"
#include "somasim/pps/ports.hpp"
#include "somasim/robot/ports.hpp"

namespace somasim::plugins {

struct PresentationGeometry {
  double size = 0.025;  ///< contact distance of the object (see above) [m]
  double distance_min = 0.2, distance_max = 0.3;
  double cone_rad = 0.0;  ///< [rad]
  double speed_min = 0.05, speed_max = 0.15;
  double linger = 0.1;
  double static_duration = 2.0;
  double receding_start_min = 0.05, receding_start_max = 0.10;
};

struct PlannedObject {
  Eigen::Vector3d start = Eigen::Vector3d::Zero();  ///< centre at spawn [m]
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  double speed = 0.0;
  double lifetime = 0.0;  ///< removed this long after spawn [s]
  double travel = 0.0;    ///< approach: time to reach the skin [s]; otherwise 0
};

/// Accepts or rejects the path of an object's centre, `start` -> `end` [m, root frame]
/// (approach: start -> target; static: start -> start; receding: start -> where it is removed).
using PathCheck = std::function<bool(const Eigen::Vector3d& start, const Eigen::Vector3d& end)>;

/// Draws one presentation for `motion` aimed at the taxel (`taxel`, unit `normal`). Draws, in
/// order: per attempt a direction (2 numbers) and a start distance (1); then a speed (1, also
/// for static objects, so the streams of mixed motions stay aligned). `clear` accepts or
/// rejects each attempt's path (e.g. start and path clear of the robot); nullopt when
/// `attempts` attempts were all rejected.
std::optional<PlannedObject> plan_presentation(PresentationMotion motion,
                                               const Eigen::Vector3d& taxel,
                                               const Eigen::Vector3d& normal,
                                               const PresentationGeometry& g, std::mt19937_64& rng,
                                               const PathCheck& clear, int attempts = 100);

/// Which way a cylinder's axis lies in the plane across the aimed taxel's normal.
enum class CylinderAxis {
  kAny,         ///< a direction fixed by the normal alone (Eigen's unitOrthogonal)
  kAcrossPart,  ///< across the skin part's long axis (across a forearm: spans its width)
  kAlongPart,   ///< along the skin part's long axis
};
inline constexpr NamedValue<CylinderAxis> kCylinderAxisNames[] = {
    {CylinderAxis::kAny, "any"},
    {CylinderAxis::kAcrossPart, "across_part"},
    {CylinderAxis::kAlongPart, "along_part"}};
/// "any", "across_part", "along_part".
constexpr std::span<const NamedValue<CylinderAxis>> name_table(CylinderAxis) {
  return kCylinderAxisNames;
}

/// The long axis of a skin part: the unit direction of largest spread of its taxel positions
/// [root frame] (sign arbitrary); zero for fewer than two distinct positions.
Eigen::Vector3d part_long_axis(const std::vector<Eigen::Vector3d>& taxel_positions);

/// How an object is turned toward the taxel it is aimed at (outward unit normal), and its
/// ObjectSpawn::size: a cylinder's round side faces the taxel (its axis across the normal, laid
/// as `axis` says relative to the part's unit `long_axis`; kAny, or a long axis parallel to the
/// normal or zero, falls back to a direction fixed by the normal), a cube a corner (`corner`) or
/// its local +z face, a sphere as it is.
struct PresentedBody {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< root <- object
  Eigen::Vector3d size = Eigen::Vector3d::Zero();          ///< as ObjectSpawn::size [m]
};
PresentedBody presented_body(ObjectShape shape, bool corner, const Eigen::Vector3d& normal,
                             double size, double cylinder_half_height,
                             CylinderAxis axis = CylinderAxis::kAny,
                             const Eigen::Vector3d& long_axis = Eigen::Vector3d::Zero());

/// "sphere", "box", "cylinder", "mesh".
const char* shape_name(ObjectShape shape);

}  // namespace somasim::plugins
