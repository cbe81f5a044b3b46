#pragma once
// job::render of a video file: segments rendered in parallel and joined by stream copy.
#include <string>

#include "discreel/job.hpp"

namespace discreel::job {

// Frame slots a pipeline of this frame size keeps in flight.
int slots_for(int width, int height);

// Renders `range` of def.plan.scene in segments into def.plan.sink.path (or only
// def.plan.segment), with `sink` as the settings of every segment (size, rate and colours filled in) and `format` the
// output's ("mp4", "mkv", "webm").
Expected<RenderSummary> render_segments(const RenderDef& def, FrameRange range,
                                        const encode::SinkDef& sink, const std::string& format);

}  // namespace discreel::job
