// Segments (docs/scale.md): a video file is encoded in segments of video.segment seconds and
// joined by stream copy, so its bytes are the same for any --jobs and for segments rendered
// apart (--segment K) and joined with `discreel concat`. Through the binary, so GL; ffprobe
// and the ffmpeg CLI are the independent readers.
#include <sys/stat.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <sstream>

#include "test_support.hpp"

namespace discreel {
namespace {

using testing::probe_video;
using testing::read_file;
using testing::run_command;
using testing::TempDir;
using testing::write_file;

const std::string bin = DISCREEL_BIN;

// 160x120 at 24 fps for 2.5 s: 60 frames, in segments of 0.5 s (12 frames): 5 segments. Trails
// and a follow camera remember earlier frames, and a throw and a bounce fall inside segments,
// so a segment's frames depend on everything before them.
const std::string scene_text = R"(version: 1
video: {size: [160, 120], fps: 24, duration: 2.5, segment: 0.5}
physics: {rate: 480, restitution: 0.8}
camera: {follow: red, height: 3}
style: {trails: {length: 0.5}, clock: {format: frame}}
walls:
  - box: [[0, 0], [4, 3]]
discs:
  - {id: red, position: [1, 2], velocity: [3, 0], radius: 0.3, color: "#e4572e"}
  - {id: teal, position: [3, 1], velocity: [-1, 3], radius: 0.25, color: "#17bebb"}
throws:
  - {disc: red, at: 0.9, velocity: [-3, 4]}
)";

struct Scene {
    TempDir dir;
    std::string path = dir / "scene.yaml";
    Scene() { write_file(path, scene_text); }
};

testing::CommandResult discreel(std::vector<std::string> args) {
    args.insert(args.begin(), bin);
    return run_command(args);
}

// Every way of rendering the clip gives the same file, in each container: --jobs 1, 2 and 3,
// the default, and the five segments rendered one by one (in reverse, as a farm may finish
// them) and joined.
TEST(SegmentsGLTest, EveryWayOfRenderingGivesTheSameBytes) {
    Scene scene;
    for (const std::string format : {"mp4", "mkv", "webm"}) {
        SCOPED_TRACE(format);
        const std::string whole = scene.dir / ("default." + format);
        ASSERT_EQ(discreel({"render", scene.path, "-o", whole, "-q"}).exit_code, 0);
        const std::string expected = read_file(whole);
        ASSERT_GT(expected.size(), 1000u);
        for (const std::string jobs : {"1", "2", "3"}) {
            const std::string out = scene.dir / ("jobs" + jobs + "." + format);
            const auto run = discreel({"render", scene.path, "-o", out, "--jobs", jobs, "-q"});
            ASSERT_EQ(run.exit_code, 0) << run.err;
            EXPECT_EQ(read_file(out), expected) << "--jobs " << jobs;
        }
        const std::string segments = scene.dir / ("segments-" + format);
        for (int k = 4; k >= 0; --k) {
            const auto run = discreel({"render", scene.path, "-o", segments, "--segment",
                                       std::to_string(k), "--format", format});
            ASSERT_EQ(run.exit_code, 0) << run.err;
            EXPECT_EQ(run.out, "wrote " + segments + "/segment-000" + std::to_string(k) +
                                   "-of-0005." + format + ": 12 frames, 160x120, 0.50 s at 24 "
                                   "fps, frames " + std::to_string(12 * k) + ".." +
                                   std::to_string(12 * k + 11) + run.out.substr(run.out.find(" (")));
        }
        const std::string joined = scene.dir / ("joined." + format);
        const auto concat = discreel({"concat", segments, "-o", joined});
        ASSERT_EQ(concat.exit_code, 0) << concat.err;
        EXPECT_EQ(concat.out, "wrote " + joined + ": 5 segments joined\n");
        EXPECT_EQ(read_file(joined), expected);
        // What a player sees: 60 frames, 2.5 s, each segment opening with a keyframe.
        const auto probe = probe_video(joined);
        EXPECT_EQ(probe.at("nb_read_frames"), "60");
        EXPECT_EQ(probe.at("r_frame_rate"), "24/1");
    }
}

// The keyframes are the segments' first frames and no others (scene cuts are off), and the
// file plays for exactly the clip's duration.
TEST(SegmentsGLTest, EachSegmentIsOneClosedGroupOfPictures) {
    Scene scene;
    const std::string out = scene.dir / "clip.mp4";
    ASSERT_EQ(discreel({"render", scene.path, "-o", out, "-q"}).exit_code, 0);
    const auto frames = run_command({"ffprobe", "-v", "error", "-select_streams", "v",
                                     "-show_entries", "frame=key_frame,pict_type", "-of", "csv=p=0",
                                     out});
    ASSERT_EQ(frames.exit_code, 0) << frames.err;
    std::vector<int> keyframes;
    std::istringstream lines(frames.out);
    std::string line;
    int n = 0;
    while (std::getline(lines, line)) {
        // "KEY,TYPE", with a further field where the frame has side data (x264's SEI with
        // its settings, once per segment); other lines are that side data's.
        if (line.size() < 3 || line[1] != ',' || line.find_first_of("IPB") != 2) continue;
        if (line[0] == '1') keyframes.push_back(n);
        ++n;
    }
    EXPECT_EQ(n, 60);
    EXPECT_EQ(keyframes, (std::vector<int>{0, 12, 24, 36, 48}));
    const auto duration = run_command({"ffprobe", "-v", "error", "-show_entries",
                                       "format=duration", "-of", "csv=p=0", out});
    EXPECT_EQ(duration.out, "2.500000\n");
}

// A segment rendered on its own shows exactly the frames a whole render draws there: its
// worker simulated (and remembered, for trails and the camera) every frame before it. Lossless
// FFV1 against a PNG sequence of the whole clip drawn in one pass.
TEST(SegmentsGLTest, ASegmentsFramesAreTheWholeRendersFrames) {
    Scene scene;
    const std::string segments = scene.dir / "lossless";
    auto run = discreel({"render", scene.path, "-o", segments, "--segment", "3", "--format",
                         "mkv", "--lossless", "-q"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    run = discreel({"render", scene.path, "-o", scene.dir / "f_%02d.png", "-q"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto decode = [](std::vector<std::string> input) {
        std::vector<std::string> argv{"ffmpeg", "-v", "error"};
        argv.insert(argv.end(), input.begin(), input.end());
        for (const char* arg : {"-pix_fmt", "rgb24", "-f", "framemd5", "-"}) argv.emplace_back(arg);
        const auto decoded = run_command(argv);
        std::vector<std::string> sums;
        std::istringstream lines(decoded.out);
        std::string line;
        while (std::getline(lines, line)) {
            if (!line.empty() && line[0] != '#') sums.push_back(line.substr(line.rfind(',') + 1));
        }
        return sums;
    };
    const auto segment = decode({"-i", segments + "/segment-0003-of-0005.mkv"});
    const auto whole = decode({"-start_number", "36", "-i", scene.dir / "f_%02d.png",
                               "-frames:v", "12"});
    ASSERT_EQ(segment.size(), 12u);
    EXPECT_EQ(segment, whole);
}

// The soundtrack (docs/sound.md) travels with the segments: AAC in MP4 and Matroska, Opus in
// WebM, encoded once over the joined samples, so --jobs and concat give the same bytes with
// sound too, and sound and pictures end together (within one audio frame: 1024 or 960
// samples, 21 ms).
TEST(SegmentsGLTest, SoundJoinsWithTheSegments) {
    Scene scene;
    write_file(scene.path, scene_text + "audio: {enabled: true, volume: 0.7}\n");
    for (const auto& [format, codec] :
         std::vector<std::pair<std::string, std::string>>{{"mp4", "aac"}, {"mkv", "aac"},
                                                          {"webm", "opus"}}) {
        SCOPED_TRACE(format);
        const std::string whole = scene.dir / ("jobs1." + format);
        ASSERT_EQ(discreel({"render", scene.path, "-o", whole, "--jobs", "1", "-q"}).exit_code, 0);
        const std::string two = scene.dir / ("jobs2." + format);
        ASSERT_EQ(discreel({"render", scene.path, "-o", two, "--jobs", "2", "-q"}).exit_code, 0);
        EXPECT_EQ(read_file(two), read_file(whole));
        const std::string parts = scene.dir / ("parts-" + format);
        for (const std::string k : {"4", "2", "0", "1", "3"}) {
            ASSERT_EQ(discreel({"render", scene.path, "-o", parts, "--segment", k, "--format",
                                format, "-q"})
                          .exit_code,
                      0);
        }
        EXPECT_TRUE(std::filesystem::exists(parts + "/segment-0002-of-0005.wav"));
        const std::string joined = scene.dir / ("joined." + format);
        ASSERT_EQ(discreel({"concat", parts, "-o", joined, "-q"}).exit_code, 0);
        EXPECT_EQ(read_file(joined), read_file(whole));

        const auto streams = run_command({"ffprobe", "-v", "error", "-count_packets",
                                          "-show_entries", "stream=codec_name,sample_rate",
                                          "-of", "csv=p=0", whole});
        EXPECT_EQ(streams.out, (format == "webm" ? "vp9\n" : "h264\n") + codec + ",48000\n");
        // Where each stream starts and ends on the file's clock (Matroska shifts both by the
        // AAC encoder's delay): the sound ends with the pictures, within one audio frame (the
        // encoders pad their last one; 1024 or 960 samples, 21 ms).
        const auto span_of = [&](const std::string& stream) {
            const auto packets = run_command({"ffprobe", "-v", "error", "-select_streams",
                                              stream, "-show_entries",
                                              "packet=pts_time,duration_time", "-of", "csv=p=0",
                                              whole});
            std::pair<double, double> span{1e9, -1e9};
            std::istringstream lines(packets.out);
            for (std::string line; std::getline(lines, line);) {
                const auto comma = line.find(',');
                if (comma == std::string::npos || line.find("N/A") != std::string::npos) continue;
                const double pts = std::stod(line.substr(0, comma));
                span.first = std::min(span.first, pts);
                span.second = std::max(span.second, pts + std::stod(line.substr(comma + 1)));
            }
            return span;
        };
        const auto video = span_of("v:0");
        EXPECT_NEAR(video.second - video.first, 2.5, 0.002);   // Matroska's clock is in ms
        EXPECT_NEAR(span_of("a:0").second, video.second, 0.0215);
        EXPECT_EQ(testing::probe_video(whole).at("nb_read_frames"), "60");
        EXPECT_EQ(run_command({"ffmpeg", "-v", "error", "-i", whole, "-map", "0:a", "-f", "null",
                               "-"})
                      .err,
                  "");
    }
    // --no-audio: the pictures alone, the same bytes as a scene without sound.
    ASSERT_EQ(discreel({"render", scene.path, "-o", scene.dir / "silent.mp4", "--no-audio",
                        "-q"}).exit_code, 0);
    const auto streams = run_command({"ffprobe", "-v", "error", "-show_entries",
                                      "stream=codec_name", "-of", "csv=p=0",
                                      scene.dir / "silent.mp4"});
    EXPECT_EQ(streams.out, "h264\n");
    // A missing sound is named; formats without sound refuse --audio.
    std::filesystem::remove(scene.dir / "parts-mp4/segment-0003-of-0005.wav");
    auto run = discreel({"concat", scene.dir / "parts-mp4", "-o", scene.dir / "x.mp4"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: '" + scene.dir / "parts-mp4" + "' lacks the sound of segment 3 "
                       "(segment-0003-of-0005.wav); render it again with --segment 3\n");
    run = discreel({"render", scene.path, "-o", scene.dir / "x.gif", "--audio"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err,
              "discreel: --audio: gif carries no sound; write .mp4, .mkv, .webm, - or .wav\n");
}

// --dry-run: the plan a script submits tasks by (deploy/slurm/clip.sh), and nothing written.
TEST(SegmentsGLTest, DryRunPrintsThePlan) {
    Scene scene;
    auto run = discreel({"render", scene.path, "-o", scene.dir / "clip.webm", "--fps", "30",
                         "--dry-run"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.out, "output=" + scene.dir / "clip.webm" +
                           "\nformat=webm\nsize=160x120\nfps=30\nframes=0-74\nsegments=5\n"
                           "segment_frames=15\naudio=no\n");
    run = discreel({"render", scene.path, "-o", scene.dir / "parts", "--segment", "2",
                    "--dry-run"});
    EXPECT_EQ(run.out, "output=" + scene.dir / "parts/segment-0002-of-0005.mp4" +
                           "\nformat=mp4\nsize=160x120\nfps=24\nframes=24-35\nsegments=5\n"
                           "segment_frames=12\naudio=no\n");
    run = discreel({"render", scene.path, "-o", scene.dir / "clip.gif", "--dry-run"});
    EXPECT_NE(run.out.find("\nsegments=0\n"), std::string::npos) << run.out;
    EXPECT_EQ(testing::directory_entries(scene.dir.path()), std::vector<std::string>{"scene.yaml"});
}

TEST(SegmentsGLTest, MistakesAreNamed) {
    Scene scene;
    auto run = discreel({"render", scene.path, "-o", scene.dir / "s", "--segment", "5"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: --segment 5 is past the end: the clip has 5 segments (0..4)\n");
    EXPECT_FALSE(std::filesystem::exists(scene.dir / "s"));
    run = discreel({"render", scene.path, "-o", scene.dir / "s", "--segment", "0", "--trace",
                    scene.dir / "t.csv"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err,
              "discreel: --trace, --events, --joints and the ground truth (--shapes, --camera, "
              "--masks, --boxes) belong to a whole render, not to one segment\n");

    const std::string dir = scene.dir / "parts";
    for (const std::string k : {"0", "1", "3", "4"}) {
        ASSERT_EQ(discreel({"render", scene.path, "-o", dir, "--segment", k, "-q"}).exit_code, 0);
    }
    run = discreel({"concat", dir, "-o", scene.dir / "out.mp4"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: '" + dir + "' lacks segment 2 of 5 (segment-0002-of-0005.mp4); "
                       "render it with --segment 2\n");
    ASSERT_EQ(discreel({"render", scene.path, "-o", dir, "--segment", "2", "-q"}).exit_code, 0);
    run = discreel({"concat", dir, "-o", scene.dir / "out.webm"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: the segments are mp4 files; join them into a .mp4 file, not '" +
                           scene.dir / "out.webm" + "'\n");
    // Segments of another render (other crf, so other encoder settings) in the same directory.
    ASSERT_EQ(discreel({"render", scene.path, "-o", scene.dir / "other", "--segment", "2",
                        "--crf", "30", "--size", "320x240", "-q"})
                  .exit_code,
              0);
    std::filesystem::copy_file(scene.dir / "other/segment-0002-of-0005.mp4",
                               dir + "/segment-0002-of-0005.mp4",
                               std::filesystem::copy_options::overwrite_existing);
    run = discreel({"concat", dir, "-o", scene.dir / "out.mp4"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: segment '" + dir + "/segment-0002-of-0005.mp4' was not "
                       "encoded like '" + dir + "/segment-0000-of-0005.mp4' (codec, size, frame "
                       "rate or encoder settings differ); join the segments of one render\n");
    write_file(dir + "/segment-0001-of-0004.mkv", "");
    run = discreel({"concat", dir, "-o", scene.dir / "out.mp4"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_NE(run.err.find("holds segments of different renders"), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(scene.dir / "out.mp4"));
    run = discreel({"concat", scene.dir / "none", "-o", scene.dir / "out.mp4"});
    EXPECT_EQ(run.exit_code, 2);
}

// What concat must never do: overwrite one of its own inputs, join a cut-off sound, join one
// file twice, or wait for ever on a FIFO.
TEST(SegmentsGLTest, ConcatRefusesWhatWouldLoseOrHangIt) {
    Scene scene;
    write_file(scene.path, scene_text + "audio: {enabled: true}\n");
    const std::string dir = scene.dir / "parts";
    for (const std::string k : {"0", "1", "2", "3", "4"}) {
        ASSERT_EQ(discreel({"render", scene.path, "-o", dir, "--segment", k, "-q"}).exit_code, 0);
    }
    const std::string two = dir + "/segment-0002-of-0005.mp4";
    const std::string kept = read_file(two);
    auto run = discreel({"concat", dir, "-o", two});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: -o '" + two + "' is the same file as segment '" + two +
                           "', which it would overwrite; write to another file\n");
    EXPECT_EQ(read_file(two), kept);

    // A sound cut off after 1 000 bytes: the later sounds would come early.
    const std::string sound = dir + "/segment-0002-of-0005.wav";
    const std::string whole_sound = read_file(sound);
    write_file(sound, whole_sound.substr(0, 1000));
    run = discreel({"concat", dir, "-o", scene.dir / "out.mp4"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: the sound '" + sound + "' holds 239 samples, and its "
                       "segment's 12 frames need 24000; render segment 2 again\n");
    write_file(sound, whole_sound);

    // Two names of one file.
    const std::string three = dir + "/segment-0003-of-0005.mp4";
    std::filesystem::rename(three, scene.dir / "three.mp4");
    std::filesystem::create_symlink(dir + "/segment-0001-of-0005.mp4", three);
    run = discreel({"concat", dir, "-o", scene.dir / "out.mp4"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: '" + three + "' and '" + dir + "/segment-0001-of-0005.mp4' "
                       "are the same file; each segment must be its own\n");
    std::filesystem::remove(three);
    std::filesystem::rename(scene.dir / "three.mp4", three);

    // A FIFO for a segment: refused at once, not waited on.
    const std::string four = dir + "/segment-0004-of-0005.mp4";
    std::filesystem::remove(four);
    ASSERT_EQ(mkfifo(four.c_str(), 0644), 0);
    const auto started = std::chrono::steady_clock::now();
    run = discreel({"concat", dir, "-o", scene.dir / "out.mp4"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: '" + four + "' is not a regular file; segments and their "
                       "sounds are files that render --segment wrote\n");
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(5));
    EXPECT_FALSE(std::filesystem::exists(scene.dir / "out.mp4"));

    // An output that is a FIFO nobody reads: refused at once too.
    const std::string fifo = scene.dir / "sound.wav";
    ASSERT_EQ(mkfifo(fifo.c_str(), 0644), 0);
    run = discreel({"render", scene.path, "-o", fifo});
    EXPECT_EQ(run.exit_code, 3);
    EXPECT_EQ(run.err, "discreel: cannot write '" + fifo +
                           "': it is a FIFO that no process is reading\n");
}

}  // namespace
}  // namespace discreel
