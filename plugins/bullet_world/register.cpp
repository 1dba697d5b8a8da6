// Physics world (Bullet).
#include "bullet_world.hpp"

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::bullet_world::BulletWorld>();
}
