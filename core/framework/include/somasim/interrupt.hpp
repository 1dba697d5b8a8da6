#pragma once
/// @file
/// Cooperative interruption (SIGINT): the scheduler polls the flag once per tick and ends the
/// run cleanly, flushing every output, with status "interrupted".
namespace somasim {

/// Installs a SIGINT/SIGTERM handler that sets the flag (a second SIGINT kills at once).
void install_interrupt_handler();
/// Sets the flag (signal-safe).
void request_interrupt();
bool interrupt_requested();
void clear_interrupt();

}  // namespace somasim
