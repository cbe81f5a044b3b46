// Every output format through open_sink, read back with ffprobe/ffmpeg as independent readers:
// codec, pixel format, size, frame count, colour tags, byte-identical output, exact round trips
// where the format is lossless, and the settings each format refuses.
#include <gtest/gtest.h>

#include <string>

#include "discreel/encode.hpp"
#include "encode_test_support.hpp"

namespace discreel::encode::test {
namespace {

using discreel::testing::decode_frames_rgb24;
using discreel::testing::probe_video;

constexpr int width = 64;
constexpr int height = 48;
constexpr int frame_count = 24;

SinkDef small_def(const std::filesystem::path& path) {
    SinkDef def;
    def.path = path.string();
    def.width = width;
    def.height = height;
    def.fps = 30;
    return def;
}

void write_frames(const SinkDef& def, const std::vector<Image>& frames) {
    auto sink = open_sink(def);
    ASSERT_TRUE(sink.ok()) << sink.error().message;
    for (const Image& frame : frames) {
        const Status written = (*sink)->write(frame.view());
        ASSERT_TRUE(written.ok()) << written.error().message;
    }
    const Status finished = (*sink)->finish();
    ASSERT_TRUE(finished.ok()) << finished.error().message;
}

std::vector<Image> animation(int count = frame_count) {
    std::vector<Image> frames;
    for (int i = 0; i < count; ++i) frames.push_back(moving_shapes_frame(width, height, i));
    return frames;
}

// The frames as packed RGB24, the layout decode_frames_rgb24 returns.
std::vector<std::uint8_t> rgb24_of(const std::vector<Image>& frames) {
    std::vector<std::uint8_t> rgb;
    for (const Image& frame : frames) {
        for (std::size_t i = 0; i < frame.rgba.size(); i += 4) {
            rgb.insert(rgb.end(), {frame.rgba[i], frame.rgba[i + 1], frame.rgba[i + 2]});
        }
    }
    return rgb;
}

std::string check_message(const SinkDef& def) {
    const Status status = check_settings(def);
    return status.ok() ? "ok" : status.error().message;
}

TEST(OutputFormatsTest, DescribeOutputNamesTheFormat) {
    const auto describe = [](const std::string& path) {
        auto d = describe_output(path);
        if (!d) return d.error().message;
        return d->format + (d->one_frame ? " one-frame" : "") + (d->to_stdout ? " stdout" : "");
    };
    EXPECT_EQ(describe("a.mp4"), "mp4");
    EXPECT_EQ(describe("dir/A.MKV"), "mkv");
    EXPECT_EQ(describe("a.webm"), "webm");
    EXPECT_EQ(describe("a.gif"), "gif");
    EXPECT_EQ(describe("a.png"), "png one-frame");
    EXPECT_EQ(describe("out/frame_%04d.png"), "png sequence");
    EXPECT_EQ(describe("100%%_%d.png"), "png sequence");
    EXPECT_EQ(describe("-"), "mkv stdout");
    EXPECT_EQ(describe("a_%04d_%d.png"),
              "'a_%04d_%d.png': a '%' in an output name must be one frame number, %d or %0Nd "
              "such as %04d (write %% for a percent sign)");
    EXPECT_EQ(describe("a_%s.png"),
              "'a_%s.png': a '%' in an output name must be one frame number, %d or %0Nd such as "
              "%04d (write %% for a percent sign)");
}

TEST(OutputFormatsTest, SettingsAFormatCannotTakeAreNamed) {
    const auto with = [](const std::string& path, auto change) {
        SinkDef def = small_def(path);
        change(def);
        return check_message(def);
    };
    EXPECT_EQ(with("a.mp4", [](SinkDef& d) { d.lossless = true; }),
              "lossless output is FFV1 in Matroska: use .mkv or -, not .mp4");
    EXPECT_EQ(with("a.webm", [](SinkDef& d) { d.lossless = true; }),
              "lossless output is FFV1 in Matroska: use .mkv or -, not .webm");
    EXPECT_EQ(with("a.mp4", [](SinkDef& d) { d.codec = "vp9"; }),
              "codec 'vp9' is not available for .mp4 (h264)");
    EXPECT_EQ(with("a.webm", [](SinkDef& d) { d.codec = "h264"; }),
              "codec 'h264' is not available for .webm (vp9)");
    EXPECT_EQ(with("a.mkv", [](SinkDef& d) { d.codec = "hevc"; }),
              "codec 'hevc' is not available for .mkv (h264, vp9, ffv1)");
    EXPECT_EQ(with("a.mkv", [](SinkDef& d) { d.lossless = true; d.codec = "h264"; }),
              "lossless output is FFV1; it cannot be combined with codec 'h264'");
    EXPECT_EQ(with("a.mkv", [](SinkDef& d) { d.lossless = true; d.crf = 10; }),
              "crf does not apply to FFV1 (lossless)");
    EXPECT_EQ(with("-", [](SinkDef& d) { d.lossless = true; d.pixel_format = "yuv444p"; }),
              "pixel format does not apply to FFV1 (lossless, it stores RGB as bgr0)");
    EXPECT_EQ(with("a.mp4", [](SinkDef& d) { d.pixel_format = "rgb24"; }),
              "pixel format 'rgb24' is not available for H.264 (yuv420p, yuv444p)");
    EXPECT_EQ(with("a.webm", [](SinkDef& d) { d.preset = "fast"; }),
              "preset does not apply to VP9 (it is an x264 setting)");
    EXPECT_EQ(with("a.webm", [](SinkDef& d) { d.crf = 64; }), "crf 64 is outside 0..63");
    EXPECT_EQ(with("a.webm", [](SinkDef& d) { d.crf = 63; }), "ok");
    EXPECT_EQ(with("a.mkv", [](SinkDef& d) { d.crf = 52; }), "crf 52 is outside 0..51");
    EXPECT_EQ(with("a.gif", [](SinkDef& d) { d.crf = 20; }), "crf does not apply to GIF");
    EXPECT_EQ(with("a.gif", [](SinkDef& d) { d.codec = "gif"; }), "codec does not apply to GIF");
    EXPECT_EQ(with("a.png", [](SinkDef& d) { d.preset = "slow"; }), "preset does not apply to PNG");
    EXPECT_EQ(with("f%d.png", [](SinkDef& d) { d.lossless = true; }),
              "lossless does not apply to PNG");
    EXPECT_EQ(with("a.mkv", [](SinkDef& d) { d.codec = "vp9"; d.pixel_format = "yuv444p"; }),
              "ok");
}

TEST(OutputFormatsTest, OpenSinkPrefixesSettingsErrorsWithThePathAndCreatesNothing) {
    const auto directory = scratch_directory();
    SinkDef def = small_def(directory / "clip.mp4");
    def.lossless = true;
    auto sink = open_sink(def);
    ASSERT_FALSE(sink.ok());
    EXPECT_EQ(sink.error().message,
              "cannot write '" + def.path +
                  "': lossless output is FFV1 in Matroska: use .mkv or -, not .mp4");
    EXPECT_TRUE(directory_entries(directory).empty());
}

TEST(OutputFormatsTest, MkvIsH264Bt709ByDefault) {
    const auto directory = scratch_directory();
    const auto path = directory / "clip.mkv";
    write_frames(small_def(path), animation());
    auto stream = probe_video(path.string());
    EXPECT_EQ(stream["codec_name"], "h264");
    EXPECT_EQ(stream["pix_fmt"], "yuv420p");
    EXPECT_EQ(stream["width"], "64");
    EXPECT_EQ(stream["height"], "48");
    EXPECT_EQ(stream["nb_read_frames"], "24");
    EXPECT_EQ(stream["color_space"], "bt709");
    EXPECT_EQ(stream["color_primaries"], "bt709");
    EXPECT_EQ(stream["color_transfer"], "bt709");
    EXPECT_EQ(stream["color_range"], "tv");
}

TEST(OutputFormatsTest, Yuv444pKeepsFullColourResolution) {
    const auto directory = scratch_directory();
    for (const char* name : {"clip.mp4", "clip.webm"}) {
        SinkDef def = small_def(directory / name);
        def.pixel_format = "yuv444p";
        write_frames(def, animation(6));
        auto stream = probe_video(def.path);
        EXPECT_EQ(stream["pix_fmt"], "yuv444p") << name;
        EXPECT_EQ(stream["nb_read_frames"], "6") << name;
        EXPECT_EQ(stream["color_space"], "bt709") << name;
    }
    EXPECT_EQ(probe_video((directory / "clip.mp4").string())["profile"], "High 4:4:4 Predictive");
}

TEST(OutputFormatsTest, WebmIsVp9Bt709LimitedRange) {
    const auto directory = scratch_directory();
    const auto path = directory / "clip.webm";
    write_frames(small_def(path), animation());
    auto stream = probe_video(path.string());
    EXPECT_EQ(stream["codec_name"], "vp9");
    EXPECT_EQ(stream["pix_fmt"], "yuv420p");
    EXPECT_EQ(stream["width"], "64");
    EXPECT_EQ(stream["height"], "48");
    EXPECT_EQ(stream["nb_read_frames"], "24");
    EXPECT_EQ(stream["color_space"], "bt709");
    EXPECT_EQ(stream["color_primaries"], "bt709");
    EXPECT_EQ(stream["color_transfer"], "bt709");
    EXPECT_EQ(stream["color_range"], "tv");
}

TEST(OutputFormatsTest, LosslessMkvIsFfv1AndExactInRgb) {
    const auto directory = scratch_directory();
    const auto path = directory / "exact.mkv";
    SinkDef def = small_def(path);
    def.lossless = true;
    const auto frames = animation();
    write_frames(def, frames);
    auto stream = probe_video(path.string());
    EXPECT_EQ(stream["codec_name"], "ffv1");
    EXPECT_EQ(stream["pix_fmt"], "bgr0");
    EXPECT_EQ(stream["nb_read_frames"], "24");
    EXPECT_EQ(stream["color_space"], "gbr");
    EXPECT_EQ(stream["color_transfer"], "iec61966-2-1");
    EXPECT_EQ(stream["color_range"], "pc");
    // Every pixel of every frame, exactly: no tolerance, this is the lossless promise.
    EXPECT_TRUE(decode_frames_rgb24(path.string()) == rgb24_of(frames));
}

TEST(OutputFormatsTest, GifIsEveryFrameExactWhenTheSceneHasFewColours) {
    const auto directory = scratch_directory();
    const auto path = directory / "clip.gif";
    const auto frames = animation();
    write_frames(small_def(path), frames);
    auto stream = probe_video(path.string());
    EXPECT_EQ(stream["codec_name"], "gif");
    EXPECT_EQ(stream["width"], "64");
    EXPECT_EQ(stream["height"], "48");
    EXPECT_EQ(stream["nb_read_frames"], "24");
    // Three colours fit the palette, so nothing is approximated.
    EXPECT_TRUE(decode_frames_rgb24(path.string()) == rgb24_of(frames));
}

TEST(OutputFormatsTest, GifFlatColourRoundTripsExactly) {
    const auto directory = scratch_directory();
    const auto path = directory / "flat.gif";
    write_frames(small_def(path), std::vector<Image>(3, solid_image(width, height, 12, 34, 56)));
    EXPECT_TRUE(decode_frames_rgb24(path.string()) ==
                rgb24_of(std::vector<Image>(3, solid_image(width, height, 12, 34, 56))));
}

// More colours than a palette holds: the key colours stay exact, the rest is the nearest entry.
TEST(OutputFormatsTest, GifKeepsKeyColoursExactBeyond256Colours) {
    const auto directory = scratch_directory();
    const auto path = directory / "many.gif";
    Image frame = solid_image(width, height, 0, 0, 0);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            std::uint8_t* p = &frame.rgba[4 * static_cast<std::size_t>(y * width + x)];
            if (x < 8) {   // a stripe of the key colour, rarer than most gradient colours
                p[0] = 201; p[1] = 13; p[2] = 77;
            } else {       // 3 072 distinct colours
                p[0] = static_cast<std::uint8_t>(x * 4); p[1] = static_cast<std::uint8_t>(y * 5);
                p[2] = static_cast<std::uint8_t>((x + y) % 3 * 100);
            }
        }
    }
    SinkDef def = small_def(path);
    def.key_colours = {{201, 13, 77}};
    write_frames(def, {frame});
    const auto rgb = decode_frames_rgb24(path.string());
    ASSERT_EQ(rgb.size(), std::size_t{3} * width * height);
    int worst = 0;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y * width + x);
            if (x < 8) {
                ASSERT_EQ(rgb[3 * i], 201); ASSERT_EQ(rgb[3 * i + 1], 13); ASSERT_EQ(rgb[3 * i + 2], 77);
            }
            for (int c = 0; c < 3; ++c) {
                worst = std::max(worst, std::abs(int{rgb[3 * i + c]} - int{frame.rgba[4 * i + c]}));
            }
        }
    }
    // 256 entries for 3 072 gradient colours: not exact, but the fallback colour cube (5 levels
    // per channel, 32 units apart at most) keeps every colour within sqrt(3) * 32 = 55.4 of an
    // entry, so no channel is off by more than 55.
    EXPECT_GT(worst, 0);
    EXPECT_LE(worst, 55);
}

// Same frames and settings, same bytes; for VP9 and FFV1 also across encoder thread counts
// (their tiles and slices follow the frame size, not the threads). x264's bytes do depend on
// its thread count, which is why SinkDef pins it; VideoSinkTest covers its repeatability.
TEST(OutputFormatsTest, EveryFormatIsByteIdenticalAcrossRunsAndEncoderThreads) {
    const auto directory = scratch_directory();
    const auto frames = animation(12);
    struct Case {
        std::string name;
        bool lossless;
        bool threads_change_bytes;
    };
    for (const Case& c : {Case{"h264.mkv", false, true}, Case{"vp9.webm", false, false},
                          Case{"a.gif", false, false}, Case{"ffv1.mkv", true, false},
                          Case{"a.mp4", false, true}}) {
        const auto bytes_with = [&](const std::string& run, int threads) {
            std::filesystem::create_directories(directory / run);
            SinkDef def = small_def(directory / run / c.name);
            def.lossless = c.lossless;
            def.threads = threads;
            write_frames(def, frames);
            return file_bytes(def.path);
        };
        const auto first = bytes_with("first", 2);
        ASSERT_FALSE(first.empty()) << c.name;
        EXPECT_TRUE(bytes_with("second", 2) == first) << c.name;
        if (!c.threads_change_bytes) {
            EXPECT_TRUE(bytes_with("one-thread", 1) == first) << c.name;
            EXPECT_TRUE(bytes_with("three-threads", 3) == first) << c.name;
        }
    }
}

TEST(OutputFormatsTest, PngSequenceFramesAreTheStills) {
    const auto directory = scratch_directory();
    const auto frames = animation(5);
    write_frames(small_def(directory / "frame_%03d.png"), frames);
    EXPECT_EQ(directory_entries(directory),
              (std::vector<std::string>{"frame_000.png", "frame_001.png", "frame_002.png",
                                        "frame_003.png", "frame_004.png"}));
    for (int i = 0; i < 5; ++i) {
        const auto still = directory / ("still" + std::to_string(i) + ".png");
        write_frames(small_def(still), {frames[i]});
        EXPECT_TRUE(file_bytes(still) ==
                    file_bytes(directory / ("frame_00" + std::to_string(i) + ".png")))
            << i;
    }
}

TEST(OutputFormatsTest, AbandonedPngSequenceLeavesNoPartialSet) {
    const auto directory = scratch_directory();
    write_file(directory / "f1.png", "an earlier frame");
    {
        auto sink = open_sink(small_def(directory / "f%d.png"));
        ASSERT_TRUE(sink.ok()) << sink.error().message;
        for (int i = 0; i < 3; ++i) {
            ASSERT_TRUE((*sink)->write(moving_shapes_frame(width, height, i).view()).ok());
        }
        // destroyed without finish()
    }
    EXPECT_EQ(directory_entries(directory), std::vector<std::string>{"f1.png"});
    const auto bytes = file_bytes(directory / "f1.png");
    EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "an earlier frame");
}

TEST(OutputFormatsTest, PngSequenceInAMissingDirectoryFailsOnOpen) {
    const auto directory = scratch_directory();
    const auto path = directory / "x" / "f%04d.png";
    auto sink = open_sink(small_def(path));
    ASSERT_FALSE(sink.ok());
    EXPECT_EQ(sink.error().message, "cannot write '" + (directory / "x" / "f0000.png").string() +
                                        "': directory '" + (directory / "x").string() +
                                        "' does not exist");
}

}  // namespace
}  // namespace discreel::encode::test
