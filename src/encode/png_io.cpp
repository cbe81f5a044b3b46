// read_png / write_png: PNG files on disk, written atomically through OutputFile.
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

#include "discreel/encode.hpp"
#include "discreel/output_file.hpp"
#include "png_codec.hpp"

namespace discreel::encode {

Expected<Image> read_png(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) {
        return Error{"cannot read '" + path + "': " + std::strerror(errno)};
    }
    const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(file),
                                          std::istreambuf_iterator<char>()};
    if (file.bad()) {
        return Error{"cannot read '" + path + "': " + std::strerror(errno)};
    }
    auto image = decode_png(bytes);
    if (!image) {
        return Error{"cannot read '" + path + "': " + image.error().message};
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

Status write_png(const std::string& path, const ImageView& image) {
    auto file = write_png_to_temporary(path, image);
    if (!file) {
        return file.error();
    }
    return file->commit();
}

}  // namespace discreel::encode
