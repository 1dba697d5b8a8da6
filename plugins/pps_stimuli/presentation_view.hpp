#pragma once
// Whether the robot's eyes can see a presented object coming (object_thrower's `view`): the
// whole object (its bounding sphere) inside every checked camera's image where it appears (a
// tracker can acquire it there), its centre inside them and not hidden behind the robot's own
// links along the path it will fly, the head posed as it is when the object appears. An
// approaching object is checked until it is `until` from the skin (the last stretch may leave
// the image as the object meets the skin), a static one where it stands, a receding one along
// its whole path. Points and poses in the root frame [m].
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "somasim/name_table.hpp"
#include "somasim/pps/ports.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::plugins {

/// What the thrower does with the check: nothing, label each presentation (in_view /
/// out_of_view), or present only objects the cameras can see coming.
enum class ViewPolicy : std::uint8_t { kIgnore, kReport, kRequire };
/// "ignore", "report", "require".
inline constexpr NamedValue<ViewPolicy> kViewPolicyNames[] = {{ViewPolicy::kIgnore, "ignore"},
                                                              {ViewPolicy::kReport, "report"},
                                                              {ViewPolicy::kRequire, "require"}};
constexpr std::span<const NamedValue<ViewPolicy>> name_table(ViewPolicy) {
  return kViewPolicyNames;
}

class PresentationView {
 public:
  /// `cameras`: indices into model.cameras() (all must see the object); `until` [m];
  /// `margin_px` [px] kept from the image border.
  PresentationView(const robot::RobotModel& model, std::vector<int> cameras, double until,
                   double margin_px);

  /// nullopt when every camera sees an object of bounding radius `reach` [m] along the path
  /// `start` -> `end` of `motion` (see above);
  /// otherwise which camera does not, where and why (e.g. "'right_eye': outside the image
  /// 0.21 m from the end of the path").
  std::optional<std::string> unseen(const std::vector<Eigen::Isometry3d>& link_poses,
                                    PresentationMotion motion, const Eigen::Vector3d& start,
                                    const Eigen::Vector3d& end, double reach) const;

 private:
  const robot::RobotModel& model_;
  std::vector<int> cameras_;
  double until_ = 0.05, margin_px_ = 5.0;
};

}  // namespace somasim::plugins
