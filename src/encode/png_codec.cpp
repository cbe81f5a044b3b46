#include "png_codec.hpp"

#include <cstring>

extern "C" {
#include <libavutil/pixdesc.h>
}

#include "av_handles.hpp"
#include "image_check.hpp"
#include "libav_log.hpp"

namespace discreel::encode {
namespace {

Error libav_failure(const char* what, int error_code) {
    return Error{std::string(what) + ": " + libav_reason(error_code)};
}

// Copies rows between a packed RGBA buffer and a frame whose rows may be padded.
void copy_rows(std::uint8_t* destination, int destination_stride, const std::uint8_t* source,
               int source_stride, int row_bytes, int rows) {
    for (int row = 0; row < rows; ++row) {
        std::memcpy(destination + static_cast<std::ptrdiff_t>(row) * destination_stride,
                    source + static_cast<std::ptrdiff_t>(row) * source_stride,
                    static_cast<std::size_t>(row_bytes));
    }
}

Expected<CodecContextPtr> open_png_codec(const AVCodec* codec, int width, int height,
                                        AVPixelFormat format = AV_PIX_FMT_RGBA) {
    if (codec == nullptr) {
        return Error{"libavcodec was built without its PNG codec"};
    }
    CodecContextPtr context(avcodec_alloc_context3(codec));
    if (!context) {
        return libav_failure("cannot allocate a PNG codec context", AVERROR(ENOMEM));
    }
    // One thread: a single still gains nothing from frame threads, and the bytes stay simple.
    context->thread_count = 1;
    if (av_codec_is_encoder(codec)) {
        context->width = width;
        context->height = height;
        context->pix_fmt = format;
        context->time_base = AVRational{1, 1};   // required by the API, meaningless for a still
        context->flags |= AV_CODEC_FLAG_BITEXACT;
    }
    if (const int result = avcodec_open2(context.get(), codec, nullptr); result < 0) {
        return libav_failure("cannot open the PNG codec", result);
    }
    return context;
}

// One packed plane (rows of `row_bytes`) in `format` as a PNG.
Expected<std::vector<std::uint8_t>> encode_plane(const std::uint8_t* pixels, int width,
                                                 int height, int row_bytes,
                                                 AVPixelFormat format) {
    begin_libav_call();
    auto context =
        open_png_codec(avcodec_find_encoder(AV_CODEC_ID_PNG), width, height, format);
    if (!context) {
        return context.error();
    }
    FramePtr frame(av_frame_alloc());
    PacketPtr packet(av_packet_alloc());
    if (!frame || !packet) {
        return libav_failure("cannot allocate a frame", AVERROR(ENOMEM));
    }
    frame->width = width;
    frame->height = height;
    frame->format = format;
    if (const int result = av_frame_get_buffer(frame.get(), 0); result < 0) {
        return libav_failure("cannot allocate a frame", result);
    }
    copy_rows(frame->data[0], frame->linesize[0], pixels, row_bytes, row_bytes, height);

    if (const int result = avcodec_send_frame(context->get(), frame.get()); result < 0) {
        return libav_failure("PNG encoder rejected the image", result);
    }
    if (const int result = avcodec_send_frame(context->get(), nullptr); result < 0) {
        return libav_failure("PNG encoder could not flush", result);
    }
    std::vector<std::uint8_t> png;
    for (;;) {
        const int result = avcodec_receive_packet(context->get(), packet.get());
        if (result == AVERROR_EOF) {
            break;
        }
        if (result < 0) {
            return libav_failure("PNG encoder failed", result);
        }
        png.insert(png.end(), packet->data, packet->data + packet->size);
        av_packet_unref(packet.get());
    }
    return png;
}

}  // namespace

Expected<std::vector<std::uint8_t>> encode_png(const ImageView& image) {
    if (auto problem = image_problem(image)) {
        return Error{*problem};
    }
    return encode_plane(image.rgba.data(), image.width, image.height, 4 * image.width,
                        AV_PIX_FMT_RGBA);
}

Expected<std::vector<std::uint8_t>> encode_png_gray16(const Gray16View& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.values.size() != static_cast<std::size_t>(image.width) *
                                   static_cast<std::size_t>(image.height)) {
        return Error{"a 16-bit grey image needs width x height values"};
    }
    // PNG stores 16-bit samples big-endian.
    std::vector<std::uint8_t> bytes(2 * image.values.size());
    for (std::size_t i = 0; i < image.values.size(); ++i) {
        bytes[2 * i] = static_cast<std::uint8_t>(image.values[i] >> 8);
        bytes[2 * i + 1] = static_cast<std::uint8_t>(image.values[i] & 0xff);
    }
    return encode_plane(bytes.data(), image.width, image.height, 2 * image.width,
                        AV_PIX_FMT_GRAY16BE);
}

namespace {

// The decoded frame of a PNG, in whatever format the file has.
Expected<FramePtr> decode_frame(std::span<const std::uint8_t> png_bytes) {
    begin_libav_call();
    auto context = open_png_codec(avcodec_find_decoder(AV_CODEC_ID_PNG), 0, 0);
    if (!context) {
        return context.error();
    }
    FramePtr frame(av_frame_alloc());
    PacketPtr packet(av_packet_alloc());
    if (!frame || !packet) {
        return libav_failure("cannot allocate a frame", AVERROR(ENOMEM));
    }
    // The decoder reads past the end of its input by up to AV_INPUT_BUFFER_PADDING_SIZE bytes;
    // av_new_packet provides that zeroed padding.
    if (const int result = av_new_packet(packet.get(), static_cast<int>(png_bytes.size()));
        result < 0) {
        return libav_failure("cannot allocate a packet", result);
    }
    std::memcpy(packet->data, png_bytes.data(), png_bytes.size());

    if (const int result = avcodec_send_packet(context->get(), packet.get()); result < 0) {
        return libav_failure("not a PNG image", result);
    }
    if (const int result = avcodec_receive_frame(context->get(), frame.get()); result < 0) {
        return libav_failure("not a PNG image", result);
    }
    return frame;
}

}  // namespace

Expected<Gray16Image> decode_png_gray16(std::span<const std::uint8_t> png_bytes) {
    auto decoded = decode_frame(png_bytes);
    if (!decoded) return decoded.error();
    const AVFrame& frame = **decoded;
    if (frame.format != AV_PIX_FMT_GRAY16BE) {
        return Error{std::string("not a 16-bit grey PNG (it is ") +
                     av_get_pix_fmt_name(static_cast<AVPixelFormat>(frame.format)) + ")"};
    }
    Gray16Image image;
    image.width = frame.width;
    image.height = frame.height;
    image.values.reserve(static_cast<std::size_t>(frame.width) *
                         static_cast<std::size_t>(frame.height));
    for (int row = 0; row < frame.height; ++row) {
        const std::uint8_t* p = frame.data[0] + static_cast<std::ptrdiff_t>(row) * frame.linesize[0];
        for (std::size_t x = 0; x < static_cast<std::size_t>(frame.width); ++x) {
            image.values.push_back(static_cast<std::uint16_t>((p[2 * x] << 8) | p[2 * x + 1]));
        }
    }
    return image;
}

Expected<Image> decode_png(std::span<const std::uint8_t> png_bytes) {
    auto decoded = decode_frame(png_bytes);
    if (!decoded) return decoded.error();
    FramePtr frame = std::move(*decoded);

    Image image;
    image.width = frame->width;
    image.height = frame->height;
    image.rgba.resize(std::size_t{4} * static_cast<std::size_t>(image.width) *
                      static_cast<std::size_t>(image.height));
    const int row_bytes = 4 * image.width;
    if (frame->format == AV_PIX_FMT_RGBA) {
        copy_rows(image.rgba.data(), row_bytes, frame->data[0], frame->linesize[0], row_bytes,
                  image.height);
        return image;
    }

    // Grey, palette, RGB and 16-bit PNGs: libswscale widens them to RGBA8. All of these are
    // RGB-family or full-range grey, so no YUV matrix is involved. The intermediate frame has
    // libav's aligned rows, which swscale wants.
    FramePtr rgba(av_frame_alloc());
    if (!rgba) {
        return libav_failure("cannot allocate a frame", AVERROR(ENOMEM));
    }
    rgba->width = image.width;
    rgba->height = image.height;
    rgba->format = AV_PIX_FMT_RGBA;
    if (const int result = av_frame_get_buffer(rgba.get(), 0); result < 0) {
        return libav_failure("cannot allocate a frame", result);
    }
    SwsContextPtr converter(sws_getContext(
        image.width, image.height, static_cast<AVPixelFormat>(frame->format), image.width,
        image.height, AV_PIX_FMT_RGBA, SWS_POINT | SWS_ACCURATE_RND | SWS_BITEXACT, nullptr,
        nullptr, nullptr));
    if (!converter) {
        return Error{std::string("cannot convert PNG pixel format '") +
                     av_get_pix_fmt_name(static_cast<AVPixelFormat>(frame->format)) +
                     "' to RGBA"};
    }
    sws_scale(converter.get(), frame->data, frame->linesize, 0, image.height, rgba->data,
              rgba->linesize);
    copy_rows(image.rgba.data(), row_bytes, rgba->data[0], rgba->linesize[0], row_bytes,
              image.height);
    return image;
}

}  // namespace discreel::encode
