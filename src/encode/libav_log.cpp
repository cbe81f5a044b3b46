#include "libav_log.hpp"

#include <cstdarg>
#include <mutex>

#include "av_handles.hpp"

extern "C" {
#include <libavutil/log.h>
}

namespace discreel::encode {
namespace {

thread_local std::string latest_error_line;

void capture_log_line(void* context, int level, const char* format, va_list arguments) {
    if (level > AV_LOG_ERROR) {
        return;   // warnings and chatter (x264's banner) are dropped, never printed
    }
    char line[1024];
    int print_prefix = 0;
    av_log_format_line2(context, level, format, arguments, line, sizeof line, &print_prefix);
    std::string text(line);
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) {
        text.pop_back();
    }
    if (text.empty()) {
        return;
    }
    // libav's own prefix carries the context's address, which would make the same failure
    // read differently from run to run; the component's name is enough.
    const AVClass* component =
        context != nullptr ? *static_cast<const AVClass* const*>(context) : nullptr;
    latest_error_line =
        component != nullptr ? std::string(component->item_name(context)) + ": " + text : text;
}

}  // namespace

void begin_libav_call() {
    static std::once_flag installed;
    std::call_once(installed, [] { av_log_set_callback(capture_log_line); });
    latest_error_line.clear();
}

std::string libav_reason(int error_code) {
    std::string reason = av_error_text(error_code);
    if (!latest_error_line.empty()) {
        reason += " (" + latest_error_line + ")";
    }
    return reason;
}

}  // namespace discreel::encode
