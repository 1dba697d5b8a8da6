#include "somasim/robot/scene_file.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>

#include <yaml-cpp/yaml.h>

#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"
#include "somasim/robot/object_geometry.hpp"
#include "somasim/units.hpp"

namespace somasim::robot {
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kKeys = {"name",    "shape",    "radius",        "size", "length",
                                        "file",    "scale",    "motion",        "mass", "xyz",
                                        "rpy_deg", "velocity", "remove_after_s"};
const std::map<std::string, ObjectShape> kShapes = {{"sphere", ObjectShape::kSphere},
                                                    {"box", ObjectShape::kBox},
                                                    {"cylinder", ObjectShape::kCylinder},
                                                    {"mesh", ObjectShape::kMesh}};
const std::map<std::string, ObjectMotion> kMotions = {{"static", ObjectMotion::kStatic},
                                                      {"dynamic", ObjectMotion::kDynamic},
                                                      {"kinematic", ObjectMotion::kKinematic},
                                                      {"guided", ObjectMotion::kGuided}};

template <class T>
std::vector<std::string> keys_of(const std::map<std::string, T>& m) {
  std::vector<std::string> k;
  for (const auto& [name, value] : m) k.push_back(name);
  return k;
}

class SceneReader {
 public:
  explicit SceneReader(fs::path file) : file_(std::move(file)) {}

  std::vector<SceneObject> read() {
    YAML::Node root;
    try {
      root = YAML::LoadFile(file_.string());
    } catch (const YAML::BadFile&) {
      throw InputError("scene file '" + file_.string() + "' cannot be read");
    } catch (const YAML::Exception& e) {
      throw InputError(at(e.mark).str() + ": " + e.msg);
    }
    std::vector<SceneObject> out;
    if (!root.IsMap() || !root["objects"] || !root["objects"].IsSequence()) {
      diag_.add(at(root.Mark()), "", "objects", "expected a list of objects under 'objects'");
    } else {
      for (const auto& [key, value] : pairs(root))
        if (key != "objects")
          diag_.add(at(value.Mark()), "", key,
                    "unknown key" + did_you_mean(key, {"objects"}) + "; expected 'objects'");
      const YAML::Node list = root["objects"];
      for (std::size_t i = 0; i < list.size(); ++i) read_object(list[i], i, out);
    }
    diag_.throw_if_any();
    return out;
  }

 private:
  SourceLocation at(const YAML::Mark& m) const {
    return {file_.string(), m.line >= 0 ? m.line + 1 : 0, m.column >= 0 ? m.column + 1 : 0};
  }
  static std::vector<std::pair<std::string, YAML::Node>> pairs(const YAML::Node& map) {
    std::vector<std::pair<std::string, YAML::Node>> out;
    for (const auto& kv : map) out.emplace_back(kv.first.as<std::string>(), kv.second);
    return out;
  }

  std::optional<double> number(const YAML::Node& n, const std::string& item,
                               const std::string& key) {
    try {
      const double v = n.as<double>();
      if (std::isfinite(v)) return v;
    } catch (const YAML::Exception&) {
    }
    add(at(n.Mark()), item, key, "expected a finite number");
    return std::nullopt;
  }
  std::optional<Eigen::Vector3d> vec3(const YAML::Node& n, const std::string& item,
                                      const std::string& key) {
    if (!n.IsSequence() || n.size() != 3) {
      add(at(n.Mark()), item, key, "expected a list of 3 numbers");
      return std::nullopt;
    }
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) {
      auto x = number(n[i], item, key);
      if (!x) return std::nullopt;
      v[i] = *x;
    }
    return v;
  }
  std::optional<double> positive(const YAML::Node& n, const std::string& item,
                                 const std::string& key) {
    auto v = number(n, item, key);
    if (v && *v <= 0) {
      add(at(n.Mark()), item, key, "expected a number > 0");
      return std::nullopt;
    }
    return v;
  }

  void read_object(const YAML::Node& n, std::size_t index, std::vector<SceneObject>& out) {
    const std::string prefix = "objects[" + std::to_string(index) + "]";
    if (!n.IsMap()) {
      diag_.add(at(n.Mark()), "", prefix, "expected a map {name, shape, ...}");
      return;
    }
    SceneObject so;
    so.where = at(n.Mark());
    ObjectSpawn& s = so.spawn;
    s.id = index;
    s.name = n["name"] ? n["name"].as<std::string>() : "object" + std::to_string(index);
    const std::string item = prefix;
    const std::size_t errors_before = diag_.items().size();
    for (const auto& [key, value] : pairs(n))
      if (std::find(kKeys.begin(), kKeys.end(), key) == kKeys.end())
        add(at(value.Mark()), item, key,
            "unknown key" + did_you_mean(key, kKeys) + "; expected one of " + join_names(kKeys));
    if (!n["shape"]) {
      add(so.where, item, "shape", "missing; expected one of " + join_names(keys_of(kShapes)));
      return;
    }
    const std::string shape = n["shape"].as<std::string>();
    if (auto it = kShapes.find(shape); it != kShapes.end()) {
      s.shape = it->second;
    } else {
      add(at(n["shape"].Mark()), item, "shape",
          "unknown object type '" + shape + "'" + did_you_mean(shape, keys_of(kShapes)) +
              "; expected one of " + join_names(keys_of(kShapes)));
      return;
    }
    if (n["motion"]) {
      const std::string motion = n["motion"].as<std::string>();
      if (auto it = kMotions.find(motion); it != kMotions.end())
        s.motion = it->second;
      else
        add(at(n["motion"].Mark()), item, "motion",
            "unknown motion '" + motion + "'" + did_you_mean(motion, keys_of(kMotions)) +
                "; expected one of " + join_names(keys_of(kMotions)));
    }
    auto require = [&](const char* key) -> YAML::Node {
      if (!n[key]) add(so.where, item, key, "missing (needed by a " + shape + ")");
      return n[key];
    };
    switch (s.shape) {
      case ObjectShape::kSphere:
        if (auto r = require("radius"); r)
          if (auto v = positive(r, item, "radius")) s.size.x() = *v;
        break;
      case ObjectShape::kBox:
        if (auto sz = require("size"); sz)
          if (auto v = vec3(sz, item, "size")) {
            if ((v->array() <= 0).any()) add(at(sz.Mark()), item, "size", "expected 3 numbers > 0");
            s.size = 0.5 * *v;
          }
        break;
      case ObjectShape::kCylinder:
        if (auto r = require("radius"); r)
          if (auto v = positive(r, item, "radius")) s.size.x() = *v;
        if (auto l = require("length"); l)
          if (auto v = positive(l, item, "length")) s.size.y() = 0.5 * *v;
        break;
      case ObjectShape::kMesh:
        if (auto f = require("file"); f) {
          const fs::path p = fs::path(f.as<std::string>()).is_absolute()
                                 ? fs::path(f.as<std::string>())
                                 : file_.parent_path() / f.as<std::string>();
          if (!fs::exists(p))
            add(at(f.Mark()), item, "file",
                "mesh file '" + f.as<std::string>() + "' does not exist (resolved to '" +
                    p.lexically_normal().string() + "')");
          s.mesh = p.lexically_normal().string();
        }
        s.size = Eigen::Vector3d::Ones();
        if (const YAML::Node sc = n["scale"]; sc) {
          if (sc.IsSequence()) {
            if (auto v = vec3(sc, item, "scale")) s.size = *v;
          } else if (auto v = positive(sc, item, "scale")) {
            s.size.setConstant(*v);
          }
        }
        break;
    }
    if (n["mass"])
      if (auto v = positive(n["mass"], item, "mass")) s.mass = *v;
    Eigen::Vector3d xyz = Eigen::Vector3d::Zero(), rpy = Eigen::Vector3d::Zero();
    if (n["xyz"])
      if (auto v = vec3(n["xyz"], item, "xyz")) xyz = *v;
    if (n["rpy_deg"])
      if (auto v = vec3(n["rpy_deg"], item, "rpy_deg")) rpy = *v * kRadPerDeg;
    s.pose = Eigen::Isometry3d::Identity();
    s.pose.translation() = xyz;
    s.pose.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                       Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                       Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                          .toRotationMatrix();
    if (n["velocity"])
      if (auto v = vec3(n["velocity"], item, "velocity")) s.linear_velocity = *v;
    if (n["remove_after_s"])
      if (auto v = number(n["remove_after_s"], item, "remove_after_s")) s.remove_after_s = *v;
    if (diag_.items().size() == errors_before) out.push_back(std::move(so));
  }

  // "file:line:col: key 'objects[2].shape': message".
  void add(SourceLocation where, const std::string& item, const std::string& key,
           std::string message) {
    diag_.add(std::move(where), "", item + "." + key, std::move(message));
  }

  fs::path file_;
  Diagnostics diag_;
};

}  // namespace

std::vector<SceneObject> load_scene(const fs::path& file) {
  return SceneReader(file).read();
}

}  // namespace somasim::robot
