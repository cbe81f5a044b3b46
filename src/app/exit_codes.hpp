#pragma once

namespace discreel::app {

// The CLI's exit codes, as documented in the README and docs/cli.md.
enum ExitCode : int {
    exit_ok = 0,
    exit_golden_mismatch = 1,
    exit_bad_input = 2,      // bad command line or scene
    exit_runtime_failure = 3, // I/O, GL or encoder failure
    // Stopped by a signal: 128 + the signal's number, as shells report it (SIGINT 130,
    // SIGTERM 143).
    exit_interrupted_base = 128
};

}  // namespace discreel::app
