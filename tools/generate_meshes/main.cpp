// generate_meshes: writes somasim's own robot meshes (Wavefront OBJ) from primitives, so that no
// third-party mesh is needed. The iCub description uses them as visual geometry of the forearm
// covers (an oval section, as on the real robot) while collisions use primitives.
//
//   generate_meshes OUT_DIR
//
// Output is deterministic (same numbers, same text); the committed files under
// assets/robots/meshes/ are this program's output.
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace {

struct Mesh {
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<int, 3>> faces;  // 0-based, counter-clockwise seen from outside
};

// A closed elliptic cylinder: semi-axes a (x) and b (z), from y = y0 to y = y1, `segments`
// around. The forearm link frame of the iCub has the forearm along -y.
Mesh elliptic_cylinder(double a, double b, double y0, double y1, int segments) {
  Mesh m;
  for (double y : {y0, y1})
    for (int i = 0; i < segments; ++i) {
      const double t = 2.0 * M_PI * i / segments;
      m.vertices.push_back({a * std::cos(t), y, b * std::sin(t)});
    }
  const int c0 = static_cast<int>(m.vertices.size());
  m.vertices.push_back({0, y0, 0});
  m.vertices.push_back({0, y1, 0});
  for (int i = 0; i < segments; ++i) {
    const int j = (i + 1) % segments;
    // side quad as two triangles; caps as fans (orientation: outward for y0 > y1)
    m.faces.push_back({i, j, segments + j});
    m.faces.push_back({i, segments + j, segments + i});
    m.faces.push_back({c0, j, i});
    m.faces.push_back({c0 + 1, segments + i, segments + j});
  }
  return m;
}

void write_obj(const Mesh& m, const std::filesystem::path& file, const std::string& what) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file.string());
  out << "# " << what << "\n# written by somasim tools/generate_meshes (units: m, link frame)\n";
  char line[128];
  for (const auto& v : m.vertices) {
    std::snprintf(line, sizeof line, "v %.6f %.6f %.6f\n", v[0], v[1], v[2]);
    out << line;
  }
  for (const auto& f : m.faces)
    out << "f " << f[0] + 1 << " " << f[1] + 1 << " " << f[2] + 1 << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: generate_meshes OUT_DIR\n";
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  // Real iCub forearm cover: about 0.080 x 0.065 m in section, 0.14 m long.
  write_obj(elliptic_cylinder(0.040, 0.0325, 0.0, -0.14, 48), dir / "forearm_cover.obj",
            "iCub forearm cover: elliptic cylinder 0.080 x 0.065 m, 0.14 m along -y");
  std::cout << "wrote " << (dir / "forearm_cover.obj").string() << "\n";
  return 0;
}
