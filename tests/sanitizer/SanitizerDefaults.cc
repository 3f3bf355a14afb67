// Linked into every target of the sanitizer build (-DANODE_SANITIZE=ON): the options the runtime
// uses when the environment sets none, so ctest, sus and the tests all fail on the first report.
// The suppressions are leaks inside libOSMesa (its current-context state, allocated by
// OSMesaMakeCurrent and kept after OSMesaDestroyContext) and inside Open MPI's own libraries and
// plugins (state they keep past MPI_Finalize); our own allocations are all checked.
extern "C" {

// Shared objects stay loaded in this build: Open MPI unloads its plugins (mca_*.so) at
// MPI_Finalize, and a leak report naming an unloaded plugin shows "<unknown module>", which no
// suppression can match. Only the sanitizer build has this definition.
int dlclose(void*) {
  return 0;
}

const char* __asan_default_options() {
  return "halt_on_error=1:detect_leaks=1:strict_string_checks=1";
}

const char* __ubsan_default_options() {
  return "halt_on_error=1:print_stacktrace=1";
}

const char* __lsan_default_suppressions() {
  return "leak:libOSMesa.so\n"
         "leak:libmpi.so\n"
         "leak:libopen-pal.so\n"
         "leak:libopen-rte.so\n"
         "leak:libpmix.so\n"
         "leak:libhwloc.so\n"
         "leak:libevent\n"
         "leak:/openmpi/\n"
         // Strings Open MPI formats with asprintf, whose stack ends inside libc (no frame
         // pointers there); this code calls no asprintf or vasprintf.
         "leak:__vasprintf_internal\n";
}

}  // extern "C"
