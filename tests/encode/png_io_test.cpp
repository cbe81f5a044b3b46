#include <gtest/gtest.h>

#include <cstdlib>

#include "discreel/encode.hpp"
#include "encode_test_support.hpp"

namespace discreel::encode::test {
namespace {

// Every byte value in every channel, alpha included, so a lossy or premultiplying path fails.
Image all_values_image(int width, int height) {
    Image image{width, height, std::vector<std::uint8_t>(std::size_t{4} * width * height)};
    for (std::size_t i = 0; i < image.rgba.size(); ++i) {
        image.rgba[i] = static_cast<std::uint8_t>((i * 7 + i / 4 * 13) % 256);
    }
    return image;
}

TEST(PngIoTest, RoundTripIsExact) {
    const auto directory = scratch_directory();
    const auto path = (directory / "round.png").string();
    const Image original = all_values_image(67, 33);   // odd sizes are fine for PNG

    ASSERT_TRUE(write_png(path, original.view()).ok());
    auto decoded = read_png(path);
    ASSERT_TRUE(decoded.ok()) << decoded.error().message;
    EXPECT_EQ(decoded->width, 67);
    EXPECT_EQ(decoded->height, 33);
    EXPECT_EQ(decoded->rgba, original.rgba);
    EXPECT_EQ(directory_entries(directory), std::vector<std::string>{"round.png"});
}

TEST(PngIoTest, WritesAnEightBitRgbaPng) {
    const auto directory = scratch_directory();
    const auto path = (directory / "probe.png").string();
    ASSERT_TRUE(write_png(path, moving_shapes_frame(64, 48, 3).view()).ok());
    const auto bytes = file_bytes(path);
    ASSERT_GE(bytes.size(), 26u);
    // PNG signature, then IHDR: bit depth 8, colour type 6 (RGBA).
    EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 8),
              (std::vector<std::uint8_t>{0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A}));
    EXPECT_EQ(bytes[24], 8);
    EXPECT_EQ(bytes[25], 6);
}

// Makes a PNG of the given pixel format with the ffmpeg CLI (not our encoder) from raw bytes.
void ffmpeg_png_from_raw(const std::filesystem::path& directory, const std::string& pixel_format,
                         int width, int height, const std::vector<std::uint8_t>& raw,
                         const std::filesystem::path& png) {
    const auto raw_path = directory / "input.raw";
    write_file(raw_path, std::string(raw.begin(), raw.end()));
    const std::string command = "ffmpeg -v error -y -f rawvideo -pix_fmt " + pixel_format +
                                " -s " + std::to_string(width) + "x" + std::to_string(height) +
                                " -i '" + raw_path.string() + "' -frames:v 1 -pix_fmt " +
                                pixel_format + " '" + png.string() + "'";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
}

TEST(PngIoTest, ReadsRgbPngWrittenByFfmpegAsOpaqueRgba) {
    const auto directory = scratch_directory();
    const auto path = directory / "rgb.png";
    std::vector<std::uint8_t> rgb;
    Image expected{16, 8, {}};
    for (int i = 0; i < 16 * 8; ++i) {
        const auto r = static_cast<std::uint8_t>(i * 2), g = static_cast<std::uint8_t>(255 - i),
                   b = static_cast<std::uint8_t>(i * 31);
        rgb.insert(rgb.end(), {r, g, b});
        expected.rgba.insert(expected.rgba.end(), {r, g, b, 255});
    }
    ffmpeg_png_from_raw(directory, "rgb24", 16, 8, rgb, path);

    auto decoded = read_png(path.string());
    ASSERT_TRUE(decoded.ok()) << decoded.error().message;
    EXPECT_EQ(decoded->width, 16);
    EXPECT_EQ(decoded->height, 8);
    EXPECT_EQ(decoded->rgba, expected.rgba);
}

TEST(PngIoTest, ReadsGreyPngAtFullRange) {
    const auto directory = scratch_directory();
    const auto path = directory / "grey.png";
    std::vector<std::uint8_t> grey;
    Image expected{16, 16, {}};
    for (int value = 0; value < 256; ++value) {
        const auto v = static_cast<std::uint8_t>(value);
        grey.push_back(v);
        expected.rgba.insert(expected.rgba.end(), {v, v, v, 255});
    }
    ffmpeg_png_from_raw(directory, "gray", 16, 16, grey, path);

    auto decoded = read_png(path.string());
    ASSERT_TRUE(decoded.ok()) << decoded.error().message;
    // Grey levels map to equal RGB: 255 stays 255, not squeezed into video range (235).
    EXPECT_EQ(decoded->rgba, expected.rgba);
}

TEST(PngIoTest, ReadingAMissingFileNamesPathAndReason) {
    const auto directory = scratch_directory();
    const auto path = (directory / "absent.png").string();
    auto decoded = read_png(path);
    ASSERT_FALSE(decoded.ok());
    EXPECT_EQ(decoded.error().message, "cannot read '" + path + "': No such file or directory");
}

TEST(PngIoTest, ReadingANonPngFails) {
    const auto directory = scratch_directory();
    const auto path = directory / "text.png";
    write_file(path, "this is not a PNG file");
    auto decoded = read_png(path.string());
    ASSERT_FALSE(decoded.ok());
    // Judged by its first bytes, before anything else is read or decoded.
    EXPECT_EQ(decoded.error().message, "cannot read '" + path.string() + "': not a PNG file");
}

TEST(PngIoTest, WritingIntoAMissingDirectoryFailsAndCreatesNothing) {
    const auto directory = scratch_directory();
    const auto path = (directory / "missing" / "out.png").string();
    const Status status = write_png(path, solid_image(4, 4, 1, 2, 3).view());
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().message, "cannot write '" + path + "': directory '" +
                                          (directory / "missing").string() + "' does not exist");
    EXPECT_TRUE(directory_entries(directory).empty());
}

TEST(PngIoTest, ImageWithWrongByteCountIsRejectedAndTargetKept) {
    const auto directory = scratch_directory();
    const auto path = directory / "kept.png";
    write_file(path, "previous contents");
    const std::vector<std::uint8_t> too_short(10);
    const Status status = write_png(path.string(), ImageView{4, 4, too_short});
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().message, "cannot write '" + path.string() +
                                          "': a 4x4 RGBA image needs 64 bytes, got 10");
    EXPECT_EQ(directory_entries(directory), std::vector<std::string>{"kept.png"});
    const auto bytes = file_bytes(path);
    EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "previous contents");
}

TEST(PngIoTest, OverwritesAnExistingFileOnSuccess) {
    const auto directory = scratch_directory();
    const auto path = directory / "replaced.png";
    write_file(path, "previous contents");
    const Image image = solid_image(8, 6, 9, 8, 7, 6);
    ASSERT_TRUE(write_png(path.string(), image.view()).ok());
    auto decoded = read_png(path.string());
    ASSERT_TRUE(decoded.ok()) << decoded.error().message;
    EXPECT_EQ(decoded->rgba, image.rgba);
    EXPECT_EQ(directory_entries(directory), std::vector<std::string>{"replaced.png"});
}

}  // namespace
}  // namespace discreel::encode::test
