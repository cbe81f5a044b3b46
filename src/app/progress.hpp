#pragma once
// The render's progress on standard error: frames done, frames per second, time elapsed and
// time left. On a terminal it is one line rewritten in place; elsewhere (a log, a CI job) it is
// off unless asked for, and then one plain line per update, with no carriage returns; or, for
// wrappers, one JSON object per line.
#include <ostream>
#include <string>

namespace discreel::app {

enum class ProgressStyle {
    none,       // nothing
    terminal,   // one line, redrawn with a carriage return, erased at the end
    lines,      // one line per update
    json,       // one JSON object per update and one at the end, for programs to read
};

// What --progress asked for: nothing, `--progress` (lines) or `--progress json`.
enum class ProgressRequest { none, lines, json };

// --quiet wins; --progress json is always JSON; --progress forces lines where stderr is no
// terminal; otherwise it follows whether stderr is a terminal.
ProgressStyle pick_progress_style(bool quiet, ProgressRequest request, bool stderr_is_terminal);

// "frame 300/600 (50%), 60.0 fps, elapsed 0:05, left 0:05"; time left is "?" until a frame
// is done. Times are m:ss, or h:mm:ss from an hour on.
std::string format_progress(int done, int total, double elapsed_seconds);

// {"stage":"render","frame":300,"frames":600,"fps":60.0,"elapsed":5.00,"eta":5.00}: frames
// done and in all, frames per second, seconds since the start and seconds left (null until a
// frame is done). `stage` is "render" while frames are made and "done" once the outputs are in
// place.
std::string format_progress_json(const char* stage, int done, int total, double elapsed_seconds);

class ProgressMeter {
public:
    ProgressMeter(std::ostream& out, ProgressStyle style, int total_frames);

    // `done` frames are encoded, `elapsed_seconds` after the start. Prints when an update is
    // due (terminal: every 0.25 s, lines: every second) and always when the last frame is done.
    void update(int done, double elapsed_seconds);

    // On a terminal, erases the line so the summary that follows starts clean.
    void finish();

    // JSON only: the final object, stage "done", once the outputs are in place.
    void done(double elapsed_seconds);

private:
    std::ostream& out_;
    ProgressStyle style_;
    int total_;
    double next_due_ = 0;   // seconds
    bool drawn_ = false;
};

}  // namespace discreel::app
