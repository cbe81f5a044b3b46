#pragma once
// Maps video frames onto physics steps. Frame n shows the state at t = n / fps; physics runs at
// its own fixed rate, so the frame shows the step nearest to that time. Integer arithmetic keeps
// the mapping exact: the same scene at 30 and 60 fps lands on the same steps where times agree.
#include <cstdint>

namespace discreel::job {

struct Timeline {
    int fps = 60;           // video frames per second
    int rate = 480;         // physics steps per second
    int frame_count = 0;    // frames in the clip

    // Index of the physics step whose state frame n shows: round(n * rate / fps).
    std::int64_t step_for_frame(int frame) const;
    double time_of_frame(int frame) const { return static_cast<double>(frame) / fps; }
};

}  // namespace discreel::job
