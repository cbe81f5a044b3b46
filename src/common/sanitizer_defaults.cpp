// Compiled into every executable of a DISCREEL_SANITIZE build (see src/common/CMakeLists.txt).
// The sanitizer runtimes ask for these hooks at start-up, so the settings hold wherever the
// binary runs: under ctest, in a child process of a test, or by hand.

// Mesa keeps its process-wide state (the gallium screen, LLVM's JIT) alive until exit by
// design; those allocations are not ours to free. Nothing else is suppressed.
extern "C" const char* __lsan_default_suppressions() {
    return "leak:libOSMesa.so\n";
}

// The suppression statistics would otherwise be printed to stderr at exit, and the CLI's
// tests compare stderr word for word.
extern "C" const char* __lsan_default_options() {
    return "print_suppressions=0";
}

extern "C" const char* __ubsan_default_options() {
    return "print_stacktrace=1:halt_on_error=1";
}
