// A shared library that is not a somasim plugin (no entry point): the loader must reject it.
extern "C" int somasim_test_not_a_plugin() {
  return 42;
}
