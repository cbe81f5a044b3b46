#include "progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace discreel::app {
namespace {

std::string clock_text(double seconds) {
    const long total = std::lround(std::max(0.0, seconds));
    char text[32];
    if (total >= 3600) {
        std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", total / 3600, total / 60 % 60,
                      total % 60);
    } else {
        std::snprintf(text, sizeof text, "%ld:%02ld", total / 60, total % 60);
    }
    return text;
}

}  // namespace

ProgressStyle pick_progress_style(bool quiet, ProgressRequest request, bool stderr_is_terminal) {
    if (quiet) return ProgressStyle::none;
    if (request == ProgressRequest::json) return ProgressStyle::json;
    if (stderr_is_terminal) return ProgressStyle::terminal;
    return request == ProgressRequest::lines ? ProgressStyle::lines : ProgressStyle::none;
}

std::string format_progress(int done, int total, double elapsed_seconds) {
    const double fps = elapsed_seconds > 0 ? done / elapsed_seconds : 0.0;
    const int percent = total > 0 ? static_cast<int>(100LL * done / total) : 100;
    char head[96];
    std::snprintf(head, sizeof head, "frame %d/%d (%d%%), %.1f fps, elapsed ", done, total,
                  percent, fps);
    std::string text = head + clock_text(elapsed_seconds) + ", left ";
    text += fps > 0 ? clock_text((total - done) / fps) : std::string("?");
    return text;
}

std::string format_progress_json(const char* stage, int done, int total, double elapsed_seconds) {
    const double fps = elapsed_seconds > 0 ? done / elapsed_seconds : 0.0;
    char text[192];
    std::snprintf(text, sizeof text,
                  "{\"stage\":\"%s\",\"frame\":%d,\"frames\":%d,\"fps\":%.2f,\"elapsed\":%.3f,"
                  "\"eta\":",
                  stage, done, total, fps, elapsed_seconds);
    std::string line = text;
    if (fps > 0) {
        std::snprintf(text, sizeof text, "%.3f}", (total - done) / fps);
        line += text;
    } else {
        line += "null}";
    }
    return line;
}

ProgressMeter::ProgressMeter(std::ostream& out, ProgressStyle style, int total_frames)
    : out_(out), style_(style), total_(total_frames) {}

void ProgressMeter::update(int done, double elapsed_seconds) {
    if (style_ == ProgressStyle::none) return;
    if (elapsed_seconds < next_due_ && done < total_) return;
    next_due_ = elapsed_seconds + (style_ == ProgressStyle::terminal ? 0.25 : 1.0);
    if (style_ == ProgressStyle::json) {
        out_ << format_progress_json("render", done, total_, elapsed_seconds) << '\n'
             << std::flush;
        return;
    }
    const std::string line = format_progress(done, total_, elapsed_seconds);
    if (style_ == ProgressStyle::terminal) {
        // "\x1b[K" clears what a longer previous line left to the right.
        out_ << '\r' << line << "\x1b[K" << std::flush;
        drawn_ = true;
    } else {
        out_ << line << '\n' << std::flush;
    }
}

void ProgressMeter::finish() {
    if (drawn_) out_ << "\r\x1b[K" << std::flush;
    drawn_ = false;
}

void ProgressMeter::done(double elapsed_seconds) {
    if (style_ != ProgressStyle::json) return;
    out_ << format_progress_json("done", total_, total_, elapsed_seconds) << '\n' << std::flush;
}

}  // namespace discreel::app
