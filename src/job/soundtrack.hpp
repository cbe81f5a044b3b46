#pragma once
// job::render of a .wav: the scene's soundtrack alone.
#include "discreel/job.hpp"

namespace discreel::job {

Expected<RenderSummary> render_soundtrack(const RenderDef& def, FrameRange range);

}  // namespace discreel::job
