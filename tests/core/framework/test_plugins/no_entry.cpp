// A shared library that is not a somasim plugin (no entry point): the loader must reject it
// without loading it. Its constructor leaves a marker file (named by the environment variable
// SOMASIM_TEST_CONSTRUCTOR_MARKER) if it is ever loaded, so tests can see that it was not.
#include <cstdio>
#include <cstdlib>

namespace {

__attribute__((constructor)) void leave_marker() {
  if (const char* marker = std::getenv("SOMASIM_TEST_CONSTRUCTOR_MARKER"))
    if (std::FILE* f = std::fopen(marker, "w")) std::fclose(f);
}

}  // namespace

extern "C" int somasim_test_not_a_plugin() {
  return 42;
}
