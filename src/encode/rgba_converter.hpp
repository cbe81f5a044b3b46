#pragma once
// RGBA8 frames into the encoder's pixel format with libswscale, using the YUV matrix and range
// the stream is tagged with. libswscale's default is BT.601 whatever the tags say, which turns
// pure red into (255, 23, 0) in an HD player; the matrix is therefore set explicitly.
#include "av_handles.hpp"
#include "frame_converter.hpp"
#include "discreel/expected.hpp"
#include "discreel/image.hpp"

namespace discreel::encode {

class RgbaConverter final : public FrameConverter {
public:
    static Expected<RgbaConverter> create(int width, int height, AVPixelFormat output_format,
                                          AVColorSpace colorspace, AVColorRange range);

    // Fills `output` (allocated with the size and format given to create, and writable).
    void convert(const ImageView& frame, AVFrame& output) override;

private:
    explicit RgbaConverter(SwsContextPtr context) : context_(std::move(context)) {}
    SwsContextPtr context_;
};

}  // namespace discreel::encode
