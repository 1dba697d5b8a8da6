#pragma once
/// @file
/// Port value types of peripersonal space: the perceived stimulus (pps::Stimulus, from
/// stimulus.hpp, with `present`) and the object a stimulus source is presenting (for
/// evaluators). Positions and velocities are in the robot's root frame.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "somasim/port_type.hpp"
#include "somasim/pps/stimulus.hpp"

namespace somasim {

/// How a presented object moves relative to the skin taxel it is placed at (PPS evaluation):
/// toward it until it reaches the skin, held still, or moving away from it.
enum class PresentationMotion : std::uint8_t { kApproach, kStatic, kReceding };

/// "approach", "static" or "receding" (as in parameters, metrics and file names).
inline const char* motion_name(PresentationMotion motion) {
  switch (motion) {
    case PresentationMotion::kApproach:
      return "approach";
    case PresentationMotion::kStatic:
      return "static";
    case PresentationMotion::kReceding:
      return "receding";
  }
  return "unknown";
}

/// Whether the robot's cameras could see a presented object coming (its source checks the path
/// against the cameras' images and the robot's body at presentation time).
enum class PresentationSight : std::uint8_t { kNotChecked, kInView, kOutOfView };

/// "not_checked", "in_view" or "out_of_view" (as in metrics).
inline const char* presentation_sight_name(PresentationSight sight) {
  switch (sight) {
    case PresentationSight::kNotChecked:
      return "not_checked";
    case PresentationSight::kInView:
      return "in_view";
    case PresentationSight::kOutOfView:
      return "out_of_view";
  }
  return "unknown";
}

/// The object a stimulus source is presenting now (one at a time), for evaluators.
struct Presentation {
  std::uint64_t id = 0;  ///< 1, 2, ... per producer; 0: nothing presented yet
  bool active = false;   ///< the object is in the world now
  PresentationMotion motion = PresentationMotion::kApproach;
  std::string object;                                        ///< object name in ObjectStates
  std::string body_part;                                     ///< skin part aimed at
  int taxel_id = -1;                                         ///< taxel aimed at (layout id)
  Eigen::Vector3d aimed_point = Eigen::Vector3d::Zero();     ///< taxel at presentation [m], root
  double start_time_s = 0.0;                                 ///< sim time it appeared [s]
  double speed = 0.0;                                        ///< [m/s] (0 for static)
  PresentationSight sight = PresentationSight::kNotChecked;  ///< seen coming by the cameras
};

template <>
struct PortTraits<Presentation> {
  static constexpr const char* name = "presentation";
  static constexpr const char* header = "somasim/pps/ports.hpp";
  static std::vector<std::string> csv_columns(const Presentation&) {
    return {"id", "active", "motion (0 approach, 1 static, 2 receding)", "taxel_id", "speed [m/s]"};
  }
  static void csv_write(const Presentation& p, std::string& row) {
    csv_append(row, static_cast<double>(p.id));
    csv_append(row, p.active ? 1.0 : 0.0);
    csv_append(row, static_cast<double>(p.motion));
    csv_append(row, static_cast<double>(p.taxel_id));
    csv_append(row, p.speed);
  }
};

template <>
struct PortTraits<pps::Stimulus> {
  static constexpr const char* name = "stimulus";
  static constexpr const char* header = "somasim/pps/ports.hpp";
  static std::vector<std::string> csv_columns(const pps::Stimulus&) {
    return {"present", "x [m]", "y [m]", "z [m]", "vx [m/s]", "vy [m/s]", "vz [m/s]", "radius [m]"};
  }
  static void csv_write(const pps::Stimulus& s, std::string& row) {
    csv_append(row, s.present ? 1.0 : 0.0);
    for (int i = 0; i < 3; ++i) csv_append(row, s.position[i]);
    for (int i = 0; i < 3; ++i) csv_append(row, s.velocity[i]);
    csv_append(row, s.radius);
  }
};

}  // namespace somasim
