#pragma once
// The render's progress on standard error: frames done, frames per second, time elapsed and
// time left. On a terminal it is one line rewritten in place; elsewhere (a log, a CI job) it is
// off unless asked for, and then one plain line per update, with no carriage returns.
#include <ostream>
#include <string>

namespace discreel::app {

enum class ProgressStyle {
    none,       // nothing
    terminal,   // one line, redrawn with a carriage return, erased at the end
    lines,      // one line per update
};

// --quiet wins; --progress forces it; otherwise it follows whether stderr is a terminal.
ProgressStyle pick_progress_style(bool quiet, bool forced, bool stderr_is_terminal);

// "frame 300/600 (50%), 60.0 fps, elapsed 0:05, left 0:05"; time left is "?" until a frame
// is done. Times are m:ss, or h:mm:ss from an hour on.
std::string format_progress(int done, int total, double elapsed_seconds);

class ProgressMeter {
public:
    ProgressMeter(std::ostream& out, ProgressStyle style, int total_frames);

    // `done` frames are encoded, `elapsed_seconds` after the start. Prints when an update is
    // due (terminal: every 0.25 s, lines: every second) and always when the last frame is done.
    void update(int done, double elapsed_seconds);

    // On a terminal, erases the line so the summary that follows starts clean.
    void finish();

private:
    std::ostream& out_;
    ProgressStyle style_;
    int total_;
    double next_due_ = 0;   // seconds
    bool drawn_ = false;
};

}  // namespace discreel::app
