// Robot description loader: frames, cameras, skin.

#include <tuple>
#include <utility>

#include "robot_loader_internal.hpp"

namespace somasim::robot::detail {

namespace {

const std::vector<std::string> kFrameKeys = {"link", "origin"};
constexpr std::int64_t kMaxImageSide = 16384;  // [px] (OpenGL's usual framebuffer limit)
const std::vector<std::string> kCameraKeys = {"link", "frame", "origin", "fx",   "fy", "cx",
                                              "cy",   "width", "height", "near", "far"};
const std::vector<std::string> kSurfaces = {"cylinder", "box_face"};
const std::vector<std::string> kCylinderSkinKeys = {
    "link",  "surface",       "origin",        "radius",  "z_min",
    "z_max", "angle_min_deg", "angle_max_deg", "spacing", "group_size"};
const std::vector<std::string> kBoxFaceSkinKeys = {"link",   "surface", "origin",    "size_x",
                                                   "size_y", "spacing", "group_size"};

}  // namespace

std::optional<int> RobotLoader::find_link(const YAML::Node& map, const std::string& key,
                                          const std::string& item, bool required) {
  const auto name = reader_.string(map, key, item, "", required);
  if (!name) return std::nullopt;
  if (auto it = link_index_.find(*name); it != link_index_.end()) return it->second;
  reader_.error(map[key], item, key,
                "unknown link " + in_quotes(*name) + did_you_mean(*name, link_names()));
  return std::nullopt;
}

void RobotLoader::add_frame(Frame f, const YAML::Node& at, const std::string& item) {
  for (const auto& other : frames_)
    if (other.name == f.name) {
      reader_.error(at, item, "",
                    "a frame of this name already exists; expected unique frame names");
      return;
    }
  frames_.push_back(std::move(f));
}

void RobotLoader::read_frames(const YAML::Node& frames) {
  for (const auto& tip : chain_tips_) {
    const int link = link_index_.at(old_link_names_.at(tip.link));
    add_frame({tip.name, link, tip.pose}, tip.at, tip.item);
  }
  if (!frames) return;
  if (!reader_.expect_map(frames, "", "frames", "a map of frame names to {link, origin}")) return;
  for (const auto& kv : frames) {
    const std::string item = "frame '" + kv.first.Scalar() + "'";
    if (!reader_.expect_map(kv.second, item, "", "a map with 'link' and 'origin'")) continue;
    reader_.check_keys(kv.second, kFrameKeys, item, "");
    const auto link = find_link(kv.second, "link", item, true);
    const auto pose = reader_.pose(kv.second, "origin", item, "");
    if (link && pose) add_frame({kv.first.Scalar(), *link, *pose}, kv.first, item);
  }
}

void RobotLoader::read_cameras(const YAML::Node& cameras) {
  if (!cameras) return;
  if (!reader_.expect_map(cameras, "", "cameras", "a map of camera names to cameras")) return;
  for (const auto& kv : cameras) {
    const std::string item = "camera '" + kv.first.Scalar() + "'";
    const YAML::Node n = kv.second;
    if (!reader_.expect_map(n, item, "", "a map with 'link' or 'frame', 'fx', 'fy', ...")) continue;
    reader_.check_keys(n, kCameraKeys, item, "");
    Camera c;
    c.name = kv.first.Scalar();
    bool ok = true;
    const auto origin = reader_.pose(n, "origin", item, "");
    if (!origin) ok = false;
    if (n["frame"] && n["link"]) {
      reader_.error(n, item, "frame", "expected either 'link' or 'frame', got both");
      ok = false;
    } else if (n["frame"]) {
      const auto f = reader_.string(n, "frame", item, "", true);
      const auto it = std::find_if(frames_.begin(), frames_.end(),
                                   [&](const Frame& fr) { return f && fr.name == *f; });
      if (!f) {
        ok = false;
      } else if (it == frames_.end()) {
        std::vector<std::string> names;
        for (const auto& fr : frames_) names.push_back(fr.name);
        reader_.error(n["frame"], item, "frame",
                      "unknown frame " + in_quotes(*f) + did_you_mean(*f, names));
        ok = false;
      } else if (origin) {
        c.link = it->link;
        c.pose = it->pose * *origin;
      }
    } else if (const auto link = find_link(n, "link", item, true)) {
      c.link = *link;
      if (origin) c.pose = *origin;
    } else {
      ok = false;
    }
    const auto fx = reader_.positive(n, "fx", item, "", true, "a focal length", "px");
    const auto fy = reader_.positive(n, "fy", item, "", true, "a focal length", "px");
    const auto w = reader_.integer(n, "width", item, "", true, 1, kMaxImageSide);
    const auto h = reader_.integer(n, "height", item, "", true, 1, kMaxImageSide);
    const auto cx = reader_.number(n, "cx", item, "", false, "px");
    const auto cy = reader_.number(n, "cy", item, "", false, "px");
    const auto near_clip = reader_.positive(n, "near", item, "", false, "a clipping distance", "m");
    const auto far_clip = reader_.positive(n, "far", item, "", false, "a clipping distance", "m");
    if (!fx || !fy || !w || !h || (n["cx"] && !cx) || (n["cy"] && !cy) ||
        (n["near"] && !near_clip) || (n["far"] && !far_clip))
      ok = false;
    if (!ok) continue;
    c.fx = *fx;
    c.fy = *fy;
    c.width = static_cast<int>(*w);
    c.height = static_cast<int>(*h);
    c.cx = cx.value_or(0.5 * c.width);
    c.cy = cy.value_or(0.5 * c.height);
    c.near = near_clip.value_or(0.01);
    c.far = far_clip.value_or(100.0);
    // A focal length far from the image's size renders nothing useful (1e-300: every point
    // on one pixel; 1e308: nothing in view): fx and fy within [1e-3, 1e3] of the image width.
    for (const auto& [key, f] : {std::pair{"fx", c.fx}, std::pair{"fy", c.fy}})
      if (f < 1e-3 * c.width || f > 1e3 * c.width) {
        reader_.error(n[key], item, key,
                      fmt::format("{} px for an image {} px wide; expected a focal length in "
                                  "[{:g}, {:g}] px (1e-3 to 1e3 times the width)",
                                  f, c.width, 1e-3 * c.width, 1e3 * c.width));
        ok = false;
      }
    for (const auto& [key, v, size] :
         {std::tuple{"cx", c.cx, c.width}, std::tuple{"cy", c.cy, c.height}})
      if (std::abs(v) > 10.0 * size) {
        reader_.error(n[key], item, key,
                      fmt::format("{} px for an image of {} px; expected a principal point "
                                  "within 10 image sizes of the image",
                                  v, size));
        ok = false;
      }
    if (!ok) continue;
    if (c.far <= c.near) {
      reader_.error(n["far"] ? n["far"] : n, item, "far",
                    fmt::format("far {} <= near {}; expected far > near [m]", c.far, c.near));
      continue;
    }
    cameras_.push_back(std::move(c));
  }
}

void RobotLoader::read_skin(const YAML::Node& skin) {
  if (!skin) return;
  if (!reader_.expect_map(skin, "", "skin", "a map of body-part names to skin patches")) return;
  for (const auto& kv : skin) {
    const std::string item = "skin patch '" + kv.first.Scalar() + "'";
    const YAML::Node n = kv.second;
    if (!reader_.expect_map(n, item, "", "a map with 'link', 'surface' and its parameters"))
      continue;
    SkinPatch p;
    p.body_part = kv.first.Scalar();
    const auto link = find_link(n, "link", item, true);
    const auto surface = reader_.string(n, "surface", item, "", true);
    const auto origin = reader_.pose(n, "origin", item, "");
    if (!surface) continue;
    if (std::find(kSurfaces.begin(), kSurfaces.end(), *surface) == kSurfaces.end()) {
      reader_.error(n["surface"], item, "surface",
                    "unknown surface " + in_quotes(*surface) + did_you_mean(*surface, kSurfaces) +
                        "; expected one of: " + join_names(kSurfaces));
      continue;
    }
    p.surface = *surface;
    const bool cylinder = *surface == "cylinder";
    reader_.check_keys(n, cylinder ? kCylinderSkinKeys : kBoxFaceSkinKeys, item, "");
    bool ok = link && origin;
    const auto put = [&](const std::string& key, std::optional<double> v, bool required) {
      if (v)
        p.params[key] = *v;
      else if (required || n[key])
        ok = false;
    };
    const auto spacing = reader_.positive(n, "spacing", item, "", true, "a spacing", "m");
    put("spacing", spacing, true);
    const auto group = reader_.integer(n, "group_size", item, "", false, 1);
    put("group_size", group ? std::optional<double>(static_cast<double>(*group)) : std::nullopt,
        false);
    if (cylinder) {
      put("radius", reader_.positive(n, "radius", item, "", true, "a radius", "m"), true);
      const auto z0 = reader_.number(n, "z_min", item, "", true, "m");
      const auto z1 = reader_.number(n, "z_max", item, "", true, "m");
      put("z_min", z0, true);
      put("z_max", z1, true);
      if (z0 && z1 && *z0 >= *z1) {
        reader_.error(n["z_max"], item, "z_max",
                      fmt::format("z_max {} <= z_min {}; expected z_min < z_max [m]",
                                  n["z_max"].Scalar(), n["z_min"].Scalar()));
        ok = false;
      }
      const auto a0 = reader_.number(n, "angle_min_deg", item, "", false, "deg");
      const auto a1 = reader_.number(n, "angle_max_deg", item, "", false, "deg");
      put("angle_min_deg", a0.value_or(-180.0), false);
      put("angle_max_deg", a1.value_or(180.0), false);
      if ((n["angle_min_deg"] && !a0) || (n["angle_max_deg"] && !a1)) ok = false;
      const double span = a1.value_or(180.0) - a0.value_or(-180.0);
      if (ok && (span <= 0 || span > 360)) {
        reader_.error(n["angle_max_deg"] ? n["angle_max_deg"] : n, item, "angle_max_deg",
                      fmt::format("the angle range [{}, {}] deg is empty or wider than a turn; "
                                  "expected angle_min_deg < angle_max_deg <= angle_min_deg + 360",
                                  a0.value_or(-180.0), a1.value_or(180.0)));
        ok = false;
      }
    } else {
      put("size_x", reader_.positive(n, "size_x", item, "", true, "a size", "m"), true);
      put("size_y", reader_.positive(n, "size_y", item, "", true, "a size", "m"), true);
    }
    if (!ok) continue;
    p.link = *link;
    p.origin = *origin;
    skin_patches_.push_back(std::move(p));
  }
}

}  // namespace somasim::robot::detail
