// Linked into every target of the sanitizer build (-DANODE_SANITIZE=ON): the options the runtime
// uses when the environment sets none, so ctest, sus and the tests all fail on the first report.
// The one suppression is a leak inside libOSMesa (its current-context state, allocated by
// OSMesaMakeCurrent and kept after OSMesaDestroyContext); our own allocations are all checked.
extern "C" {

const char* __asan_default_options() {
  return "halt_on_error=1:detect_leaks=1:strict_string_checks=1";
}

const char* __ubsan_default_options() {
  return "halt_on_error=1:print_stacktrace=1";
}

const char* __lsan_default_suppressions() {
  return "leak:libOSMesa.so\n";
}

}  // extern "C"
