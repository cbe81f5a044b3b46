#pragma once
// Every frame as its own PNG, named by a FramePattern (frame_%04d.png), numbered from 0. The
// files are the same bytes as PNG stills of the same frames. Each frame is encoded and written
// to a temporary file as it arrives (memory stays flat); the commit renames them all into place
// together: a rename that fails puts back the frames already replaced, so a failed run leaves
// the old sequence exactly as it was.
#include <memory>

#include "discreel/encode.hpp"
#include "frame_pattern.hpp"

namespace discreel::encode {

Expected<std::unique_ptr<Sink>> open_png_sequence_sink(const SinkDef& def, FramePattern pattern);

}  // namespace discreel::encode
