#pragma once
/// @file
/// Triangle meshes read with assimp (OBJ, STL, DAE, ...), all sub-meshes merged, node
/// transforms applied, scaled per axis.
#include <array>
#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace somasim::robot {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;      ///< [m], in the mesh frame
  std::vector<std::array<int, 3>> triangles;  ///< vertex indices
};

/// InputError "mesh file 'F': <why>" when the file cannot be read or holds no triangles.
TriangleMesh load_triangle_mesh(const std::filesystem::path& file, const Eigen::Vector3d& scale);

}  // namespace somasim::robot
