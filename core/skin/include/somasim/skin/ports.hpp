#pragma once
/// @file
/// Port value types of the skin: taxels posed in the root frame, contact events and one value
/// per taxel. Positions and normals are in the robot's root frame (waist: x backward, y to the
/// robot's right, z up) unless a field says otherwise.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "somasim/port_type.hpp"

namespace somasim {

/// Skin taxels of one body part, posed in the root frame at the current instant.
struct SkinPart {
  std::string name;                             ///< body part, e.g. "left_forearm"
  std::string link;                             ///< the link the skin is attached to
  std::vector<int> taxel_ids;                   ///< ids as in the skin layout
  std::vector<Eigen::Vector3d> positions;       ///< taxel centres [m], root frame
  std::vector<Eigen::Vector3d> normals;         ///< outward unit normals, root frame
  std::vector<Eigen::Vector3d> positions_link;  ///< taxel centres [m], link frame (fixed)
  std::vector<Eigen::Vector3d> normals_link;    ///< outward unit normals, link frame (fixed)
};

/// All skin parts a skin (or stimulus) plugin exposes.
struct SkinTaxels {
  std::vector<SkinPart> parts;
};

/// A contact on the skin of one body part (pressure over threshold on enough taxels).
struct ContactEvent {
  std::uint64_t id = 0;             ///< strictly increasing per producer; consumers skip seen ids
  double time_s = 0.0;              ///< sim time the contact was detected [s]
  std::string body_part;            ///< the part that was touched
  std::vector<int> touched_taxels;  ///< ids of the (virtual) taxels touched; may be empty
  /// Sim time of the first contact point of this contact episode [s] (the world's clock, so
  /// finer than a slower skin's steps; <= time_s). NaN when the producer does not know it.
  double first_touch_s = std::numeric_limits<double>::quiet_NaN();
  /// Centre of pressure of the touch [m] and the skin's outward unit normal there, both in the
  /// frame of the touched part's link (fixed to the skin, so independent of any kinematic
  /// belief). NaN when the producer does not know them.
  Eigen::Vector3d contact_point_link =
      Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d contact_normal_link =
      Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
};

/// The recent contact events of a producer (it prunes old ones; consumers track `id`).
struct ContactEvents {
  std::vector<ContactEvent> recent;
};

/// One value per taxel, in the order of a SkinTaxels input, parts concatenated.
struct TaxelValues {
  std::vector<std::string> labels;  ///< "part/id", for CSV headers
  std::vector<double> values;
};

template <>
struct PortTraits<SkinTaxels> {
  static constexpr const char* name = "skin_taxels";
  static constexpr const char* header = "somasim/skin/ports.hpp";
};

template <>
struct PortTraits<ContactEvents> {
  static constexpr const char* name = "contact_events";
  static constexpr const char* header = "somasim/skin/ports.hpp";
};

template <>
struct PortTraits<TaxelValues> {
  static constexpr const char* name = "taxel_values";
  static constexpr const char* header = "somasim/skin/ports.hpp";
  static std::vector<std::string> csv_columns(const TaxelValues& v) { return v.labels; }
  static void csv_write(const TaxelValues& v, std::string& row) {
    for (double x : v.values) csv_append(row, x);
  }
};

}  // namespace somasim
