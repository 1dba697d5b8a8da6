#pragma once
/// @file
/// The iCub skin's contact lists (`/skinManager/skin_events:o`, iCub::skinDynLib::
/// skinContactList) in their Bottle form: one list per contact,
/// @code
///   ((CONTACT_ID BODY_PART LINK SKIN_PART) (CoP x y z) (force x y z) (moment x y z)
///    (geometric centre x y z) (normal x y z) (TAXEL_ID ...) PRESSURE)
/// @endcode
/// Positions [m] and the normal are in the frame of the skin part's link (the iCub's DH link
/// frame, LINK = index in the arm chain: 2 upper arm, 4 forearm, 6 hand); force [N], moment
/// [N·m]; taxel ids index the part's taxel positions file (skinGui/conf/positions); pressure is
/// the skin's raw average over the touched taxels.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "somasim/recordings/yarp_bottle.hpp"

namespace somasim::recordings {

/// One contact of a contact list.
struct SkinContactRecord {
  std::int64_t contact_id = 0;
  int body_part = 0;  ///< iCub BodyPart: 1 torso, 2 head, 3 left arm, 4 right arm, ...
  int link = 0;       ///< link of the body part's chain
  int skin_part = 0;  ///< iCub SkinPart (see icub_skin_part_name)
  Eigen::Vector3d centre_of_pressure = Eigen::Vector3d::Zero();  ///< [m], link frame
  Eigen::Vector3d force = Eigen::Vector3d::Zero();               ///< [N], link frame
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();              ///< [N m], link frame
  Eigen::Vector3d geometric_centre = Eigen::Vector3d::Zero();    ///< [m], link frame
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< link frame (zero: not estimated)
  std::vector<int> taxels;                           ///< touched taxel ids
  double pressure = 0.0;                             ///< raw skin units
};

/// Decodes a contact list. Throws BottleSyntaxError at the column of the first value that does
/// not fit the layout above (saying which contact and field, and what was expected).
std::vector<SkinContactRecord> decode_skin_contact_list(const BottleList& bottle);

/// The iCub's name of a SkinPart id (iCub::skinDynLib::SkinPart): 1 "left_hand",
/// 2 "left_forearm", 3 "left_upper_arm", 4 "right_hand", 5 "right_forearm", 6 "right_upper_arm",
/// 7 "front_torso", 8 "left_upper_leg", 9 "left_lower_leg", 10 "left_foot", 11 "right_upper_leg",
/// 12 "right_lower_leg", 13 "right_foot"; std::nullopt for any other id.
std::optional<std::string_view> icub_skin_part_name(int skin_part);

/// The SkinPart id of an iCub skin part name (as icub_skin_part_name), or std::nullopt.
std::optional<int> icub_skin_part_id(std::string_view name);

}  // namespace somasim::recordings
