#pragma once
// The `recent` contact history of the world's contacts output (see somasim::Contacts).
#include "somasim/robot/ports.hpp"

namespace somasim::bullet_world {

/// Stamps the current points with `t` [s], appends them to `contacts.recent` and drops the
/// points older than `horizon` [s] (horizon <= 0 keeps only the current step's points).
void record_contact_history(Contacts& contacts, double t, double horizon);

}  // namespace somasim::bullet_world
