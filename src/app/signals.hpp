#pragma once
// SIGINT and SIGTERM as a request to stop, not an abrupt end: the handler only records the
// signal, and the render loop polls it between frames, unwinds, and lets the sinks delete their
// temporary files. A second signal of the same kind ends the process the default way, for a
// user who does not want to wait for that.
namespace discreel::app {

// Installs the handlers; call once, from main(), before rendering.
void install_stop_handlers();

// The signal that asked to stop (SIGINT, SIGTERM), or 0 while none has arrived.
// Makes writes past a file-size limit fail (EFBIG) instead of killing the process.
void ignore_file_size_signal();

int stop_signal();

}  // namespace discreel::app
