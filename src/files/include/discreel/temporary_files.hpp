#pragma once
// The temporary files this process has open (OutputFile registers each one), so that a crash
// can delete them: a clip that dies half-written leaves nothing behind, not even a hidden
// `.NAME.tmp-XXXXXX`.
#include <cstddef>
#include <string>

namespace discreel {

// Registers `path` until unregister_temporary_file(handle); returns the handle.
std::size_t register_temporary_file(const std::string& path);
void unregister_temporary_file(std::size_t handle);

// Installs handlers for SIGSEGV, SIGBUS, SIGILL, SIGFPE and SIGABRT that delete every
// registered file and then let the signal take its course (the previous handler, such as a
// sanitizer's, or the default: the process dies with that signal). For programs, not
// libraries: call it once from main(), before any thread starts.
void delete_temporary_files_on_crash();

// Deletes every registered file now. Async-signal-safe: for a handler that is about to end the
// process (a second Ctrl-C) and must not leave temporary files behind.
void delete_temporary_files_now();

}  // namespace discreel
