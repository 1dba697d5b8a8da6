// Meshes read with assimp: sub-meshes merged, scaled, and bad files reported with the file.
#include <gtest/gtest.h>

#include <fstream>

#include "somasim/error.hpp"
#include "somasim/robot/mesh_loader.hpp"

namespace somasim::robot {
namespace {

std::filesystem::path write_obj(const std::string& name, const std::string& text) {
  const auto file = std::filesystem::temp_directory_path() / name;
  std::ofstream(file) << text;
  return file;
}

TEST(MeshLoader, ReadsAndScalesATriangle) {
  const auto file = write_obj("somasim_tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const TriangleMesh m = load_triangle_mesh(file, Eigen::Vector3d(2, 3, 4));
  ASSERT_EQ(m.vertices.size(), 3u);
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.vertices[1], Eigen::Vector3d(2, 0, 0));
  EXPECT_EQ(m.vertices[2], Eigen::Vector3d(0, 3, 0));
  std::filesystem::remove(file);
}

TEST(MeshLoader, ANonFiniteVertexIsAnInputErrorNamingTheVertex) {
  const auto file = write_obj("somasim_nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  try {
    load_triangle_mesh(file, Eigen::Vector3d::Ones());
    FAIL() << "accepted";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("mesh file '" + file.string() + "': ", 0), 0u) << msg;
    EXPECT_NE(msg.find("is not finite"), std::string::npos) << msg;
  }
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace somasim::robot
