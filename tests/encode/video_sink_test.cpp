#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <string>

#include "discreel/encode.hpp"
#include "encode_test_support.hpp"

namespace discreel::encode::test {
namespace {

SinkDef small_mp4(const std::filesystem::path& path) {
    SinkDef def;
    def.path = path.string();
    def.width = 64;
    def.height = 48;
    def.fps = 30;
    def.crf = 20;
    def.preset = "veryfast";
    def.threads = 2;
    return def;
}

// Writes `frame_count` frames of the moving-shapes animation and finishes.
void write_animation(const SinkDef& def, int frame_count) {
    auto sink = open_sink(def);
    ASSERT_TRUE(sink.ok()) << sink.error().message;
    for (int i = 0; i < frame_count; ++i) {
        const Image frame = moving_shapes_frame(def.width, def.height, i);
        const Status written = (*sink)->write(frame.view());
        ASSERT_TRUE(written.ok()) << written.error().message;
    }
    const Status finished = (*sink)->finish();
    ASSERT_TRUE(finished.ok()) << finished.error().message;
}

TEST(VideoSinkTest, Mp4IsH264Yuv420pWithEveryFrameAndTheRightDuration) {
    const auto directory = scratch_directory();
    const auto path = directory / "clip.mp4";
    const SinkDef def = small_mp4(path);
    write_animation(def, 36);

    auto stream = discreel::testing::probe_video(path.string());
    EXPECT_EQ(stream["codec_name"], "h264");
    EXPECT_EQ(stream["pix_fmt"], "yuv420p");
    EXPECT_EQ(stream["width"], "64");
    EXPECT_EQ(stream["height"], "48");
    EXPECT_EQ(stream["r_frame_rate"], "30/1");
    EXPECT_EQ(stream["nb_read_frames"], "36");
    EXPECT_EQ(stream["duration"], "1.200000");   // 36 frames / 30 fps
    EXPECT_EQ(directory_entries(directory), std::vector<std::string>{"clip.mp4"});
}

TEST(VideoSinkTest, Mp4IsTaggedBt709LimitedRange) {
    const auto directory = scratch_directory();
    const auto path = directory / "tagged.mp4";
    write_animation(small_mp4(path), 4);

    auto stream = discreel::testing::probe_video(path.string());
    EXPECT_EQ(stream["color_space"], "bt709");
    EXPECT_EQ(stream["color_primaries"], "bt709");
    EXPECT_EQ(stream["color_transfer"], "bt709");
    EXPECT_EQ(stream["color_range"], "tv");
}

TEST(VideoSinkTest, Mp4HasItsIndexBeforeTheMediaData) {
    const auto directory = scratch_directory();
    const auto path = directory / "faststart.mp4";
    write_animation(small_mp4(path), 10);

    const auto boxes = discreel::testing::mp4_top_level_boxes(path.string());
    const auto moov = std::find(boxes.begin(), boxes.end(), "moov");
    const auto mdat = std::find(boxes.begin(), boxes.end(), "mdat");
    ASSERT_NE(moov, boxes.end());
    ASSERT_NE(mdat, boxes.end());
    EXPECT_LT(moov, mdat) << "faststart: moov must precede mdat";
}

TEST(VideoSinkTest, SameFramesAndSettingsGiveIdenticalBytes) {
    const auto directory = scratch_directory();
    const auto first = directory / "first.mp4";
    const auto second = directory / "second.mp4";
    write_animation(small_mp4(first), 24);
    write_animation(small_mp4(second), 24);

    const auto first_bytes = file_bytes(first);
    ASSERT_FALSE(first_bytes.empty());
    EXPECT_EQ(first_bytes, file_bytes(second));
}

TEST(VideoSinkTest, PureRedDecodesAsRedInATagAwareDecoder) {
    const auto directory = scratch_directory();
    const auto path = directory / "red.mp4";
    SinkDef def = small_mp4(path);
    {
        auto sink = open_sink(def);
        ASSERT_TRUE(sink.ok()) << sink.error().message;
        const Image red = solid_image(def.width, def.height, 255, 0, 0);
        for (int i = 0; i < 5; ++i) {
            ASSERT_TRUE((*sink)->write(red.view()).ok());
        }
        ASSERT_TRUE((*sink)->finish().ok());
    }
    const auto rgb = discreel::testing::decode_first_frame_rgb24(path.string());
    ASSERT_EQ(rgb.size(), std::size_t{3} * 64 * 48);
    // A pixel in the middle. Limited-range 8-bit YUV and H.264 quantisation of a flat frame
    // cost a few units at most; converting with BT.601 while tagging BT.709 (libswscale's
    // default) gives about (255, 23, 0), far outside this tolerance.
    constexpr int tolerance = 4;
    const std::size_t middle = 3 * (std::size_t{24} * 64 + 32);
    EXPECT_NEAR(rgb[middle + 0], 255, tolerance);
    EXPECT_NEAR(rgb[middle + 1], 0, tolerance);
    EXPECT_NEAR(rgb[middle + 2], 0, tolerance);
}

TEST(VideoSinkTest, WritesToAHiddenTemporaryFileUntilFinished) {
    const auto directory = scratch_directory();
    const auto path = directory / "pending.mp4";
    const SinkDef def = small_mp4(path);
    auto sink = open_sink(def);
    ASSERT_TRUE(sink.ok()) << sink.error().message;
    ASSERT_TRUE((*sink)->write(moving_shapes_frame(64, 48, 0).view()).ok());

    const auto during = directory_entries(directory);
    ASSERT_EQ(during.size(), 1u);
    EXPECT_EQ(during[0].rfind(".pending.mp4.tmp-", 0), 0u) << during[0];

    ASSERT_TRUE((*sink)->finish().ok());
    EXPECT_EQ(directory_entries(directory), std::vector<std::string>{"pending.mp4"});
}

TEST(VideoSinkTest, AbandonedSinkLeavesTheExistingTargetAndNoTemporaryFile) {
    const auto directory = scratch_directory();
    const auto path = directory / "existing.mp4";
    write_file(path, "an earlier render");
    {
        auto sink = open_sink(small_mp4(path));
        ASSERT_TRUE(sink.ok()) << sink.error().message;
        for (int i = 0; i < 5; ++i) {
            ASSERT_TRUE((*sink)->write(moving_shapes_frame(64, 48, i).view()).ok());
        }
        // destroyed without finish()
    }
    EXPECT_EQ(directory_entries(directory), std::vector<std::string>{"existing.mp4"});
    const auto bytes = file_bytes(path);
    EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "an earlier render");
}

TEST(VideoSinkTest, OddSizeIsRejectedBeforeAnyFileIsCreated) {
    const auto directory = scratch_directory();
    const auto path = directory / "odd.mp4";
    SinkDef def = small_mp4(path);
    def.width = 65;
    auto sink = open_sink(def);
    ASSERT_FALSE(sink.ok());
    EXPECT_EQ(sink.error().message, "cannot write '" + path.string() +
                                        "': yuv420p video needs an even width and height, "
                                        "got 65x48");
    EXPECT_TRUE(directory_entries(directory).empty());
}

TEST(VideoSinkTest, FrameOfTheWrongSizeIsRejected) {
    const auto directory = scratch_directory();
    const auto path = directory / "sized.mp4";
    auto sink = open_sink(small_mp4(path));
    ASSERT_TRUE(sink.ok()) << sink.error().message;
    const Status written = (*sink)->write(moving_shapes_frame(32, 24, 0).view());
    ASSERT_FALSE(written.ok());
    EXPECT_EQ(written.error().message,
              "cannot write '" + path.string() + "': frame is 32x24 but the video is 64x48");
}

TEST(VideoSinkTest, FinishingWithoutFramesFailsAndLeavesNothing) {
    const auto directory = scratch_directory();
    const auto path = directory / "empty.mp4";
    {
        auto sink = open_sink(small_mp4(path));
        ASSERT_TRUE(sink.ok()) << sink.error().message;
        const Status finished = (*sink)->finish();
        ASSERT_FALSE(finished.ok());
        EXPECT_EQ(finished.error().message,
                  "cannot write '" + path.string() + "': no frames were written");
    }
    EXPECT_TRUE(directory_entries(directory).empty());
}

TEST(VideoSinkTest, WritingAfterFinishIsAnError) {
    const auto directory = scratch_directory();
    const auto path = directory / "done.mp4";
    auto sink = open_sink(small_mp4(path));
    ASSERT_TRUE(sink.ok()) << sink.error().message;
    ASSERT_TRUE((*sink)->write(moving_shapes_frame(64, 48, 0).view()).ok());
    ASSERT_TRUE((*sink)->finish().ok());
    const Status written = (*sink)->write(moving_shapes_frame(64, 48, 1).view());
    ASSERT_FALSE(written.ok());
    EXPECT_EQ(written.error().message,
              "cannot write '" + path.string() + "': the sink is already finished");
}

TEST(VideoSinkTest, BadEncoderSettingsAreNamed) {
    const auto directory = scratch_directory();
    const auto path = directory / "settings.mp4";
    const std::string prefix = "cannot write '" + path.string() + "': ";

    SinkDef def = small_mp4(path);
    def.preset = "warp";
    auto sink = open_sink(def);
    ASSERT_FALSE(sink.ok());
    EXPECT_EQ(sink.error().message,
              prefix + "unknown x264 preset 'warp' (ultrafast, superfast, veryfast, faster, "
                       "fast, medium, slow, slower, veryslow, placebo)");

    def = small_mp4(path);
    def.crf = 52;
    sink = open_sink(def);
    ASSERT_FALSE(sink.ok());
    EXPECT_EQ(sink.error().message, prefix + "crf 52 is outside 0..51");

    def = small_mp4(path);
    def.threads = 0;
    sink = open_sink(def);
    ASSERT_FALSE(sink.ok());
    EXPECT_EQ(sink.error().message, prefix + "encoder threads must be at least 1, got 0");

    def = small_mp4(path);
    def.fps = 0;
    sink = open_sink(def);
    ASSERT_FALSE(sink.ok());
    EXPECT_EQ(sink.error().message, prefix + "fps must be positive, got 0");

    EXPECT_TRUE(directory_entries(directory).empty());
}

}  // namespace
}  // namespace discreel::encode::test
