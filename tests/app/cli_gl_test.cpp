// The discreel binary end to end: scene file -> physics -> OSMesa -> libav -> file, checked
// with ffprobe and byte comparisons. "GL" in the suite names: these need an OSMesa context.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "test_support.hpp"

namespace discreel {
namespace {

using testing::probe_video;
using testing::read_file;
using testing::run_command;
using testing::TempDir;

const std::string bin = DISCREEL_BIN;
const std::string short_scene = std::string(DISCREEL_SOURCE_DIR) + "/tests/data/scenes/short.yaml";

TEST(CliGLTest, RendersAnMp4ThatFfprobeAccepts) {
    TempDir dir;
    const auto run = run_command({bin, "render", short_scene, "-o", dir / "clip.mp4"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.err, "");

    auto probe = probe_video(dir / "clip.mp4");
    EXPECT_EQ(probe["codec_name"], "h264");
    EXPECT_EQ(probe["pix_fmt"], "yuv420p");
    EXPECT_EQ(probe["width"], "160");
    EXPECT_EQ(probe["height"], "120");
    EXPECT_EQ(probe["nb_read_frames"], "30");   // round(1.25 s * 24 fps)
    EXPECT_NEAR(std::stod(probe["duration"]), 1.25, 1e-6);
    EXPECT_EQ(probe["color_space"], "bt709");
    EXPECT_EQ(probe["color_primaries"], "bt709");
    EXPECT_EQ(probe["color_transfer"], "bt709");
    EXPECT_EQ(probe["color_range"], "tv");

    // +faststart: the index comes before the media data, so players can start streaming.
    const auto boxes = testing::mp4_top_level_boxes(dir / "clip.mp4");
    const auto moov = std::find(boxes.begin(), boxes.end(), "moov");
    const auto mdat = std::find(boxes.begin(), boxes.end(), "mdat");
    ASSERT_NE(moov, boxes.end());
    ASSERT_NE(mdat, boxes.end());
    EXPECT_LT(moov, mdat);

    EXPECT_EQ(run.out.rfind("wrote " + (dir / "clip.mp4") + ": 30 frames, 160x120, 1.25 s at 24 fps", 0), 0u)
        << run.out;
}

TEST(CliGLTest, SameSceneSameBytes) {
    TempDir dir;
    ASSERT_EQ(run_command({bin, "render", short_scene, "-o", dir / "a.mp4"}).exit_code, 0);
    ASSERT_EQ(run_command({bin, "render", short_scene, "-o", dir / "b.mp4"}).exit_code, 0);
    const std::string a = read_file(dir / "a.mp4");
    EXPECT_GT(a.size(), 1000u);
    EXPECT_TRUE(a == read_file(dir / "b.mp4"));
}

TEST(CliGLTest, PngStillOfOneFrame) {
    TempDir dir;
    const auto run = run_command({bin, "render", short_scene, "-o", dir / "f.png", "--frame", "12"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    auto probe = probe_video(dir / "f.png");
    EXPECT_EQ(probe["codec_name"], "png");
    EXPECT_EQ(probe["width"], "160");
    EXPECT_EQ(probe["height"], "120");

    // --at picks the frame nearest to that time: 0.5 s at 24 fps is frame 12.
    ASSERT_EQ(run_command({bin, "render", short_scene, "-o", dir / "at.png", "--at", "0.5"}).exit_code, 0);
    EXPECT_TRUE(read_file(dir / "f.png") == read_file(dir / "at.png"));
    // ...and a different frame is a different picture.
    ASSERT_EQ(run_command({bin, "render", short_scene, "-o", dir / "g.png", "--frame", "29"}).exit_code, 0);
    EXPECT_FALSE(read_file(dir / "f.png") == read_file(dir / "g.png"));
}

TEST(CliGLTest, BuiltInDemoRendersFromAnyDirectory) {
    TempDir dir;
    const auto run = run_command({bin, "render", "-o", dir / "demo.png", "--frame", "150",
                                  "--size", "320x180"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    auto probe = probe_video(dir / "demo.png");
    EXPECT_EQ(probe["width"], "320");
    EXPECT_EQ(probe["height"], "180");
}

TEST(CliGLTest, FrameOutsideTheClipIsABadCommandLine) {
    TempDir dir;
    const auto run = run_command({bin, "render", short_scene, "-o", dir / "f.png", "--frame", "30"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err,
              "discreel: frame 30 is outside the clip, which has 30 frames (0..29, or -30..-1 "
              "counted from the end)\n");
    EXPECT_FALSE(std::filesystem::exists(dir / "f.png"));
}

TEST(CliGLTest, UnknownOutputExtensionIsABadCommandLine) {
    TempDir dir;
    const auto run = run_command({bin, "render", short_scene, "-o", dir / "clip.avi"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err,
              "discreel: unsupported output extension '.avi' (supported: .mp4 (H.264), .mkv "
              "(H.264, VP9, or FFV1 lossless), .webm (VP9), .gif, .png (one frame, or every frame "
              "for a numbered name such as frame_%04d.png), - (Matroska or fragmented MP4 on "
              "standard output), .wav (the soundtrack alone))\n");
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(CliGLTest, EveryVideoFormatFromTheCommandLine) {
    TempDir dir;
    struct Case {
        std::vector<std::string> args;
        std::string codec, pix_fmt, color_space;
    };
    const std::vector<Case> cases = {
        {{"-o", dir / "h264.mkv"}, "h264", "yuv420p", "bt709"},
        {{"-o", dir / "crisp.mp4", "--pix-fmt", "yuv444p", "--crf", "18", "--preset", "fast"},
         "h264", "yuv444p", "bt709"},
        {{"-o", dir / "clip.webm", "--crf", "40"}, "vp9", "yuv420p", "bt709"},
        {{"-o", dir / "vp9.mkv", "--codec", "vp9"}, "vp9", "yuv420p", "bt709"},
        {{"-o", dir / "exact.mkv", "--lossless"}, "ffv1", "bgr0", "gbr"},
        {{"-o", dir / "clip.gif"}, "gif", "bgra", ""},
    };
    // A GIF shows the scene's 24 fps at 20 fps, the fastest rate its delays express at or
    // below it: 1.25 s is 25 frames.
    for (const Case& c : cases) {
        std::vector<std::string> argv = {bin, "render", short_scene};
        argv.insert(argv.end(), c.args.begin(), c.args.end());
        const auto run = run_command(argv);
        ASSERT_EQ(run.exit_code, 0) << c.args[1] << ": " << run.err;
        auto probe = probe_video(c.args[1]);
        EXPECT_EQ(probe["codec_name"], c.codec) << c.args[1];
        EXPECT_EQ(probe["pix_fmt"], c.pix_fmt) << c.args[1];
        EXPECT_EQ(probe["width"], "160") << c.args[1];
        EXPECT_EQ(probe["height"], "120") << c.args[1];
        EXPECT_EQ(probe["nb_read_frames"], c.codec == "gif" ? "25" : "30") << c.args[1];
        if (!c.color_space.empty()) {
            EXPECT_EQ(probe["color_space"], c.color_space) << c.args[1];
        }
    }
}

// "Any thread count": the renderer's thread count (llvmpipe's LP_NUM_THREADS) must not change a
// byte of any format; the encoders' thread counts are pinned in the sink.
TEST(CliGLTest, SameBytesWhateverTheRendererThreadCount) {
    TempDir dir;
    for (const std::string name : {"clip.mp4", "clip.webm", "clip.gif", "exact.mkv"}) {
        std::vector<std::string> outputs;
        for (const std::string threads : {"1", "4"}) {
            const std::string output = dir / (threads + name);
            std::vector<std::string> argv = {bin, "render", short_scene, "-o", output};
            if (name == "exact.mkv") argv.push_back("--lossless");
            const auto run = run_command(argv, {{"LP_NUM_THREADS", threads}});
            ASSERT_EQ(run.exit_code, 0) << run.err;
            outputs.push_back(read_file(output));
        }
        EXPECT_GT(outputs[0].size(), 1000u) << name;
        EXPECT_TRUE(outputs[0] == outputs[1]) << name;
    }
}

TEST(CliGLTest, PngSequenceFramesEqualTheStills) {
    TempDir dir;
    std::filesystem::create_directory(dir / "seq");
    const auto run = run_command({bin, "render", short_scene, "-o", dir / "seq/frame_%04d.png"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path() / "seq"),
                            std::filesystem::directory_iterator()), 30);
    for (const std::string frame : {"0", "12", "29"}) {
        const std::string still = dir / ("still" + frame + ".png");
        ASSERT_EQ(run_command({bin, "render", short_scene, "-o", still, "--frame", frame}).exit_code, 0);
        const std::string numbered = std::string(4 - frame.size(), '0') + frame;
        EXPECT_TRUE(read_file(still) == read_file(dir / ("seq/frame_" + numbered + ".png"))) << frame;
    }
}

TEST(CliGLTest, DashWritesStreamableMatroskaToStdoutAndTheSummaryToStderr) {
    TempDir dir;
    const auto first = run_command({bin, "render", short_scene, "-o", "-"});
    ASSERT_EQ(first.exit_code, 0) << first.err;
    EXPECT_EQ(first.err.rfind("wrote -: 30 frames, 160x120, 1.25 s at 24 fps", 0), 0u) << first.err;
    testing::write_file(dir / "piped.mkv", first.out);
    auto probe = probe_video(dir / "piped.mkv");
    EXPECT_EQ(probe["codec_name"], "h264");
    EXPECT_EQ(probe["nb_read_frames"], "30");
    EXPECT_EQ(probe["color_space"], "bt709");
    // Written for a pipe: Matroska's EBML header first, and no index (Cues), which would need
    // seeking back to write.
    EXPECT_EQ(first.out.substr(0, 4), std::string("\x1a\x45\xdf\xa3"));
    EXPECT_EQ(first.out.find(std::string("\x1c\x53\xbb\x6b")), std::string::npos);
    EXPECT_TRUE(run_command({bin, "render", short_scene, "-o", "-"}).out == first.out);
}

// `--format mp4` streams fragmented MP4 instead, for tools that want MP4 from a pipe.
TEST(CliGLTest, DashWithFormatMp4WritesFragmentedMp4ToStdout) {
    TempDir dir;
    const auto first = run_command({bin, "render", short_scene, "-o", "-", "--format", "mp4"});
    ASSERT_EQ(first.exit_code, 0) << first.err;
    testing::write_file(dir / "piped.mp4", first.out);
    auto probe = probe_video(dir / "piped.mp4");
    EXPECT_EQ(probe["codec_name"], "h264");
    EXPECT_EQ(probe["nb_read_frames"], "30");
    EXPECT_EQ(probe["color_space"], "bt709");
    // Written for a pipe: an empty moov up front, then fragments (moof + mdat), no index at
    // the end to seek back for.
    const auto boxes = testing::mp4_top_level_boxes(dir / "piped.mp4");
    ASSERT_GE(boxes.size(), 4u);
    EXPECT_EQ(boxes[0], "ftyp");
    EXPECT_EQ(boxes[1], "moov");
    EXPECT_EQ(boxes[2], "moof");
    EXPECT_EQ(boxes[3], "mdat");
    EXPECT_TRUE(run_command({bin, "render", short_scene, "-o", "-", "--format", "mp4"}).out ==
                first.out);
}

TEST(CliGLTest, FormatOptionsThatDoNotFitAreABadCommandLine) {
    TempDir dir;
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"-o", dir / "c.mkv", "--format", "mp4"},
         "discreel: a container is chosen for standard output (-o -) or a segment "
         "(--segment) only; a file's extension picks its format\n"},
        {{"-o", dir / "c.mp4", "--lossless"},
         "discreel: lossless output is FFV1 in Matroska: use .mkv or -, not .mp4\n"},
        {{"-o", dir / "c.mp4", "--codec", "vp9"},
         "discreel: codec 'vp9' is not available for .mp4 (h264)\n"},
        {{"-o", dir / "c.webm", "--preset", "slow"},
         "discreel: preset does not apply to VP9 (it is an x264 setting)\n"},
        {{"-o", dir / "c.mkv", "--lossless", "--crf", "10"},
         "discreel: crf does not apply to FFV1 (lossless)\n"},
        {{"-o", dir / "c.mp4", "--crf", "52"}, "discreel: crf 52 is outside 0..51\n"},
        {{"-o", dir / "c.mp4", "--pix-fmt", "rgb24"},
         "discreel: pixel format 'rgb24' is not available for H.264 (yuv420p, yuv444p)\n"},
        {{"-o", dir / "c.gif", "--crf", "20"}, "discreel: crf does not apply to GIF\n"},
        {{"-o", dir / "f%04d.png", "--frame", "3"},
         "discreel: --frame and --at select a still; a numbered .png name writes every frame "
         "(--frames A-B writes some)\n"},
        {{"-o", dir / "f%s.png"},
         "discreel: '" + (dir / "f%s.png") + "': a '%' in an output name must be one frame "
         "number, %d or %0Nd such as %04d (write %% for a percent sign)\n"},
    };
    for (const auto& [args, message] : cases) {
        std::vector<std::string> argv = {bin, "render", short_scene};
        argv.insert(argv.end(), args.begin(), args.end());
        const auto run = run_command(argv);
        EXPECT_EQ(run.exit_code, 2) << message;
        EXPECT_EQ(run.err, message);
    }
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

// Only video in yuv420p needs even sides: a still, a GIF and yuv444p take any size.
TEST(CliGLTest, OddSizesAreForStillsGifsAndFullColourVideo) {
    TempDir dir;
    auto run = run_command({bin, "render", short_scene, "-o", dir / "c.mp4", "--size", "161x120"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: --size 161x120: mp4 video (yuv420p) stores colour at half "
                       "resolution, so its width and height must be even; PNG, GIF and "
                       "--pix-fmt yuv444p take any size\n");
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
    testing::write_file(dir / "odd.yaml", "version: 1\nvideo: {size: [161, 121], duration: 0.2}\n");
    run = run_command({bin, "render", dir / "odd.yaml", "-o", dir / "c.webm"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: video.size 161x121: webm video (yuv420p) stores colour at half "
                       "resolution, so its width and height must be even; PNG, GIF and "
                       "--pix-fmt yuv444p take any size\n");
    for (const std::string name : {"s.png", "c.gif", "f.mp4"}) {
        std::vector<std::string> argv{bin, "render", dir / "odd.yaml", "-o", dir / name};
        if (name == "f.mp4") argv.insert(argv.end(), {"--pix-fmt", "yuv444p"});
        run = run_command(argv);
        ASSERT_EQ(run.exit_code, 0) << name << run.err;
        const auto probe = run_command({"ffprobe", "-v", "error", "-select_streams", "v:0",
                                        "-show_entries", "stream=width,height", "-of", "csv=p=0",
                                        dir / name});
        EXPECT_EQ(probe.out, "161,121\n") << name;
    }
}

TEST(CliGLTest, BadSceneLeavesAnExistingOutputUntouched) {
    TempDir dir;
    testing::write_file(dir / "bad.yaml", "version: 1\nvideo:\n  fsp: 30\n");
    testing::write_file(dir / "out.mp4", "precious");
    const auto run = run_command({bin, "render", dir / "bad.yaml", "-o", dir / "out.mp4"});
    EXPECT_EQ(run.exit_code, 2);
    // The message itself is the scene module's (checked word for word in its tests); here we
    // check it reaches the user as file:line:column.
    EXPECT_EQ(run.err.rfind(dir / "bad.yaml" + ":3:3: ", 0), 0u) << run.err;
    EXPECT_EQ(read_file(dir / "out.mp4"), "precious");
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()),
                            std::filesystem::directory_iterator()), 2);
}

// A missing directory is made (FaultsGLTest); a file in its place cannot be.
TEST(CliGLTest, AFileWhereTheOutputDirectoryShouldBeIsARunTimeFailure) {
    TempDir dir;
    testing::write_file(dir / "nowhere", "");
    const auto run = run_command({bin, "render", short_scene, "-o", dir / "nowhere/c.mp4"});
    EXPECT_EQ(run.exit_code, 3);
    EXPECT_NE(run.err.find(dir / "nowhere"), std::string::npos) << run.err;
}

TEST(CliTest, VersionAndHelp) {
    const auto version = run_command({bin, "--version"});
    EXPECT_EQ(version.exit_code, 0);
    EXPECT_EQ(version.out, "discreel 0.1.0\n");
    const auto help = run_command({bin, "render", "--help"});
    EXPECT_EQ(help.exit_code, 0);
    EXPECT_NE(help.out.find("--output"), std::string::npos);
    EXPECT_NE(help.out.find("built-in demo"), std::string::npos);
}

TEST(CliTest, UnknownCommandIsABadCommandLine) {
    const auto run = run_command({bin, "paint"});
    EXPECT_EQ(run.exit_code, 2);
}

TEST(CliTest, ValidateReportsEachScene) {
    TempDir dir;
    testing::write_file(dir / "bad.yaml", "version: 1\nvideo:\n  fsp: 30\n");
    const auto good = run_command({bin, "validate", short_scene});
    EXPECT_EQ(good.exit_code, 0) << good.err;
    EXPECT_EQ(good.out, short_scene + ": ok (3 discs, 30 frames)\n");
    const auto bad = run_command({bin, "validate", short_scene, dir / "bad.yaml"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_EQ(bad.err.rfind(dir / "bad.yaml" + ":3:3: ", 0), 0u) << bad.err;
}

// A scene beyond the range a crowd holds loads with a warning and runs: two 5 cm discs head-on
// at 1 000 m/s each at the default rate (20 radii per step), among eight resting ones (a crowd,
// which speeds are judged in), meet at the exact time t* = 1.9 m / 2 000 m/s and swap
// velocities, so at 0.4 s each is back at 0.05 + 1 000 (0.4 - t*) m from the centre.
TEST(CliTest, ASceneBeyondTheCrowdRangeRunsWithAWarningPerSpeed) {
    TempDir dir;
    testing::write_file(dir / "fast.yaml", R"(version: 1
video: {duration: 0.5, fps: 10}
physics: {gravity: [0, 0]}
discs:
  - {id: left, position: [-1, 0], radius: 0.05, velocity: [1000, 0], restitution: 1}
  - {id: right, position: [1, 0], radius: 0.05, velocity: [-1000, 0], restitution: 1}
  - grid: {origin: [-2, 5], count: [8, 1], spacing: [0.5, 1], radius: 0.05}
)");
    const auto run = run_command({bin, "simulate", dir / "fast.yaml", "--trace", dir / "t.csv"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const std::string beyond =
        "1000 m/s: crowds of this scene's bodies are measured to stay apart up to 240 m/s at "
        "480 Hz (10 radii of the smallest moving body, 'left', 0.05 m, per physics step); where "
        "several bodies this fast meet at once they may overlap; physics.rate 2000 or more keeps "
        "them apart (docs/physics.md, Limits)\n";
    EXPECT_EQ(run.err, dir / "fast.yaml" + ":5:59: warning: discs[0].velocity: " + beyond +
                           dir / "fast.yaml" + ":6:59: warning: discs[1].velocity: " + beyond);
    // validate: ok, with the warnings counted.
    const auto validated = run_command({bin, "validate", dir / "fast.yaml"});
    EXPECT_EQ(validated.exit_code, 0);
    EXPECT_EQ(validated.out, dir / "fast.yaml" + ": ok (10 discs, 5 frames, 2 warnings)\n");
    EXPECT_EQ(validated.err, run.err);
    std::istringstream trace(read_file(dir / "t.csv"));
    std::string row, last_left, last_right;
    while (std::getline(trace, row)) {
        if (row.find(",left,") != std::string::npos) last_left = row;
        if (row.find(",right,") != std::string::npos) last_right = row;
    }
    // frame,t,id,x,y,angle,vx,...
    const auto field = [](const std::string& r, int n) {
        std::istringstream in(r);
        std::string value;
        for (int k = 0; k <= n; ++k) std::getline(in, value, ',');
        return std::stod(value);
    };
    const double flown = 0.05 + 1000 * (0.4 - 1.9 / 2000);
    EXPECT_NEAR(field(last_left, 3), -flown, 1e-9);
    EXPECT_NEAR(field(last_right, 3), flown, 1e-9);
    EXPECT_EQ(field(last_left, 6), -1000);
    EXPECT_EQ(field(last_right, 6), 1000);
}

// --max-bodies limits discs and shapes together, generated ones included; --max-discs is the
// same option.
TEST(CliTest, MaxBodiesAndItsAliasMaxDiscsLimitEveryKindOfBody) {
    TempDir dir;
    testing::write_file(dir / "three.yaml", R"(version: 1
discs:
  - {position: [0, 0], radius: 0.5}
bodies:
  - random_polygons: {count: 2, region: [[2, -1], [8, 1]], size: 0.3}
)");
    const std::string refused = dir / "three.yaml" +
                                ":5:5: bodies[0]: this entry brings the scene to 3 bodies; the "
                                "limit is 2 (raise it with --max-bodies)\n";
    for (const char* option : {"--max-bodies", "--max-discs"}) {
        const auto two = run_command({bin, "validate", dir / "three.yaml", option, "2"});
        EXPECT_EQ(two.exit_code, 2) << option;
        EXPECT_EQ(two.err, refused) << option;
        const auto three = run_command({bin, "validate", dir / "three.yaml", option, "3"});
        EXPECT_EQ(three.exit_code, 0) << option << three.err;
        EXPECT_EQ(three.out, dir / "three.yaml" + ": ok (3 bodies, 480 frames)\n") << option;
    }
}

// --duration beyond the file's: the respawns go on to the end of the longer clip, and the trace
// follows them (a new draw, a new bounding radius, at 1 s and at 2 s).
TEST(CliTest, RespawnsLastAsLongAsTheDurationGivenOnTheCommandLine) {
    TempDir dir;
    testing::write_file(dir / "respawn.yaml", R"(version: 1
video: {fps: 10, duration: 1.5}
bodies:
  - random_polygons: {count: 1, region: [[0, 0], [4, 4]], size: [0.2, 0.5], respawn_every: 1}
)");
    const auto run = run_command(
        {bin, "simulate", dir / "respawn.yaml", "--duration", "2.5", "--trace", dir / "t.csv"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    std::istringstream trace(read_file(dir / "t.csv"));
    std::string row;
    std::getline(trace, row);   // the header
    std::vector<std::string> radii;   // each new value of the radius column, in order
    int rows = 0;
    while (std::getline(trace, row)) {
        ++rows;
        const std::size_t end = row.rfind(','), mass = row.rfind(',', end - 1);
        const std::size_t radius = row.rfind(',', mass - 1);
        const std::string value = row.substr(radius + 1, mass - radius - 1);
        if (radii.empty() || radii.back() != value) radii.push_back(value);
    }
    EXPECT_EQ(rows, 25);
    EXPECT_EQ(radii.size(), 3u);
}

// The trajectory depends on the physics rate only: at 30 and 60 fps, frames at the same time
// show bit-identical states.
TEST(CliTest, TraceAgreesAcrossFrameRates) {
    TempDir dir;
    // simulate has no --fps; write two scenes that differ only in fps.
    const std::string base = read_file(short_scene);
    auto with_fps = [&](const std::string& fps) {
        std::string s = base;
        s.replace(s.find("fps: 24"), 7, "fps: " + fps);
        return s;
    };
    testing::write_file(dir / "s30.yaml", with_fps("30"));
    testing::write_file(dir / "s60.yaml", with_fps("60"));
    ASSERT_EQ(run_command({bin, "simulate", dir / "s30.yaml", "--trace", dir / "t30.csv"}).exit_code, 0);
    ASSERT_EQ(run_command({bin, "simulate", dir / "s60.yaml", "--trace", dir / "t60.csv"}).exit_code, 0);

    auto rows = [](const std::string& text) {
        std::vector<std::string> lines;
        std::istringstream in(text);
        for (std::string line; std::getline(in, line);) lines.push_back(line);
        return lines;
    };
    const auto t30 = rows(read_file(dir / "t30.csv"));
    const auto t60 = rows(read_file(dir / "t60.csv"));
    ASSERT_EQ(t30.front(), "frame,t,id,x,y,angle,vx,vy,omega,radius,mass,inertia");
    const std::size_t discs = 3;
    ASSERT_EQ(t30.size(), 1 + discs * 38);   // round(1.25 * 30) = 38 frames
    ASSERT_EQ(t60.size(), 1 + discs * 75);
    auto after_t = [](const std::string& row) {   // drop "frame,t," which differ by design
        return row.substr(row.find(',', row.find(',') + 1) + 1);
    };
    for (std::size_t frame = 0; frame < 38; ++frame) {
        for (std::size_t d = 0; d < discs; ++d) {
            EXPECT_EQ(after_t(t30[1 + frame * discs + d]), after_t(t60[1 + 2 * frame * discs + d]))
                << "frame " << frame;
        }
    }
    // Static discs report mass 0.
    EXPECT_EQ(t30[3].substr(t30[3].rfind(',')), ",0");
}

TEST(CliTest, EventsListNewContactsWithTheirImpulse) {
    TempDir dir;
    const auto run = run_command({bin, "simulate", short_scene, "--events", dir / "events.csv"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    std::istringstream in(read_file(dir / "events.csv"));
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "t,a,b,impulse,kind");
    int rows = 0, wall_rows = 0;
    double previous_t = 0;
    while (std::getline(in, line)) {
        ++rows;
        std::istringstream fields(line);
        std::string t, a, b, impulse, kind;
        std::getline(fields, t, ',');
        std::getline(fields, a, ',');
        std::getline(fields, b, ',');
        std::getline(fields, impulse, ',');
        std::getline(fields, kind, ',');
        EXPECT_EQ(kind, "contact") << line;
        EXPECT_GE(std::stod(t), previous_t) << line;
        previous_t = std::stod(t);
        EXPECT_TRUE(a == "red" || a == "teal" || a == "peg") << line;
        if (b == "wall:0") ++wall_rows;
        EXPECT_GT(std::stod(impulse), 0) << line;
    }
    EXPECT_GT(rows, 0);
    EXPECT_GT(wall_rows, 0);   // both discs are thrown against the box in 1.25 s
    EXPECT_NE(run.out.find("contacts  " + std::to_string(rows) + " new contacts"), std::string::npos)
        << run.out;
}

// The solver's settings (physics.substeps and physics.iterations, discreel's own keys) reach
// the world: simulate says what it ran, and a tuned scene moves differently.
TEST(CliTest, SimulateRunsAndNamesTheSolverSettings) {
    TempDir dir;
    std::string tuned = read_file(short_scene);
    tuned.replace(tuned.find("rate: 480"), 9, "rate: 400\n  substeps: 2\n  iterations: 5");
    testing::write_file(dir / "tuned.yaml", tuned);
    const auto plain = run_command({bin, "simulate", short_scene, "--trace", dir / "plain.csv"});
    const auto run = run_command({bin, "simulate", dir / "tuned.yaml", "--trace", dir / "tuned.csv"});
    ASSERT_EQ(plain.exit_code, 0) << plain.err;
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(plain.out.find("\nsolver    1 substep per step (1/480 s), 3 iterations per "
                             "substep\n"),
              std::string::npos)
        << plain.out;
    EXPECT_NE(run.out.find("\nsolver    2 substeps per step (1/800 s each), 5 iterations "
                           "per substep\n"),
              std::string::npos)
        << run.out;
    EXPECT_NE(read_file(dir / "plain.csv"), read_file(dir / "tuned.csv"));
}

// A bob at rest on a 2 m rod: each frame's row gives the anchors where they are (the world's
// pivot, the bob's centre) and the rod's tension, the bob's weight m g (none before a step).
TEST(CliTest, JointsListEachJointsAnchorsAndForceEveryFrame) {
    TempDir dir;
    testing::write_file(dir / "p.yaml",
                        "version: 1\nvideo: {fps: 30, duration: 0.5}\n"
                        "discs:\n  - {id: bob, position: [1, 3], radius: 0.1, mass: 2}\n"
                        "joints:\n  - distance: {id: rod, b: bob, anchor_a: [1, 5], "
                        "anchor_b: [1, 3]}\n");
    const auto run = run_command({bin, "simulate", dir / "p.yaml", "--joints", dir / "j.csv"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    std::istringstream in(read_file(dir / "j.csv"));
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "frame,t,joint,ax,ay,bx,by,force,torque");
    int rows = 0;
    while (std::getline(in, line)) {
        std::vector<std::string> f;
        std::istringstream fields(line);
        for (std::string v; std::getline(fields, v, ',');) f.push_back(v);
        ASSERT_EQ(f.size(), 9u) << line;
        EXPECT_EQ(f[0], std::to_string(rows)) << line;
        EXPECT_EQ(f[2], "rod") << line;
        EXPECT_EQ(f[3] + "," + f[4], "1,5") << line;
        EXPECT_NEAR(std::stod(f[5]), 1, 1e-12) << line;
        EXPECT_NEAR(std::stod(f[6]), 3, 1e-12) << line;
        EXPECT_NEAR(std::stod(f[7]), rows == 0 ? 0 : 2 * 9.81, 1e-9) << line;
        EXPECT_EQ(f[8], "0") << line;
        ++rows;
    }
    EXPECT_EQ(rows, 15);   // frames 0..14: 0.5 s at 30 fps
}

// render and simulate drive the physics the same way, so their traces are the same bytes.
TEST(CliGLTest, RenderWritesTheSameTraceAsSimulate) {
    TempDir dir;
    ASSERT_EQ(run_command({bin, "simulate", short_scene, "--trace", dir / "sim.csv",
                           "--events", dir / "sim-events.csv"}).exit_code, 0);
    ASSERT_EQ(run_command({bin, "render", short_scene, "-o", dir / "clip.mp4", "--trace",
                           dir / "render.csv", "--events", dir / "render-events.csv"}).exit_code, 0);
    EXPECT_TRUE(read_file(dir / "sim.csv") == read_file(dir / "render.csv"));
    EXPECT_TRUE(read_file(dir / "sim-events.csv") == read_file(dir / "render-events.csv"));
}

TEST(CliTest, UnwritableTraceFailsBeforeAnyWork) {
    TempDir dir;
    testing::write_file(dir / "no", "");   // a file where the trace's directory would be made
    const auto run = run_command({bin, "simulate", short_scene, "--trace", dir / "no/such/dir/t.csv"});
    EXPECT_EQ(run.exit_code, 3);
    EXPECT_EQ(run.err.rfind("discreel: cannot ", 0), 0u) << run.err;
    EXPECT_NE(run.err.find(dir / "no/such/dir"), std::string::npos) << run.err;
}

// A box resting flat on the floor of a box wall, through the binary: the summary names the
// manifold solver and counts bodies, the trace carries the box's inertia m (w^2 + h^2) / 12,
// and its contact with the floor on two points is one event row.
TEST(CliTest, BodiesSimulateWithTheirInertiaAndOneEventPerPair) {
    TempDir dir;
    testing::write_file(dir / "box.yaml", R"(version: 1
video: {fps: 10, duration: 0.5}
physics: {restitution: 0, friction: 0.5}
walls:
  - box: [[0, 0], [4, 4]]
bodies:
  - {id: crate, box: [1, 0.5], position: [2, 0.5], density: 2}
)");
    const auto run = run_command({bin, "simulate", dir / "box.yaml", "--trace", dir / "t.csv",
                                  "--events", dir / "e.csv"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("scene     box: 1 body, 1 wall, 0 throws\n"), std::string::npos)
        << run.out;
    EXPECT_NE(run.out.find("solver    manifold, 1 substep per step (1/480 s), 6 iterations per "
                           "substep\n"),
              std::string::npos)
        << run.out;
    std::istringstream trace(read_file(dir / "t.csv"));
    std::string header, first;
    std::getline(trace, header);
    std::getline(trace, first);
    EXPECT_EQ(header, "frame,t,id,x,y,angle,vx,vy,omega,radius,mass,inertia");
    // mass 2 * 0.5 = 1 kg; inertia (1 + 0.25) / 12 kg m^2 (to the last bit of its sum of
    // parts); radius the half-diagonal.
    EXPECT_EQ(first, "0,0,crate,2,0.5,0,0,0,0,0.5590169943749475,1,0.10416666666666666");
    EXPECT_EQ(read_file(dir / "e.csv").substr(0, 19), "t,a,b,impulse,kind\n");
    std::istringstream events(read_file(dir / "e.csv"));
    std::string line;
    int rows = 0;
    while (std::getline(events, line)) rows += line.find(",crate,wall:0,") != std::string::npos;
    EXPECT_EQ(rows, 1);
}

}  // namespace
}  // namespace discreel
