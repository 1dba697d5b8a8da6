#include "somasim/robot/robot_cache.hpp"

#include <map>
#include <mutex>

#include "somasim/error.hpp"
#include "somasim/robot/robot_loader.hpp"

namespace somasim::robot {

std::shared_ptr<const RobotModel> shared_robot_model(const std::filesystem::path& file) {
  static std::mutex mutex;
  static std::map<std::filesystem::path, std::weak_ptr<const RobotModel>> cache;
  std::error_code ec;
  const std::filesystem::path key = std::filesystem::weakly_canonical(file, ec);
  const std::scoped_lock lock(mutex);
  if (auto model = cache[ec ? file : key].lock()) return model;
  auto model = std::make_shared<const RobotModel>(load_robot_model(file));
  cache[ec ? file : key] = model;
  return model;
}

}  // namespace somasim::robot
