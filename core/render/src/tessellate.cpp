#include "somasim/render/tessellate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "somasim/error.hpp"

namespace somasim::render {

namespace {

// One point of a profile of a surface of revolution about z: radius, height and the surface
// normal in the (radial, z) plane.
struct ProfilePoint {
  double r, z, nr, nz;
};

void check_segments(int segments) {
  if (segments < 3)
    throw InputError(
        fmt::format("render: tessellation needs at least 3 segments, got {}", segments));
}

void check_length(double value, const char* what) {
  if (!std::isfinite(value) || value < 0.0)
    throw InputError(
        fmt::format("render: tessellation needs a finite {} >= 0, got {}", what, value));
}

// Adds the surface swept by a profile strip (points ordered so that the outside is on the left
// when walking down the strip seen from outside): a ring of `segments` vertices per point, or a
// single vertex where r = 0.
void add_revolution(TriangleMesh& mesh, const std::vector<ProfilePoint>& strip, int segments) {
  std::vector<std::uint32_t> first(strip.size());
  std::vector<bool> pole(strip.size());
  for (std::size_t k = 0; k < strip.size(); ++k) {
    const ProfilePoint& p = strip[k];
    first[k] = static_cast<std::uint32_t>(mesh.positions.size());
    pole[k] = p.r == 0.0;
    const int n = pole[k] ? 1 : segments;
    for (int j = 0; j < n; ++j) {
      const double phi = 2.0 * M_PI * j / segments;
      const double c = std::cos(phi), s = std::sin(phi);
      mesh.positions.emplace_back(static_cast<float>(p.r * c), static_cast<float>(p.r * s),
                                  static_cast<float>(p.z));
      mesh.normals.push_back(Eigen::Vector3d(p.nr * c, p.nr * s, p.nz).normalized().cast<float>());
    }
  }
  for (std::size_t k = 0; k + 1 < strip.size(); ++k) {
    if (pole[k] && pole[k + 1]) continue;
    for (int j = 0; j < segments; ++j) {
      const auto jn = static_cast<std::uint32_t>((j + 1) % segments);
      const auto jj = static_cast<std::uint32_t>(j);
      const std::uint32_t a0 = first[k] + (pole[k] ? 0 : jj);
      const std::uint32_t a1 = first[k] + (pole[k] ? 0 : jn);
      const std::uint32_t b0 = first[k + 1] + (pole[k + 1] ? 0 : jj);
      const std::uint32_t b1 = first[k + 1] + (pole[k + 1] ? 0 : jn);
      if (!pole[k + 1]) mesh.indices.insert(mesh.indices.end(), {a0, b0, b1});
      if (!pole[k]) mesh.indices.insert(mesh.indices.end(), {a0, b1, a1});
    }
  }
}

// Points of a hemisphere of radius r centred at height zc, from the pole at zc + sign * r to
// the equator, `rings` bands.
std::vector<ProfilePoint> hemisphere(double r, double zc, double sign, int rings) {
  std::vector<ProfilePoint> points;
  for (int k = 0; k <= rings; ++k) {
    const double theta = 0.5 * M_PI * k / rings;  // from the pole
    const double s = std::sin(theta), c = std::cos(theta);
    points.push_back({r * s, zc + sign * r * c, s, sign * c});
  }
  return points;
}

}  // namespace

Bounds bounds(const TriangleMesh& mesh) {
  Bounds b;
  if (mesh.positions.empty()) return b;
  b.min = b.max = mesh.positions.front().cast<double>();
  for (const Eigen::Vector3f& p : mesh.positions) {
    b.min = b.min.cwiseMin(p.cast<double>());
    b.max = b.max.cwiseMax(p.cast<double>());
  }
  return b;
}

TriangleMesh tessellate_box(const Eigen::Vector3d& size) {
  for (int i = 0; i < 3; ++i) check_length(size[i], "box size");
  const Eigen::Vector3d h = 0.5 * size;
  TriangleMesh mesh;
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {1.0, -1.0}) {
      const Eigen::Vector3d n = sign * Eigen::Vector3d::Unit(axis);
      // u x v = n: (e1, e2) for +e0, swapped for -e0 (cyclic in the axes).
      Eigen::Vector3d u = Eigen::Vector3d::Unit((axis + 1) % 3);
      Eigen::Vector3d v = Eigen::Vector3d::Unit((axis + 2) % 3);
      if (sign < 0) std::swap(u, v);
      const Eigen::Vector3d centre = n.cwiseProduct(h);
      const Eigen::Vector3d du = u.cwiseProduct(h), dv = v.cwiseProduct(h);
      const auto base = static_cast<std::uint32_t>(mesh.positions.size());
      for (const auto& [a, b] : {std::pair{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}}) {
        mesh.positions.push_back((centre + a * du + b * dv).cast<float>());
        mesh.normals.push_back(n.cast<float>());
      }
      mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
  }
  return mesh;
}

TriangleMesh tessellate_sphere(double radius, int segments) {
  check_segments(segments);
  check_length(radius, "sphere radius");
  const int rings = std::max(2, segments / 2);
  std::vector<ProfilePoint> strip;
  for (int k = 0; k <= rings; ++k) {
    const double theta = M_PI * k / rings;  // from the +z pole
    const double s = k == rings ? 0.0 : std::sin(theta), c = std::cos(theta);
    strip.push_back({radius * s, radius * c, s, c});
  }
  TriangleMesh mesh;
  add_revolution(mesh, strip, segments);
  return mesh;
}

TriangleMesh tessellate_cylinder(double radius, double length, int segments) {
  check_segments(segments);
  check_length(radius, "cylinder radius");
  check_length(length, "cylinder length");
  const double h = 0.5 * length;
  TriangleMesh mesh;
  add_revolution(mesh, {{0.0, h, 0.0, 1.0}, {radius, h, 0.0, 1.0}}, segments);      // top cap
  add_revolution(mesh, {{radius, h, 1.0, 0.0}, {radius, -h, 1.0, 0.0}}, segments);  // side
  add_revolution(mesh, {{radius, -h, 0.0, -1.0}, {0.0, -h, 0.0, -1.0}}, segments);  // bottom
  return mesh;
}

TriangleMesh tessellate_capsule(double radius, double length, int segments) {
  check_segments(segments);
  check_length(radius, "capsule radius");
  check_length(length, "capsule length");
  const double h = 0.5 * length;
  const int rings = std::max(1, segments / 4);
  std::vector<ProfilePoint> strip = hemisphere(radius, h, 1.0, rings);
  std::vector<ProfilePoint> bottom = hemisphere(radius, -h, -1.0, rings);
  strip.insert(strip.end(), bottom.rbegin(), bottom.rend());  // equator down to the -z pole
  TriangleMesh mesh;
  add_revolution(mesh, strip, segments);
  return mesh;
}

TriangleMesh tessellate(const robot::Geometry& geometry, int segments) {
  switch (geometry.type) {
    case robot::GeometryType::Box:
      return tessellate_box(geometry.size);
    case robot::GeometryType::Sphere:
      return tessellate_sphere(geometry.radius, segments);
    case robot::GeometryType::Cylinder:
      return tessellate_cylinder(geometry.radius, geometry.length, segments);
    case robot::GeometryType::Capsule:
      return tessellate_capsule(geometry.radius, geometry.length, segments);
    case robot::GeometryType::Mesh:
      break;
  }
  throw InputError(fmt::format(
      "render: mesh geometry ('{}') cannot be tessellated; mesh files are not rendered yet",
      geometry.mesh_file));
}

}  // namespace somasim::render
