// Meshes of the primitives: sizes, vertices on the surface, outward counter-clockwise triangles
// and enclosed volumes against the analytic ones.
#include <gtest/gtest.h>

#include <cmath>

#include "somasim/error.hpp"
#include "somasim/render/tessellate.hpp"

using namespace somasim;
using namespace somasim::render;

namespace {

// Signed volume enclosed by the mesh (divergence theorem): positive when triangles are
// counter-clockwise seen from outside.
double enclosed_volume(const TriangleMesh& m) {
  double v = 0.0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const Eigen::Vector3d a = m.positions[m.indices[t]].cast<double>();
    const Eigen::Vector3d b = m.positions[m.indices[t + 1]].cast<double>();
    const Eigen::Vector3d c = m.positions[m.indices[t + 2]].cast<double>();
    v += a.dot(b.cross(c)) / 6.0;
  }
  return v;
}

// Every non-degenerate triangle's geometric normal points the way of its vertex normals.
void expect_consistent_normals(const TriangleMesh& m) {
  ASSERT_EQ(m.positions.size(), m.normals.size());
  ASSERT_EQ(m.indices.size() % 3, 0u);
  for (const Eigen::Vector3f& n : m.normals) EXPECT_NEAR(n.norm(), 1.0f, 1e-5f);
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const Eigen::Vector3f a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                          c = m.positions[m.indices[t + 2]];
    const Eigen::Vector3f g = (b - a).cross(c - a);
    if (g.norm() < 1e-9f) continue;
    const Eigen::Vector3f mean =
        m.normals[m.indices[t]] + m.normals[m.indices[t + 1]] + m.normals[m.indices[t + 2]];
    EXPECT_GT(g.dot(mean), 0.0f) << "triangle " << t / 3;
  }
}

}  // namespace

TEST(Tessellate, BoxHasSixFlatFacesAndItsFullExtents) {
  const TriangleMesh m = tessellate_box({0.2, 0.3, 0.4});
  EXPECT_EQ(m.positions.size(), 24u);
  EXPECT_EQ(m.triangle_count(), 12u);
  const Bounds b = bounds(m);
  EXPECT_TRUE(b.min.isApprox(Eigen::Vector3d(-0.1, -0.15, -0.2), 1e-6));
  EXPECT_TRUE(b.max.isApprox(Eigen::Vector3d(0.1, 0.15, 0.2), 1e-6));
  EXPECT_NEAR(enclosed_volume(m), 0.2 * 0.3 * 0.4, 1e-7);
  expect_consistent_normals(m);
}

TEST(Tessellate, SphereVerticesLieOnTheSurfaceAndTheVolumeConverges) {
  const double r = 0.05;
  const TriangleMesh m = tessellate_sphere(r, 64);
  for (const Eigen::Vector3f& p : m.positions) EXPECT_NEAR(p.norm(), r, 1e-7);
  expect_consistent_normals(m);
  const double v = enclosed_volume(m), exact = 4.0 / 3.0 * M_PI * r * r * r;
  EXPECT_LT(v, exact);  // inscribed
  EXPECT_GT(v, 0.99 * exact);
  const Bounds b = bounds(m);
  EXPECT_NEAR(b.max.z(), r, 1e-7);  // poles on z
  EXPECT_NEAR(b.min.z(), -r, 1e-7);
}

TEST(Tessellate, CylinderIsAlongZAndEnclosesThePolygonPrism) {
  const double r = 0.03, l = 0.2;
  const int n = 48;
  const TriangleMesh m = tessellate_cylinder(r, l, n);
  expect_consistent_normals(m);
  const Bounds b = bounds(m);
  EXPECT_NEAR(b.min.z(), -l / 2, 1e-7);
  EXPECT_NEAR(b.max.z(), l / 2, 1e-7);
  EXPECT_NEAR(b.max.x(), r, 1e-7);
  // A regular n-gon of circumradius r has area n r² sin(2π/n) / 2.
  EXPECT_NEAR(enclosed_volume(m), 0.5 * n * r * r * std::sin(2 * M_PI / n) * l, 1e-9);
}

TEST(Tessellate, CapsuleAddsHemispheresBeyondTheCylindricalPart) {
  const double r = 0.04, l = 0.1;
  const TriangleMesh m = tessellate_capsule(r, l, 64);
  expect_consistent_normals(m);
  const Bounds b = bounds(m);
  EXPECT_NEAR(b.max.z(), l / 2 + r, 1e-7);
  EXPECT_NEAR(b.min.z(), -l / 2 - r, 1e-7);
  const double exact = M_PI * r * r * l + 4.0 / 3.0 * M_PI * r * r * r;
  EXPECT_LT(enclosed_volume(m), exact);
  EXPECT_GT(enclosed_volume(m), 0.99 * exact);
}

TEST(Tessellate, RobotGeometryDispatchesOnTheShapeType) {
  robot::Geometry g;
  g.type = robot::GeometryType::Cylinder;
  g.radius = 0.02;
  g.length = 0.3;
  g.origin.translation() = Eigen::Vector3d(1, 2, 3);  // not applied: the caller poses the mesh
  const Bounds b = bounds(tessellate(g, 16));
  EXPECT_NEAR(b.max.z(), 0.15, 1e-7);
  EXPECT_NEAR(b.min.z(), -0.15, 1e-7);
  g.type = robot::GeometryType::Box;
  g.size = Eigen::Vector3d(0.1, 0.2, 0.3);
  EXPECT_NEAR(bounds(tessellate(g, 16)).max.y(), 0.1, 1e-7);
  g.type = robot::GeometryType::Mesh;
  g.mesh_file = "/tmp/hand.stl";
  try {
    tessellate(g, 16);
    FAIL() << "mesh geometry accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/tmp/hand.stl"), std::string::npos) << e.what();
  }
}

TEST(Tessellate, RejectsTooFewSegmentsAndNegativeSizes) {
  EXPECT_THROW(tessellate_sphere(0.1, 2), InputError);
  EXPECT_THROW(tessellate_cylinder(-0.1, 0.2, 16), InputError);
  EXPECT_THROW(tessellate_box({0.1, NAN, 0.1}), InputError);
  EXPECT_NO_THROW(tessellate_box({0.0, 0.0, 0.0}));  // degenerate but valid
}
