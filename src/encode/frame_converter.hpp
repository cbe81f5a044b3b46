#pragma once
// RGBA8 frames into whatever the encoder is fed: libswscale for YUV and RGB formats
// (RgbaConverter), a palette for GIF (PaletteConverter).
#include <memory>

#include "av_handles.hpp"
#include "discreel/expected.hpp"
#include "discreel/image.hpp"

namespace discreel::encode {

struct SinkDef;
struct VideoFormat;

class FrameConverter {
public:
    virtual ~FrameConverter() = default;
    // Fills `output` (allocated with the sink's size and pixel format, and writable).
    virtual void convert(const ImageView& frame, AVFrame& output) = 0;
};

Expected<std::unique_ptr<FrameConverter>> make_frame_converter(const SinkDef& def,
                                                               const VideoFormat& format);

}  // namespace discreel::encode
