#pragma once
// libav reports the detail of a failure ("width not divisible by 2") only through its log,
// and by default prints it to stderr. Library code must not print, so the encode module routes
// libav's log into a per-thread buffer and quotes the latest error line in its own messages.
#include <string>

namespace discreel::encode {

// Installs the capturing log callback (once per process) and clears this thread's buffer.
void begin_libav_call();

// "<av_strerror text>", followed by libav's latest logged error line on this thread, if any.
std::string libav_reason(int error_code);

}  // namespace discreel::encode
