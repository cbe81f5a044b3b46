#include "frame_converter.hpp"

#include "bt709_converter.hpp"
#include "palette_converter.hpp"
#include "rgba_converter.hpp"
#include "video_format.hpp"

namespace discreel::encode {

Expected<std::unique_ptr<FrameConverter>> make_frame_converter(const SinkDef& def,
                                                               const VideoFormat& format) {
    if (format.pixel_format == AV_PIX_FMT_PAL8) {
        return std::unique_ptr<FrameConverter>(
            std::make_unique<PaletteConverter>(def.key_colours));
    }
    const bool bt709_limited =
        format.colorspace == AVCOL_SPC_BT709 && format.range == AVCOL_RANGE_MPEG;
    if (bt709_limited && (format.pixel_format == AV_PIX_FMT_YUV420P ||
                          format.pixel_format == AV_PIX_FMT_YUV444P)) {
        return std::unique_ptr<FrameConverter>(std::make_unique<Bt709Converter>(
            format.pixel_format == AV_PIX_FMT_YUV420P));
    }
    auto converter = RgbaConverter::create(def.width, def.height, format.pixel_format,
                                           format.colorspace, format.range);
    if (!converter) {
        return converter.error();
    }
    return std::unique_ptr<FrameConverter>(
        std::make_unique<RgbaConverter>(std::move(*converter)));
}

}  // namespace discreel::encode
