#pragma once
// What distinguishes one video output from another, as data: the muxer, the encoder, the pixel
// format and colour tags, and the options each takes. The VideoSink is written once against
// this; each container is a builder here and one row in open_sink's table, not a further sink.
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
    // What the encoder is fed. PAL8 means a palette built by PaletteConverter; anything else is
    // converted from RGBA by libswscale.
    AVPixelFormat pixel_format = AV_PIX_FMT_YUV420P;
    // YUV matrix for the RGBA conversion and the tags written on the stream, so players decode
    // with the matrix the pixels were made with.
    AVColorSpace colorspace = AVCOL_SPC_BT709;
    AVColorPrimaries primaries = AVCOL_PRI_BT709;
    AVColorTransferCharacteristic transfer = AVCOL_TRC_BT709;
    AVColorRange range = AVCOL_RANGE_MPEG;              // limited ("tv") range
    int threads = 1;                                    // encoder threads, pinned
    int gop_size = -1;                                  // keyframe interval; -1: the encoder's
    OptionList encoder_options;                         // the encoder's options
    OptionList muxer_options;                           // the muxer's private options
};

// Each builder checks the SinkDef's encoder settings for its container and says which one is
// wrong (without the path; open_sink adds it).
//   .mp4: H.264 (libx264), index first (faststart).
//   .mkv and "-": H.264 by default, VP9 with codec "vp9", FFV1 (bgr0) with lossless or "ffv1".
//   .webm: VP9 (libvpx-vp9).
//   .gif: GIF with a palette from the key colours and the first frame.
Expected<VideoFormat> mp4_format(const SinkDef& def);
// "-": Matroska, or fragmented MP4 with SinkDef::stream_container "mp4".
Expected<VideoFormat> stream_format(const SinkDef& def);
Expected<VideoFormat> mkv_format(const SinkDef& def);
Expected<VideoFormat> webm_format(const SinkDef& def);
Expected<VideoFormat> gif_format(const SinkDef& def);

// The container of a video file path (.mp4, .mkv, .webm): its muxer and muxer options, for
// joining segments; the codec fields are the format's defaults and unused.
Expected<VideoFormat> container_of(const std::string& path);

// "<setting> does not apply to <target>" when the SinkDef sets any of crf, preset, codec,
// pixel format or lossless: for outputs that take none of them (GIF, PNG).
Status reject_encoder_settings(const SinkDef& def, const std::string& target);

}  // namespace discreel::encode
