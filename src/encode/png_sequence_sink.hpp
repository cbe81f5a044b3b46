#pragma once
// Every frame as its own PNG, named by a FramePattern (frame_%04d.png), numbered from 0. The
// files are the same bytes as PNG stills of the same frames. Each frame is encoded and written
// to a temporary file as it arrives (memory stays flat); finish() renames them all into place.
// A sink destroyed before that deletes its temporary files, and a rename that fails in finish()
// removes the files renamed before it, so a failed run leaves no partial set behind.
#include <memory>

#include "discreel/encode.hpp"
#include "frame_pattern.hpp"

namespace discreel::encode {

Expected<std::unique_ptr<Sink>> open_png_sequence_sink(const SinkDef& def, FramePattern pattern);

}  // namespace discreel::encode
