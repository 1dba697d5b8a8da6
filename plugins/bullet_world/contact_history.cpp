#include "contact_history.hpp"

#include <algorithm>

namespace somasim::bullet_world {

void record_contact_history(Contacts& contacts, double t, double horizon) {
  for (Contact& c : contacts.points) c.time_s = t;
  auto& recent = contacts.recent;
  const double oldest = t - std::max(horizon, 0.0);
  const auto keep_from = std::find_if(recent.begin(), recent.end(), [&](const Contact& c) {
    return c.time_s >= oldest - 1e-12 && (horizon > 0 || c.time_s >= t);
  });
  recent.erase(recent.begin(), keep_from);
  recent.insert(recent.end(), contacts.points.begin(), contacts.points.end());
}

}  // namespace somasim::bullet_world
