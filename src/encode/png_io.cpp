// read_png / write_png: PNG files on disk, read with bounds and written atomically.
#include <array>
#include <cstring>

#include "discreel/encode.hpp"
#include "discreel/output_file.hpp"
#include "discreel/printable.hpp"
#include "discreel/read_file.hpp"
#include "png_codec.hpp"

extern "C" {
#include <libavutil/base64.h>
}

namespace discreel::encode {
namespace {

// The signature and the IHDR chunk: 8 + 4 (length) + 4 ("IHDR") + 4 (width) + 4 (height).
constexpr std::size_t header_bytes = 24;
constexpr std::int64_t max_pixels = 7680LL * 4320LL;
constexpr std::array<unsigned char, 8> signature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

Error read_error(const std::string& path, const std::string& reason) {
    return Error{"cannot read '" + printable(path) + "': " + reason};
}

std::uint32_t big_endian(const char* bytes) {
    const auto* b = reinterpret_cast<const unsigned char*>(bytes);
    return (std::uint32_t{b[0]} << 24) | (std::uint32_t{b[1]} << 16) | (std::uint32_t{b[2]} << 8) |
           std::uint32_t{b[3]};
}

Expected<ImageSize> parse_header(const std::string& path, const std::string& bytes) {
    if (bytes.size() < header_bytes ||
        std::memcmp(bytes.data(), signature.data(), signature.size()) != 0 ||
        std::memcmp(bytes.data() + 12, "IHDR", 4) != 0) {
        return read_error(path, "not a PNG file");
    }
    const std::uint32_t width = big_endian(bytes.data() + 16);
    const std::uint32_t height = big_endian(bytes.data() + 20);
    if (width == 0 || height == 0 || width > 0x7fffffffU || height > 0x7fffffffU) {
        return read_error(path, "the PNG header gives an invalid size");
    }
    if (static_cast<std::uint64_t>(width) * height > static_cast<std::uint64_t>(max_pixels)) {
        return read_error(path, "the PNG is " + std::to_string(width) + "x" +
                                    std::to_string(height) +
                                    ", more pixels than the largest frame (7680x4320)");
    }
    return ImageSize{static_cast<int>(width), static_cast<int>(height)};
}

// The most bytes a PNG of this size can take: 16-bit RGBA rows with their filter byte, stored
// uncompressed (deflate's stored blocks add 5 bytes per 65535), and room for ancillary chunks.
std::uintmax_t largest_png_bytes(const ImageSize& size) {
    const std::uintmax_t raw =
        static_cast<std::uintmax_t>(size.height) * (static_cast<std::uintmax_t>(size.width) * 8 + 1);
    return raw + raw / 8192 + (1u << 20);
}

}  // namespace

Expected<ImageSize> read_png_size(const std::string& path) {
    auto start = read_file_bounded(path, header_bytes);
    if (!start) return read_error(path, start.error().message);
    return parse_header(path, start->bytes);
}

Expected<Image> read_png(const std::string& path) {
    const auto size = read_png_size(path);
    if (!size) return size.error();
    const std::uintmax_t limit = largest_png_bytes(*size);
    auto file = read_file_bounded(path, limit);
    if (!file) return read_error(path, file.error().message);
    if (file->too_large) {
        return read_error(path, "the file is larger than any PNG of " +
                                    std::to_string(size->width) + "x" +
                                    std::to_string(size->height) + " pixels can be");
    }
    const auto* data = reinterpret_cast<const std::uint8_t*>(file->bytes.data());
    auto image = decode_png(std::span<const std::uint8_t>(data, file->bytes.size()));
    if (!image) {
        return read_error(path, image.error().message);
    }
    return image;
}

Expected<OutputFile> write_png_to_temporary(const std::string& path, const ImageView& image) {
    auto png = encode_png(image);
    if (!png) {
        return write_error(path, png.error().message);
    }
    auto file = OutputFile::create(path);
    if (!file) {
        return file.error();
    }
    if (auto written = file->write_all(png->data(), png->size()); !written) {
        return written.error();
    }
    return file;
}

Expected<OutputFile> prepare_png(const std::string& path, const ImageView& image) {
    auto file = write_png_to_temporary(path, image);
    if (!file) return file.error();
    if (Status sealed = file->seal(); !sealed) return sealed.error();
    return file;
}

Expected<OutputFile> prepare_png_gray16(const std::string& path, const Gray16View& image) {
    auto png = encode_png_gray16(image);
    if (!png) return write_error(path, png.error().message);
    auto file = OutputFile::create(path);
    if (!file) return file.error();
    if (Status written = file->write_all(png->data(), png->size()); !written) {
        return written.error();
    }
    if (Status sealed = file->seal(); !sealed) return sealed.error();
    return file;
}

Expected<Gray16Image> read_png_gray16(const std::string& path) {
    const auto size = read_png_size(path);
    if (!size) return size.error();
    auto file = read_file_bounded(path, largest_png_bytes(*size));
    if (!file) return read_error(path, file.error().message);
    const auto* data = reinterpret_cast<const std::uint8_t*>(file->bytes.data());
    auto image = decode_png_gray16(std::span<const std::uint8_t>(data, file->bytes.size()));
    if (!image) return read_error(path, image.error().message);
    return image;
}

Expected<std::vector<std::uint8_t>> png_bytes(const ImageView& image) {
    return encode_png(image);
}

Expected<std::string> png_data_uri(const ImageView& image) {
    auto png = encode_png(image);
    if (!png) return png.error();
    const std::string prefix = "data:image/png;base64,";
    std::string uri(prefix.size() + AV_BASE64_SIZE(png->size()), '\0');
    std::memcpy(uri.data(), prefix.data(), prefix.size());
    if (!av_base64_encode(uri.data() + prefix.size(), static_cast<int>(uri.size() - prefix.size()),
                          png->data(), static_cast<int>(png->size()))) {
        return Error{"cannot encode a PNG as base64"};
    }
    uri.resize(uri.find('\0'));
    return uri;
}

Status write_png(const std::string& path, const ImageView& image) {
    auto file = write_png_to_temporary(path, image);
    if (!file) {
        return file.error();
    }
    return file->commit();
}

}  // namespace discreel::encode
