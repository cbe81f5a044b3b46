#pragma once
// A single frame as a PNG file: the sink behind `-o frame.png` and `--frame N`. It takes
// exactly one frame; a second one, or finishing without one, is an error rather than a
// silently dropped or empty file.
#include <memory>

#include "discreel/encode.hpp"

namespace discreel::encode {

Expected<std::unique_ptr<Sink>> open_png_still_sink(const SinkDef& def);

}  // namespace discreel::encode
