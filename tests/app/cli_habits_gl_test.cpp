// What users bring from the tools they know (docs/cli.md): frame ranges and the last frame
// (Remotion, Manim), quality presets, machine-readable progress and an overwrite guard (ffmpeg),
// "did you mean" for command-line typos, GIF frame rates that play at the scene's speed,
// transparent backgrounds, and unquoted colours in flow style. Through the binary; "GL" in the
// suite names: these need an OSMesa context.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <sstream>

#include "discreel/encode.hpp"
#include "test_support.hpp"

namespace discreel {
namespace {

namespace fs = std::filesystem;
using testing::probe_video;
using testing::read_file;
using testing::run_command;
using testing::TempDir;
using testing::write_file;

const std::string bin = DISCREEL_BIN;
// 160x120, 24 fps, 1.25 s: 30 frames.
const std::string short_scene = std::string(DISCREEL_SOURCE_DIR) + "/tests/data/scenes/short.yaml";

testing::CommandResult render(std::vector<std::string> extra) {
    std::vector<std::string> argv{bin, "render", short_scene};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return run_command(argv);
}

// GIF delays are whole hundredths of a second: a 60 fps scene becomes a 50 fps GIF of the same
// length, and the summary says so. A frame rate asked for that a GIF cannot play is refused.
TEST(CliHabitsGLTest, GifPlaysAtTheScenesSpeed) {
    TempDir dir;
    const auto run = render({"-o", dir / "c.gif", "--fps", "50", "--duration", "0.5"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    auto probe = probe_video(dir / "c.gif");
    EXPECT_EQ(probe["r_frame_rate"], "50/1");
    EXPECT_EQ(probe["nb_read_frames"], "25");

    write_file(dir / "sixty.yaml", std::regex_replace(read_file(short_scene),
                                                      std::regex("fps: 24"), "fps: 60"));
    const auto sixty = run_command({bin, "render", dir / "sixty.yaml", "-o", dir / "s.gif"});
    ASSERT_EQ(sixty.exit_code, 0) << sixty.err;
    EXPECT_NE(sixty.out.find(": 63 frames, 160x120, 1.25 s at 50 fps (a GIF cannot play 60 fps)"),
              std::string::npos) << sixty.out;
    probe = probe_video(dir / "s.gif");
    EXPECT_EQ(probe["r_frame_rate"], "50/1");
    EXPECT_NEAR(std::stod(probe["duration"]), 1.26, 0.005);   // 63 frames of 2 cs

    const auto refused = render({"-o", dir / "r.gif", "--fps", "60"});
    EXPECT_EQ(refused.exit_code, 2);
    EXPECT_EQ(refused.err, "discreel: a GIF cannot play at 60 fps (its frame delays are whole "
                           "hundredths of a second); use --fps 50, 25, 20 or 10\n");
    EXPECT_FALSE(fs::exists(dir / "r.gif"));
}

// --frames A-B renders frames A..B into any format; a sequence numbers its files by frame, and
// each file equals the still of that frame.
TEST(CliHabitsGLTest, FrameRangesInEveryFormat) {
    TempDir dir;
    auto run = render({"-o", dir / "part.mp4", "--frames", "5-9"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find(": 5 frames, 160x120, 0.21 s at 24 fps, frames 5..9 ("),
              std::string::npos) << run.out;
    EXPECT_EQ(probe_video(dir / "part.mp4")["nb_read_frames"], "5");

    run = render({"-o", dir / "tail.webm", "--frames", "26-"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(probe_video(dir / "tail.webm")["nb_read_frames"], "4");

    fs::create_directories(dir / "seq");
    run = render({"-o", dir / "seq/f_%02d.png", "--frames", "27-29"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(testing::directory_entries(dir / "seq"),
              (std::vector<std::string>{"f_27.png", "f_28.png", "f_29.png"}));
    ASSERT_EQ(render({"-o", dir / "still.png", "--frame", "28"}).exit_code, 0);
    EXPECT_EQ(read_file(dir / "seq/f_28.png"), read_file(dir / "still.png"));

    const std::vector<std::pair<std::string, std::string>> bad = {
        {"9-5", "discreel: --frames 9-5 ends before it starts; give the first frame first\n"},
        {"5-30", "discreel: frame 30 is outside the clip, which has 30 frames (0..29, or "
                 "-30..-1 counted from the end)\n"},
        {"five", "discreel: --frames takes A-B (frames A to B, inclusive) or A- (A to the "
                 "end), got 'five'\n"},
        {"-3", "discreel: --frames takes A-B (frames A to B, inclusive) or A- (A to the end), "
               "got '-3'\n"},
    };
    for (const auto& [range, message] : bad) {
        run = render({"-o", dir / "bad.mp4", "--frames=" + range});
        EXPECT_EQ(run.exit_code, 2) << range;
        EXPECT_EQ(run.err, message);
    }
    run = render({"-o", dir / "bad.png", "--frames", "3-4"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: a .png name is one still; for frames 3-4 give a numbered name "
                       "such as frame_%04d.png\n");
    EXPECT_FALSE(fs::exists(dir / "bad.mp4"));
    EXPECT_FALSE(fs::exists(dir / "bad.png"));
}

// Manim's -s: the last frame by --frame -1, --frame last, or --at the clip's duration.
TEST(CliHabitsGLTest, TheLastFrameThreeWays) {
    TempDir dir;
    ASSERT_EQ(render({"-o", dir / "29.png", "--frame", "29"}).exit_code, 0);
    ASSERT_EQ(render({"-o", dir / "minus.png", "--frame", "-1"}).exit_code, 0);
    ASSERT_EQ(render({"-o", dir / "last.png", "--frame", "last"}).exit_code, 0);
    ASSERT_EQ(render({"-o", dir / "at.png", "--at", "1.25"}).exit_code, 0);
    ASSERT_EQ(render({"-o", dir / "28.png", "--frame", "-2"}).exit_code, 0);
    const std::string last = read_file(dir / "29.png");
    EXPECT_EQ(read_file(dir / "minus.png"), last);
    EXPECT_EQ(read_file(dir / "last.png"), last);
    EXPECT_EQ(read_file(dir / "at.png"), last);
    EXPECT_NE(read_file(dir / "28.png"), last);
    const auto run = render({"-o", dir / "x.png", "--frame", "-31"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: frame -31 is outside the clip, which has 30 frames (0..29, or "
                       "-30..-1 counted from the end)\n");
}

// Typos on the command line get what typos in scenes get; every message starts "discreel:".
TEST(CliHabitsGLTest, TyposGetASuggestionAndExit2) {
    auto run = run_command({bin, "rendr", short_scene, "-o", "x.mp4"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: unknown command 'rendr'; did you mean 'render'? (discreel "
                       "--help lists the commands)\n");
    run = run_command({bin, "frobnicate"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: unknown command 'frobnicate' (discreel --help lists the "
                       "commands)\n");
    run = render({"-o", "x.mp4", "--sise", "320x180"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: unknown option '--sise' for 'render'; did you mean '--size'? "
                       "(discreel render --help lists its options)\n");
    run = run_command({bin, "golden", short_scene, "--dir", "g", "--tolerence=0.2"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: unknown option '--tolerence' for 'golden'; did you mean "
                       "'--tolerance'? (discreel golden --help lists its options)\n");
    // CLI11's own messages get the prefix and the pointer to --help too.
    run = render({});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: --output is required\n"
                       "Run 'discreel render --help' for more information.\n");
    EXPECT_FALSE(fs::exists("x.mp4"));
}

// A background with alpha below 1 gives PNGs with that alpha; formats without alpha say that
// they draw it opaque, and do.
TEST(CliHabitsGLTest, TransparentBackgroundInPngsAndANoteElsewhere) {
    TempDir dir;
    write_file(dir / "clear.yaml",
               std::regex_replace(read_file(short_scene), std::regex("video:\n"),
                                  "video:\n  background: \"#00000000\"\n"));
    auto run = run_command({bin, "render", dir / "clear.yaml", "-o", dir / "c.png"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.err, "");
    auto image = encode::read_png(dir / "c.png");
    ASSERT_TRUE(image.ok());
    EXPECT_EQ(image->rgba[3], 0);   // the top-left corner, outside the walls: transparent
    int opaque = 0;
    for (std::size_t i = 3; i < image->rgba.size(); i += 4) opaque += image->rgba[i] == 255;
    EXPECT_GT(opaque, 0);   // the discs and walls are drawn

    run = run_command({bin, "render", dir / "clear.yaml", "-o", dir / "c.mp4"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.err, "discreel: note: mp4 has no alpha channel; the background is drawn "
                       "opaque (write .png stills or a frame_%04d.png sequence for "
                       "transparency)\n");
    EXPECT_EQ(probe_video(dir / "c.mp4")["nb_read_frames"], "30");
}

// Manim's -ql .. -qk: size (keeping the scene's aspect), fps and crf together; explicit
// options win.
TEST(CliHabitsGLTest, QualityPresetsSetSizeAndFpsUnlessGiven) {
    TempDir dir;
    auto run = render({"-o", dir / "low.mp4", "--quality", "low"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    auto probe = probe_video(dir / "low.mp4");
    EXPECT_EQ(probe["width"], "640");   // 480 high at the scene's 4:3
    EXPECT_EQ(probe["height"], "480");
    EXPECT_EQ(probe["r_frame_rate"], "15/1");

    run = render({"-o", dir / "mine.mp4", "--quality", "low", "--size", "320x240", "--fps", "10",
                  "-v"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    probe = probe_video(dir / "mine.mp4");
    EXPECT_EQ(probe["width"], "320");
    EXPECT_EQ(probe["r_frame_rate"], "10/1");
    EXPECT_NE(run.err.find("crf 28"), std::string::npos) << run.err;   // the preset's crf

    run = render({"-o", dir / "x.mp4", "--quality", "ultra"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err.rfind("discreel: --quality: ultra not in {", 0), 0U) << run.err;
}

// ffmpeg's -progress: one JSON object per line on stderr, the last one stage "done".
TEST(CliHabitsGLTest, JsonProgressForWrappers) {
    TempDir dir;
    const auto run = render({"-o", dir / "c.mp4", "--progress", "json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    std::istringstream lines(run.err);
    std::string line, last;
    int count = 0;
    const std::regex object(R"re(\{"stage":"(render|done)","frame":\d+,"frames":30,)re"
                            R"re("fps":[0-9.]+,"elapsed":[0-9.]+,"eta":([0-9.]+|null)\})re");
    while (std::getline(lines, line)) {
        EXPECT_TRUE(std::regex_match(line, object)) << line;
        last = line;
        ++count;
    }
    EXPECT_GE(count, 2);
    EXPECT_EQ(last.rfind(R"({"stage":"done","frame":30,"frames":30,)", 0), 0U) << last;
    EXPECT_NE(run.out.find("wrote "), std::string::npos);   // the summary stays on stdout
}

// ffmpeg's -n: an existing output is kept, and nothing is rendered.
TEST(CliHabitsGLTest, NoOverwriteRefusesAnExistingOutput) {
    TempDir dir;
    write_file(dir / "keep.mp4", "mine");
    auto run = render({"-o", dir / "keep.mp4", "--no-overwrite"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: '" + (dir / "keep.mp4") +
                           "' exists and --no-overwrite keeps it; nothing was written\n");
    EXPECT_EQ(read_file(dir / "keep.mp4"), "mine");
    write_file(dir / "t.csv", "mine");
    run = render({"-o", dir / "new.mp4", "--trace", dir / "t.csv", "--no-overwrite"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_FALSE(fs::exists(dir / "new.mp4"));
    run = render({"-o", dir / "new.mp4", "--no-overwrite"});
    EXPECT_EQ(run.exit_code, 0) << run.err;
}

// `{..., color: #ff0000}` as people write it: pointed at where the colour is, with the file's
// other problems still found.
TEST(CliHabitsGLTest, UnquotedColourInFlowStyleIsPointedAt) {
    TempDir dir;
    write_file(dir / "flow.yaml", "version: 1\n"
                                  "discs:\n"
                                  "  - {position: [1, 1], radius: 0.2, color: #ff0000}\n"
                                  "  - {position: [2, 1], radius: -1}\n");
    const auto run = run_command({bin, "validate", dir / "flow.yaml"});
    EXPECT_EQ(run.exit_code, 2);
    const std::string file = dir / "flow.yaml";
    EXPECT_EQ(run.err,
              file + ":3:44: a colour in {...} or [...] must be quoted: YAML reads an unquoted "
                     "'#' as the start of a comment, which hides the closing bracket; write "
                     "color: \"#rrggbb\"\n" +
                  file + ":4:32: discs[1].radius: must be greater than 0, got -1\n")
        << run.err;
}

// Render farms run one line of a manifest per task: the index from --index, a Slurm array or
// a Kubernetes indexed Job; the line means what it means after `discreel render`.
TEST(BatchGLTest, EachTaskRendersItsLineOfTheManifest) {
    TempDir dir;
    testing::write_file(dir / "renders.txt",
                        "# stills of the short scene\n\n" + short_scene + " -o '" + (dir / "a 0.png") +
                            "' --frame 2\n" + short_scene + " -o " + (dir / "b.png") +
                            " --size 64x36\n" + short_scene + " -o " + (dir / "c.png") +
                            " --colour red\n");
    auto run = run_command({bin, "batch", dir / "renders.txt", "--index", "0"});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    const auto direct = run_command({bin, "render", short_scene, "-o", dir / "direct.png",
                                     "--frame", "2", "-q"});
    ASSERT_EQ(direct.exit_code, 0);
    EXPECT_EQ(read_file(dir / "a 0.png"), read_file(dir / "direct.png"));

    run = run_command({bin, "batch", dir / "renders.txt"}, {{"SLURM_ARRAY_TASK_ID", "1"}});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(testing::probe_video(dir / "b.png")["width"], "64");
    run = run_command({bin, "batch", dir / "renders.txt"}, {{"JOB_COMPLETION_INDEX", "2"}});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err.rfind(dir / "renders.txt" + ":5: unknown option '--colour' for 'render'", 0),
              0u)
        << run.err;
    run = run_command({bin, "batch", dir / "renders.txt", "--index", "3"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: index 3 is past the end of " + (dir / "renders.txt") +
                           ", which has 3 renders (indexes 0 to 2)\n");
    run = run_command({bin, "batch", dir / "renders.txt"});
    EXPECT_EQ(run.exit_code, 2);
}

// A dataset's manifest: lines that differ only in --set, run as a range in one process (one
// warm renderer) or several at once, each byte for byte what its own run writes; the output
// directories are made as needed.
TEST(BatchGLTest, ARangeOfLinesEqualsTheLinesRunOneByOne) {
    TempDir dir;
    std::string manifest;
    for (int i = 0; i < 4; ++i) {
        manifest += short_scene + " -o " + (dir / "range") + "/" + std::to_string(i) +
                    "/f.png --frame 3 --size 64x36 --set physics.seed=" + std::to_string(i) +
                    " --set 'discs.0.velocity=[" + std::to_string(i) + ", 0]' -q\n";
    }
    write_file(dir / "m.txt", manifest);
    auto run = run_command({bin, "batch", dir / "m.txt", "--index", "0-3"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    std::vector<std::string> stills;
    for (int i = 0; i < 4; ++i) {
        const std::string one = dir / ("one" + std::to_string(i) + ".png");
        const auto single = run_command({bin, "render", short_scene, "-o", one, "--frame", "3",
                                         "--size", "64x36", "--set",
                                         "physics.seed=" + std::to_string(i), "--set",
                                         "discs.0.velocity=[" + std::to_string(i) + ", 0]", "-q"});
        ASSERT_EQ(single.exit_code, 0) << single.err;
        stills.push_back(read_file(one));
        EXPECT_EQ(read_file(dir / ("range/" + std::to_string(i) + "/f.png")), stills.back()) << i;
    }
    EXPECT_NE(stills[0], stills[3]);   // the overrides took effect

    std::filesystem::remove_all(dir / "range");
    run = run_command({bin, "batch", dir / "m.txt", "--all", "--jobs", "3"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(read_file(dir / ("range/" + std::to_string(i) + "/f.png")), stills[i]) << i;
    }
}

// A failed line does not stop the others; the batch fails and names it.
TEST(BatchGLTest, AFailedLineIsNamedAndTheOthersRun) {
    TempDir dir;
    write_file(dir / "m.txt", short_scene + " -o " + (dir / "a.png") + " -q\n" + short_scene +
                                  " -o " + (dir / "b.png") + " --set physics.sede=2\n" +
                                  short_scene + " -o " + (dir / "c.png") + " -q\n");
    const auto run = run_command({bin, "batch", dir / "m.txt", "--index", "0-2"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "--set physics.sede=2: physics: unknown key 'sede'; did you mean "
                       "'seed'?\ndiscreel: 1 of 3 renders failed (index 1)\n");
    EXPECT_TRUE(std::filesystem::exists(dir / "a.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "b.png"));
    EXPECT_TRUE(std::filesystem::exists(dir / "c.png"));
}

}  // namespace
}  // namespace discreel
