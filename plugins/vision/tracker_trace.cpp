#include "tracker_trace.hpp"

#include <iterator>

#include <fmt/format.h>

#include "somasim/atomic_file.hpp"

namespace somasim::plugins {

namespace {

void append_vector(std::string& out, const Eigen::Vector3d& v) {
  fmt::format_to(std::back_inserter(out), ",{:.5f},{:.5f},{:.5f}", v.x(), v.y(), v.z());
}

void append_eye(std::string& out, const vision::ColourTrack& t) {
  fmt::format_to(std::back_inserter(out), ",{:d},{:.2f},{:.2f},{:.2f},{}", t.tracked ? 1 : 0,
                 t.centre_px.x(), t.centre_px.y(), t.radius_px, t.object_px);
}

}  // namespace

TrackerTrace::TrackerTrace() {
  text_ =
      "time [s],outcome,"
      "left_tracked,left_u [px],left_v [px],left_radius [px],left_object [px],"
      "right_tracked,right_u [px],right_v [px],right_radius [px],right_object [px],"
      "x [m],y [m],z [m],vx [m/s],vy [m/s],vz [m/s],velocity_reported,velocity_sigma [m/s],"
      "window_fixes,radius [m],radius_rate [1/s],reprojection [px],size_ratio,"
      "truth_present,truth_x [m],truth_y [m],truth_z [m],truth_vx [m/s],truth_vy [m/s],"
      "truth_vz [m/s]\n";
}

void TrackerTrace::add(double time_s, const vision::StereoFix& fix, bool velocity_reported,
                       const pps::Stimulus* truth) {
  fmt::format_to(std::back_inserter(text_), "{:.4f},{}", time_s, enum_name(fix.outcome));
  append_eye(text_, fix.tracks[0]);
  append_eye(text_, fix.tracks[1]);
  append_vector(text_, fix.position);
  append_vector(text_, fix.velocity);
  fmt::format_to(std::back_inserter(text_), ",{:d},{:.4f},{},{:.5f},{:.4f},{:.3f},{:.3f}",
                 velocity_reported ? 1 : 0, fix.velocity_sigma, fix.window_fixes, fix.radius_m,
                 fix.window_radius_rate, fix.reprojection_px, fix.size_ratio);
  if (truth && truth->present) {
    text_ += ",1";
    append_vector(text_, truth->position);
    append_vector(text_, truth->velocity);
  } else {
    text_ += truth ? ",0,,,,,," : ",,,,,,,";
  }
  text_ += '\n';
  ++rows_;
}

void TrackerTrace::write(const std::filesystem::path& file) const {
  write_file_atomically(file, text_);
}

}  // namespace somasim::plugins
