#include "frame_converter.hpp"

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
    auto converter = RgbaConverter::create(def.width, def.height, format.pixel_format,
                                           format.colorspace, format.range);
    if (!converter) {
        return converter.error();
    }
    return std::unique_ptr<FrameConverter>(
        std::make_unique<RgbaConverter>(std::move(*converter)));
}

}  // namespace discreel::encode
