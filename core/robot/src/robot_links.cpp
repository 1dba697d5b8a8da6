// Robot description loader: link properties: geometry, mass, inertia.

#include <fstream>

#include <Eigen/Eigenvalues>

#include "robot_loader_internal.hpp"

namespace somasim::robot::detail {

namespace {

const std::vector<std::string> kLinkKeys = {"collision", "visual", "mass",
                                            "density",   "com",    "inertia"};
const std::vector<std::string> kGeometryTypes = {"sphere", "box", "cylinder", "capsule", "mesh"};

}  // namespace

void RobotLoader::read_link_properties() {
  for (std::size_t i = 0; i < links_.size(); ++i) {
    if (!links_[i].declared) continue;
    const std::string item = "link '" + links_[i].name + "'";
    const YAML::Node n = links_[i].decl;
    Link& link = built_links_[i];
    if (n.IsNull()) continue;  // a declared link without properties
    if (!reader_.expect_map(n, item, "", "a map of link properties (collision, visual, mass)"))
      continue;
    reader_.check_keys(n, kLinkKeys, item, "");
    link.collision = read_geometries(n, "collision", item);
    link.visual = n["visual"] ? read_geometries(n, "visual", item) : link.collision;
    const auto density = reader_.positive(n, "density", item, "", false, "a density", "kg/m^3");
    const auto mass = reader_.positive(n, "mass", item, "", false, "a mass", "kg");
    if (n["mass"] && !mass) continue;
    const auto com = reader_.numbers(n, "com", item, "", false, 3, "m");
    const auto inertia = reader_.numbers(n, "inertia", item, "", false, 6, "kg m^2");
    if ((n["inertia"] || n["com"]) && !n["mass"]) {
      reader_.error(n[n["inertia"] ? "inertia" : "com"], item, n["inertia"] ? "inertia" : "com",
                    "given without 'mass'; expected 'mass' [kg] as well");
      continue;
    }
    const bool has_mesh =
        std::any_of(link.collision.begin(), link.collision.end(),
                    [](const Geometry& g) { return g.type == GeometryType::Mesh; });
    if (!mass) {
      if (has_mesh) {
        reader_.error(n["collision"], item, "mass",
                      "cannot compute the mass of mesh geometry; expected 'mass' [kg]");
        continue;
      }
      link.inertial = inertial_from_geometry(link.collision, density.value_or(density_));
      continue;
    }
    Inertial in;
    double vol = 0;
    for (const auto& g : link.collision) vol += volume(g);
    if (vol > 0) in = inertial_from_geometry(link.collision, *mass / vol);
    in.mass = *mass;
    if (com) in.com = *com;
    if (inertia) {
      const auto& v = *inertia;  // ixx, iyy, izz, ixy, ixz, iyz
      in.inertia << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(in.inertia);
      // Moments that are zero to rounding (thin parts, inertias turned into link axes) pass.
      if (eig.eigenvalues().minCoeff() < -(1e-9 * in.inertia.cwiseAbs().maxCoeff() + 1e-15)) {
        reader_.error(n["inertia"], item, "inertia",
                      "not a physical inertia (not positive semi-definite); expected [ixx, iyy, "
                      "izz, ixy, ixz, iyz] about the centre of mass [kg m^2]");
        continue;
      }
    }
    link.inertial = in;
  }
}

std::vector<Geometry> RobotLoader::read_geometries(const YAML::Node& link, const std::string& key,
                                                   const std::string& item) {
  std::vector<Geometry> out;
  const YAML::Node list = link[key];
  if (!list) return out;
  if (!list.IsSequence()) {
    reader_.error(list, item, key, "expected a list of shapes, got " + describe(list));
    return out;
  }
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = fmt::format("{}[{}]", key, i);
    if (auto g = read_geometry(list[i], item, path, key == "visual")) out.push_back(std::move(*g));
  }
  return out;
}

std::optional<Geometry> RobotLoader::read_geometry(const YAML::Node& n, const std::string& item,
                                                   const std::string& path, bool visual) {
  if (!reader_.expect_map(n, item, path, "a shape {type: sphere|box|cylinder|capsule|mesh, ...}"))
    return std::nullopt;
  const std::string prefix = path + ".";
  const auto type = reader_.string(n, "type", item, prefix, true);
  if (!type) return std::nullopt;
  const auto t = std::find(kGeometryTypes.begin(), kGeometryTypes.end(), *type);
  if (t == kGeometryTypes.end()) {
    reader_.error(n["type"], item, prefix + "type",
                  "unknown geometry type " + in_quotes(*type) +
                      did_you_mean(*type, kGeometryTypes) +
                      "; expected one of: " + join_names(kGeometryTypes));
    return std::nullopt;
  }
  Geometry g;
  g.type = static_cast<GeometryType>(t - kGeometryTypes.begin());
  std::vector<std::string> keys = {"type", "origin"};
  bool ok = true;
  const auto need = [&](const auto& v) {
    if (!v) ok = false;
    return v;
  };
  switch (g.type) {
    case GeometryType::Sphere:
      keys.push_back("radius");
      g.radius =
          need(reader_.positive(n, "radius", item, prefix, true, "a radius", "m")).value_or(0);
      break;
    case GeometryType::Box: {
      keys.push_back("size");
      const auto s = need(reader_.numbers(n, "size", item, prefix, true, 3, "m"));
      if (s && s->minCoeff() <= 0) {
        reader_.error(n["size"], item, prefix + "size",
                      "expected 3 extents > 0 [m], got a non-positive extent");
        ok = false;
      } else if (s) {
        g.size = *s;
      }
      break;
    }
    case GeometryType::Cylinder:
    case GeometryType::Capsule: {
      keys.insert(keys.end(), {"radius", "length", "from", "to"});
      g.radius =
          need(reader_.positive(n, "radius", item, prefix, true, "a radius", "m")).value_or(0);
      if (n["from"] || n["to"]) {
        // Along a segment: handy for limbs between two joint centres.
        const auto from = need(reader_.numbers(n, "from", item, prefix, true, 3, "m"));
        const auto to = need(reader_.numbers(n, "to", item, prefix, true, 3, "m"));
        if (n["length"] || n["origin"]) {
          reader_.error(n, item, path,
                        "expected either 'from'/'to' or 'length'/'origin', got both");
          return std::nullopt;
        }
        if (from && to) {
          const Eigen::Vector3d axis = *to - *from;
          g.length = axis.norm();
          if (g.length <= 0) {
            reader_.error(n["to"], item, prefix + "to", "expected 'to' different from 'from'");
            return std::nullopt;
          }
          g.origin.translation() = 0.5 * (*from + *to);
          g.origin.linear() =
              Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).toRotationMatrix();
        }
      } else {
        g.length =
            need(reader_.positive(n, "length", item, prefix, true, "a length", "m")).value_or(0);
      }
      break;
    }
    case GeometryType::Mesh: {
      keys.insert(keys.end(), {"file", "scale"});
      const auto file = need(reader_.string(n, "file", item, prefix, true));
      if (file) {
        const fs::path p = (origins_.directory(n["file"]) / *file).lexically_normal();
        std::error_code ec;
        if (!fs::exists(p, ec)) {
          reader_.error(n["file"], item, prefix + "file",
                        "mesh file " + in_quotes(*file) + " does not exist (resolved to '" +
                            p.string() + "')");
          ok = false;
        } else if (!fs::is_regular_file(p, ec) || !std::ifstream(p, std::ios::binary)) {
          reader_.error(n["file"], item, prefix + "file",
                        "mesh file " + in_quotes(*file) + " cannot be read (resolved to '" +
                            p.string() + "'); expected a readable regular file");
          ok = false;
        } else {
          g.mesh_file = p.string();
        }
      }
      if (const YAML::Node s = n["scale"]; s && s.IsScalar()) {
        const auto v = need(reader_.positive(n, "scale", item, prefix, false, "a scale", "1"));
        if (v) g.mesh_scale.setConstant(*v);
      } else if (s) {
        const auto v = need(reader_.numbers(n, "scale", item, prefix, false, 3));
        if (v && v->minCoeff() <= 0) {
          reader_.error(s, item, prefix + "scale", "expected scale factors > 0");
          ok = false;
        } else if (v) {
          g.mesh_scale = *v;
        }
      }
      break;
    }
  }
  if (visual) {
    keys.push_back("colour");
    if (n["colour"]) {
      const auto c = reader_.numbers(n, "colour", item, prefix, false, 3);
      if (!c) {
        ok = false;
      } else if (c->minCoeff() < 0 || c->maxCoeff() > 1) {
        reader_.error(n["colour"], item, prefix + "colour",
                      "expected [r, g, b] with each value in [0, 1]");
        ok = false;
      } else {
        g.colour = Eigen::Vector3d(*c);
      }
    }
  } else if (n["colour"]) {
    reader_.error(n["colour"], item, prefix + "colour",
                  "only visual shapes are drawn with a colour; expected it under 'visual'");
    return std::nullopt;
  }
  reader_.check_keys(n, keys, item, prefix);
  if (!n["from"]) {
    if (const auto origin = reader_.pose(n, "origin", item, prefix))
      g.origin = *origin;
    else
      ok = false;
  }
  if (!ok) return std::nullopt;
  return g;
}

}  // namespace somasim::robot::detail
