#include "somasim/interrupt.hpp"

#include <csignal>

namespace somasim {
namespace {
volatile std::sig_atomic_t g_interrupted = 0;

extern "C" void on_signal(int sig) {
  if (g_interrupted) {  // second signal: the user insists
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
  g_interrupted = 1;
}
}  // namespace

void install_interrupt_handler() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGHUP, on_signal);  // a closed terminal: flush like SIGTERM
}
void request_interrupt() {
  g_interrupted = 1;
}
bool interrupt_requested() {
  return g_interrupted != 0;
}
void clear_interrupt() {
  g_interrupted = 0;
}

}  // namespace somasim
