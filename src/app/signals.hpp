#pragma once
// Every catchable signal whose default would end the process (SIGINT, SIGTERM, SIGHUP, SIGQUIT,
// SIGPIPE, SIGALRM, SIGUSR1, the real-time signals, ...) is a request to stop, not an abrupt
// end: the handler only records the signal, and the commands poll it between physics steps,
// unwind, and let the outputs delete their temporary files. A second such signal ends the
// process at once, with that signal's default action, after deleting the temporary files
// itself; while outputs are being committed (commit_in_progress()) it waits for the commit to
// finish. A run still going 10 s after the first signal (blocked in a call no signal
// interrupts) is ended the same way, with the first signal's default action.
// SIGPIPE is only ever recorded: the write that raised it fails with EPIPE and the run stops.
// Only SIGKILL (and a crash in the middle of a commit) can leave a temporary file behind.
namespace discreel::app {

// Installs the handlers; call once, from main(), before any work or thread starts.
void install_stop_handlers();

// Makes writes past a file-size limit fail (EFBIG) instead of killing the process.
void ignore_file_size_signal();

// The signal that asked to stop, or 0 while none has arrived.
int stop_signal();

}  // namespace discreel::app
