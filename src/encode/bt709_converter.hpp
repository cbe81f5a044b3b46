#pragma once
// RGBA8 frames into BT.709 limited-range yuv420p or yuv444p, the pixel formats every H.264 and
// VP9 clip uses, without libswscale: integer arithmetic with 16 fractional bits that the
// compiler vectorises, much faster than libswscale's bit-exact path (bench/yuv_conversion_bench,
// docs/performance.md) and the same bytes on every CPU. yuv420p chroma is the average
// of each 2x2 block (centre-sited, as libswscale places it). Alpha is ignored: frames are
// opaque. Every other format and tagging goes through RgbaConverter.
#include "frame_converter.hpp"

namespace discreel::encode {

class Bt709Converter final : public FrameConverter {
public:
    // true: yuv420p (chroma halved both ways); false: yuv444p.
    explicit Bt709Converter(bool subsampled_chroma) : subsampled_chroma_(subsampled_chroma) {}

    // Fills `output` (frame.width x frame.height, yuv420p or yuv444p as constructed, writable).
    // yuv420p needs an even width and height, as the sink already requires.
    void convert(const ImageView& frame, AVFrame& output) override;

private:
    bool subsampled_chroma_;
};

}  // namespace discreel::encode
