#include <gtest/gtest.h>

#include "discreel/encode.hpp"
#include "encode_test_support.hpp"

namespace discreel::encode::test {
namespace {

SinkDef still(const std::filesystem::path& path, int width = 64, int height = 48) {
    SinkDef def;
    def.path = path.string();
    def.width = width;
    def.height = height;
    return def;
}

TEST(PngStillSinkTest, WritesExactlyTheFrame) {
    const auto directory = scratch_directory();
    const auto path = directory / "frame.png";
    const Image frame = moving_shapes_frame(66, 41, 7);   // odd height: fine for a PNG
    {
        auto sink = open_sink(still(path, 66, 41));
        ASSERT_TRUE(sink.ok()) << sink.error().message;
        ASSERT_TRUE((*sink)->write(frame.view()).ok());
        ASSERT_TRUE((*sink)->finish().ok());
    }
    auto decoded = read_png(path.string());
    ASSERT_TRUE(decoded.ok()) << decoded.error().message;
    EXPECT_EQ(decoded->width, 66);
    EXPECT_EQ(decoded->height, 41);
    EXPECT_EQ(decoded->rgba, frame.rgba);
    EXPECT_EQ(directory_entries(directory), std::vector<std::string>{"frame.png"});
}

TEST(PngStillSinkTest, ASecondFrameIsAnError) {
    const auto directory = scratch_directory();
    const auto path = directory / "one.png";
    auto sink = open_sink(still(path));
    ASSERT_TRUE(sink.ok()) << sink.error().message;
    ASSERT_TRUE((*sink)->write(moving_shapes_frame(64, 48, 0).view()).ok());
    const Status second = (*sink)->write(moving_shapes_frame(64, 48, 1).view());
    ASSERT_FALSE(second.ok());
    EXPECT_EQ(second.error().message,
              "cannot write '" + path.string() +
                  "': a PNG still takes exactly one frame, got a second");
    // The first frame is still what gets written.
    ASSERT_TRUE((*sink)->finish().ok());
    auto decoded = read_png(path.string());
    ASSERT_TRUE(decoded.ok()) << decoded.error().message;
    EXPECT_EQ(decoded->rgba, moving_shapes_frame(64, 48, 0).rgba);
}

TEST(PngStillSinkTest, FinishingWithoutAFrameFailsAndKeepsTheExistingFile) {
    const auto directory = scratch_directory();
    const auto path = directory / "kept.png";
    write_file(path, "an earlier still");
    {
        auto sink = open_sink(still(path));
        ASSERT_TRUE(sink.ok()) << sink.error().message;
        const Status finished = (*sink)->finish();
        ASSERT_FALSE(finished.ok());
        EXPECT_EQ(finished.error().message,
                  "cannot write '" + path.string() +
                      "': a PNG still takes exactly one frame, got none");
    }
    EXPECT_EQ(directory_entries(directory), std::vector<std::string>{"kept.png"});
    const auto bytes = file_bytes(path);
    EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "an earlier still");
}

TEST(PngStillSinkTest, AbandonedSinkLeavesNoFile) {
    const auto directory = scratch_directory();
    {
        auto sink = open_sink(still(directory / "abandoned.png"));
        ASSERT_TRUE(sink.ok()) << sink.error().message;
        ASSERT_TRUE((*sink)->write(moving_shapes_frame(64, 48, 0).view()).ok());
    }
    EXPECT_TRUE(directory_entries(directory).empty());
}

TEST(PngStillSinkTest, FrameOfTheWrongSizeIsRejected) {
    const auto directory = scratch_directory();
    const auto path = directory / "sized.png";
    auto sink = open_sink(still(path));
    ASSERT_TRUE(sink.ok()) << sink.error().message;
    const Status written = (*sink)->write(moving_shapes_frame(32, 24, 0).view());
    ASSERT_FALSE(written.ok());
    EXPECT_EQ(written.error().message,
              "cannot write '" + path.string() + "': frame is 32x24 but the image is 64x48");
}

}  // namespace
}  // namespace discreel::encode::test
