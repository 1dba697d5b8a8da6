#pragma once
/// @file
/// The three error tiers of somasim.
///
/// - A bug in somasim itself: SOMASIM_CHECK aborts with file and line.
/// - Bad input (YAML, assets, learned-state files, plugin libraries): InputError, thrown only
///   while loading or configuring; the CLI prints its message as one clear line and exits 2.
/// - Trouble during a run (NaN, physics blow-up): RunError, which stops the run cleanly with
///   all outputs flushed; the CLI exits 3.
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace somasim {

/// Bad input from the user: the message is complete and says what was expected.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A failure detected while a run is in progress (after configuration succeeded).
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

[[noreturn]] inline void check_failed(const char* expr, const char* file, int line,
                                      const char* msg) {
  std::fprintf(stderr, "somasim internal error at %s:%d: check '%s' failed%s%s\n", file, line, expr,
               msg[0] ? ": " : "", msg);
  std::abort();
}

}  // namespace somasim

/// Always-on internal consistency check (not for user input: use InputError for that).
#define SOMASIM_CHECK(expr, msg) \
  ((expr) ? (void)0 : ::somasim::check_failed(#expr, __FILE__, __LINE__, msg))
