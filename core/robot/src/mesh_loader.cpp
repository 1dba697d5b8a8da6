#include "somasim/robot/mesh_loader.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>

#include "somasim/error.hpp"

namespace somasim::robot {

TriangleMesh load_triangle_mesh(const std::filesystem::path& file, const Eigen::Vector3d& scale) {
  Assimp::Importer importer;
  const aiScene* scene =
      importer.ReadFile(file.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                           aiProcess_PreTransformVertices);
  const std::string where = "mesh file '" + file.string() + "': ";
  if (!scene) throw InputError(where + "cannot be read (" + importer.GetErrorString() + ")");
  TriangleMesh mesh;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* am = scene->mMeshes[m];
    const int base = static_cast<int>(mesh.vertices.size());
    for (unsigned v = 0; v < am->mNumVertices; ++v) {
      const aiVector3D& p = am->mVertices[v];
      mesh.vertices.emplace_back(p.x * scale.x(), p.y * scale.y(), p.z * scale.z());
      if (!mesh.vertices.back().allFinite())
        throw InputError(where + "vertex " + std::to_string(v) + " of mesh " + std::to_string(m) +
                         " is not finite (" + std::to_string(p.x) + ", " + std::to_string(p.y) +
                         ", " + std::to_string(p.z) + ")");
    }
    for (unsigned f = 0; f < am->mNumFaces; ++f) {
      const aiFace& face = am->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines carry no surface
      mesh.triangles.push_back({base + static_cast<int>(face.mIndices[0]),
                                base + static_cast<int>(face.mIndices[1]),
                                base + static_cast<int>(face.mIndices[2])});
    }
  }
  if (mesh.triangles.empty()) throw InputError(where + "holds no triangles");
  return mesh;
}

}  // namespace somasim::robot
