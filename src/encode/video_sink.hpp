#pragma once
// The one video sink: RGBA frames -> libswscale -> any libavcodec encoder -> any libavformat
// muxer, as described by a VideoFormat. Written after FFmpeg's doc/examples/mux.c.
#include <memory>

#include "discreel/encode.hpp"
#include "video_format.hpp"

namespace discreel::encode {

Expected<std::unique_ptr<Sink>> open_video_sink(const SinkDef& def, const VideoFormat& format);

}  // namespace discreel::encode
