#pragma once
/// @file
/// Scene files: objects placed in the world at t = 0 (bullet_world's `scene` parameter).
///
/// ```yaml
/// objects:
///   - name: ball                 # default object<N> (N: position in the list)
///     shape: sphere              # sphere | box | cylinder | mesh
///     radius: 0.03               # sphere, cylinder [m]
///     size: [0.1, 0.1, 0.05]     # box: full extents [m]
///     length: 0.1                # cylinder: full height along its z [m]
///     file: cup.obj              # mesh: relative to the scene file (OBJ/STL/DAE via assimp)
///     scale: 1                   # mesh: s or [sx, sy, sz]
///     motion: dynamic            # static | dynamic | kinematic | guided (ports.hpp)
///     mass: 0.1                  # dynamic [kg]
///     xyz: [0, 0, 0.5]           # pose in the root frame [m]
///     rpy_deg: [0, 0, 0]         # R = Rz(yaw)·Ry(pitch)·Rx(roll) [deg]
///     velocity: [0, 0, 0]        # initial (dynamic) or of the path [m/s]
///     remove_after_s: 0          # > 0: removed after this long [s]
/// ```
/// Errors name file:line:column, the object and the key; all errors are reported together.
#include <filesystem>
#include <vector>

#include "somasim/robot/ports.hpp"
#include "somasim/source_location.hpp"

namespace somasim::robot {

struct SceneObject {
  ObjectSpawn spawn;
  SourceLocation where;  ///< the object's entry in the file
};

/// InputError on any problem (unknown keys/shapes/motions, bad sizes, missing mesh files).
std::vector<SceneObject> load_scene(const std::filesystem::path& file);

}  // namespace somasim::robot
