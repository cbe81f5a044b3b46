#pragma once
// What distinguishes one video output from another, as data: the muxer, the encoder, the pixel
// format and colour tags, and the options each takes. The VideoSink is written once against
// this; MKV, WebM/VP9 or GIF are further VideoFormat builders, not further sinks.
#include <string>
#include <utility>
#include <vector>

extern "C" {
#include <libavutil/pixfmt.h>
}

#include "discreel/encode.hpp"
#include "discreel/expected.hpp"

namespace discreel::encode {

using OptionList = std::vector<std::pair<std::string, std::string>>;

struct VideoFormat {
    std::string muxer;                                  // libavformat short name, e.g. "mp4"
    std::string encoder;                                // libavcodec encoder name, e.g. "libx264"
    AVPixelFormat pixel_format = AV_PIX_FMT_YUV420P;    // what the encoder is fed
    // YUV matrix for the RGBA conversion and the tags written on the stream, so players decode
    // with the matrix the pixels were made with.
    AVColorSpace colorspace = AVCOL_SPC_BT709;
    AVColorPrimaries primaries = AVCOL_PRI_BT709;
    AVColorTransferCharacteristic transfer = AVCOL_TRC_BT709;
    AVColorRange range = AVCOL_RANGE_MPEG;              // limited ("tv") range
    int threads = 1;                                    // encoder threads, pinned
    OptionList encoder_options;                         // the encoder's private options
    OptionList muxer_options;                           // the muxer's private options
};

// H.264 (libx264) in MP4, yuv420p BT.709 limited range, index first (faststart). Checks the
// SinkDef's encoder settings and says which one is wrong.
Expected<VideoFormat> mp4_h264_format(const SinkDef& def);

}  // namespace discreel::encode
