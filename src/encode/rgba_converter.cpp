#include "rgba_converter.hpp"

#include <string>

extern "C" {
#include <libavutil/pixdesc.h>
}

namespace discreel::encode {

Expected<RgbaConverter> RgbaConverter::create(int width, int height, AVPixelFormat output_format,
                                              AVColorSpace colorspace, AVColorRange range) {
    // Bilinear is only used for the chroma downsampling (the size does not change).
    // ACCURATE_RND and BITEXACT keep the output independent of the CPU's SIMD path, which the
    // byte-identical-output promise needs across machines.
    SwsContextPtr context(sws_getContext(width, height, AV_PIX_FMT_RGBA, width, height,
                                         output_format,
                                         SWS_BILINEAR | SWS_ACCURATE_RND | SWS_BITEXACT, nullptr,
                                         nullptr, nullptr));
    if (!context) {
        return Error{std::string("cannot convert RGBA to ") + av_get_pix_fmt_name(output_format)};
    }
    const bool output_is_yuv =
        !(av_pix_fmt_desc_get(output_format)->flags & AV_PIX_FMT_FLAG_RGB);
    if (output_is_yuv) {
        // Source: RGB, full range (its matrix argument is unused for RGB input). Destination:
        // the tagged matrix and range.
        const int* matrix = sws_getCoefficients(colorspace);
        const int full_range_output = range == AVCOL_RANGE_JPEG ? 1 : 0;
        sws_setColorspaceDetails(context.get(), sws_getCoefficients(SWS_CS_DEFAULT), 1, matrix,
                                 full_range_output, 0, 1 << 16, 1 << 16);
    }
    return RgbaConverter(std::move(context));
}

void RgbaConverter::convert(const ImageView& frame, AVFrame& output) {
    const std::uint8_t* source_planes[1] = {frame.rgba.data()};
    const int source_strides[1] = {4 * frame.width};
    sws_scale(context_.get(), source_planes, source_strides, 0, frame.height, output.data,
              output.linesize);
}

}  // namespace discreel::encode
