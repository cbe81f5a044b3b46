// `discreel golden` end to end through the binary: write goldens, pass, change a colour and
// fail with .actual.png and .diff.png, a JUnit report, a missing golden, another renderer.
// Also runs the project's own rendering regression check: every configs/ scene against its
// goldens in tests/golden/configs. "GL" in the suite names: these need an OSMesa context.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <sys/stat.h>
#include <sstream>

#include "discreel/encode.hpp"
#include "golden_compare.hpp"
#include "test_support.hpp"

namespace discreel {
namespace {

namespace fs = std::filesystem;
using testing::read_file;
using testing::run_command;
using testing::TempDir;
using testing::write_file;

const std::string bin = DISCREEL_BIN;
const fs::path source_dir = DISCREEL_SOURCE_DIR;

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
    for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
    return text;
}

// A copy of the short test scene named ball.yaml; 30 frames, so goldens 0, 15 and 29.
class GoldenCliGLTest : public ::testing::Test {
protected:
    void SetUp() override {
        scene_text_ = read_file(source_dir / "tests/data/scenes/short.yaml");
        write_file(scene_, scene_text_);
    }
    testing::CommandResult golden(std::vector<std::string> extra) {
        std::vector<std::string> argv{bin, "golden", scene_, "--dir", goldens_};
        argv.insert(argv.end(), extra.begin(), extra.end());
        return run_command(argv);
    }
    TempDir dir_;
    const std::string scene_ = dir_ / "ball.yaml";
    const std::string goldens_ = dir_ / "goldens";
    // A failure's files: golden-results beside the goldens, never among them.
    const std::string results_ = dir_ / "golden-results";
    std::string scene_text_;
};

TEST_F(GoldenCliGLTest, UpdateThenPass) {
    const auto update = golden({"--update"});
    ASSERT_EQ(update.exit_code, 0) << update.err;
    EXPECT_EQ(update.err, "");
    const std::string g = goldens_ + "/ball/";
    EXPECT_EQ(update.out, "ball frame 0: wrote " + g + "frame_0.png\n"
                          "ball frame 15: wrote " + g + "frame_15.png\n"
                          "ball frame 29: wrote " + g + "frame_29.png\n"
                          "golden: wrote 3 frames of 1 scene to " + goldens_ + "\n");
    const std::string metadata = read_file(g + "golden.txt");
    EXPECT_NE(metadata.find("\ndiscreel: 0.1.0\n"), std::string::npos) << metadata;
    EXPECT_NE(metadata.find("\nrenderer: llvmpipe"), std::string::npos) << metadata;
    EXPECT_NE(metadata.find("\nsize: 160x120\n"), std::string::npos) << metadata;

    const auto check = golden({});
    ASSERT_EQ(check.exit_code, 0) << check.out << check.err;
    EXPECT_EQ(check.out, "ball frame 0: ok (identical)\n"
                         "ball frame 15: ok (identical)\n"
                         "ball frame 29: ok (identical)\n"
                         "golden: 3 frames of 1 scene: 3 passed, 0 failed\n");
    EXPECT_FALSE(fs::exists(results_));
}

// Not on a terminal the progress stays off unless asked for; asked for, it comes as plain lines
// on stderr (simulated frames over all scenes) and leaves stdout's report as it is.
TEST_F(GoldenCliGLTest, ProgressOnRequestGoesToStderr) {
    ASSERT_EQ(golden({"--update"}).exit_code, 0);
    const auto check = golden({"--progress"});
    ASSERT_EQ(check.exit_code, 0) << check.err;
    EXPECT_EQ(check.out, "ball frame 0: ok (identical)\n"
                         "ball frame 15: ok (identical)\n"
                         "ball frame 29: ok (identical)\n"
                         "golden: 3 frames of 1 scene: 3 passed, 0 failed\n");
    EXPECT_EQ(check.err.rfind("frame 1/30 (3%), ", 0), 0u) << check.err;
    EXPECT_NE(check.err.find("frame 30/30 (100%), "), std::string::npos) << check.err;
    EXPECT_EQ(check.err.find('\r'), std::string::npos);
}

TEST_F(GoldenCliGLTest, AChangedColourFailsWithActualAndDiffImagesAndAJunitReport) {
    ASSERT_EQ(golden({"--update"}).exit_code, 0);
    // The red disc turns blue; frame 0's report is checked in full, frames 15 and 29 in part.
    write_file(scene_, replace_all(scene_text_, "\"#e4572e\"", "\"#2040ff\""));
    const auto check = golden({"--junit", dir_ / "report.xml"});
    ASSERT_EQ(check.exit_code, 1) << check.out << check.err;
    EXPECT_EQ(check.err, "");

    const std::string g = goldens_ + "/ball/";
    const std::string r = results_ + "/ball/";
    auto expected = encode::read_png(g + "frame_0.png");
    auto actual = encode::read_png(r + "frame_0.actual.png");
    auto diff = encode::read_png(r + "frame_0.diff.png");
    // Nothing of the failure lands among the goldens; the report lands among the results.
    std::vector<std::string> goldens;
    for (const auto& entry : fs::directory_iterator(g)) goldens.push_back(entry.path().filename());
    std::sort(goldens.begin(), goldens.end());
    EXPECT_EQ(goldens, (std::vector<std::string>{"frame_0.png", "frame_15.png", "frame_29.png",
                                                 "golden.txt"}));
    EXPECT_NE(read_file(results_ + "/report.html").find("<img"), std::string::npos);
    EXPECT_TRUE(check.out.ends_with("golden: report: " + results_ + "/report.html\n"))
        << check.out;
    ASSERT_TRUE(expected.ok() && actual.ok() && diff.ok());
    const golden::Comparison c = golden::compare_images(actual->view(), expected->view(), {});
    // The camera fits the 4 x 3 m box with a 5 % margin: 120 / 3.3 = 36 pixels per metre, so
    // the disc of radius 0.3 m covers about 370 pixels; its rim may pass for anti-aliasing,
    // its inside may not.
    EXPECT_GT(c.differing_pixels, 200);
    EXPECT_LT(c.differing_pixels + c.anti_aliased_pixels, 450);
    std::ostringstream percent;
    percent.precision(2);
    percent << std::fixed << 100.0 * c.differing_pixels / 19200;
    const std::string message =
        std::to_string(c.differing_pixels) + " pixels differ (" + percent.str() +
        " % of 19200, 0 allowed; largest colour distance " +
        [&] { std::ostringstream s; s.precision(3); s << std::fixed << c.max_delta; return s.str(); }() +
        ", " + std::to_string(c.anti_aliased_pixels) + " anti-aliased pixels ignored)";
    std::istringstream lines(check.out);
    std::string first;
    std::getline(lines, first);
    EXPECT_EQ(first, "ball frame 0: FAILED: " + message + "; wrote " + r + "frame_0.actual.png and " +
                         r + "frame_0.diff.png");
    EXPECT_NE(check.out.find("\nball frame 15: FAILED: "), std::string::npos) << check.out;
    EXPECT_NE(check.out.find("\nball frame 29: FAILED: "), std::string::npos) << check.out;
    EXPECT_NE(check.out.find("\ngolden: 3 frames of 1 scene: 0 passed, 3 failed\n"),
              std::string::npos) << check.out;
    // The diff marks the changed pixels red over the faded golden.
    const auto red = [&] {
        int n = 0;
        for (std::size_t i = 0; i < diff->rgba.size(); i += 4)
            n += diff->rgba[i] == 255 && diff->rgba[i + 1] == 0 && diff->rgba[i + 2] == 0;
        return n;
    }();
    EXPECT_EQ(red, c.differing_pixels);

    // Times vary run to run: each case has one, and the rest is exact.
    const std::string timed = read_file(dir_ / "report.xml");
    const std::regex time(" time=\"[0-9]+\\.[0-9]{3}\"");
    EXPECT_EQ(std::distance(std::sregex_iterator(timed.begin(), timed.end(), time),
                            std::sregex_iterator()),
              5);   // the two suites and three cases
    const std::string xml = std::regex_replace(timed, time, "");
    EXPECT_EQ(xml.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                        "<testsuites name=\"discreel golden\" tests=\"3\" failures=\"3\" errors=\"0\">\n"
                        "  <testsuite name=\"discreel golden\" tests=\"3\" failures=\"3\" errors=\"0\">\n"
                        "    <testcase classname=\"ball\" name=\"frame_0\">\n"
                        "      <failure message=\"" + message + "\" type=\"golden mismatch\">" +
                        message + "\nwrote " + r + "frame_0.actual.png and " + r +
                        "frame_0.diff.png</failure>\n    </testcase>\n", 0), 0u) << xml;
    EXPECT_NE(xml.find("<testcase classname=\"ball\" name=\"frame_29\">"), std::string::npos);

    // Put back, the scene passes again, and the leftovers of the failure are gone.
    write_file(scene_, scene_text_);
    ASSERT_EQ(golden({}).exit_code, 0);
    EXPECT_FALSE(fs::exists(r + "frame_0.actual.png"));
    EXPECT_FALSE(fs::exists(r + "frame_0.diff.png"));
}

TEST_F(GoldenCliGLTest, TolerancesLetAChangeThrough) {
    ASSERT_EQ(golden({"--update"}).exit_code, 0);
    write_file(scene_, replace_all(scene_text_, "\"#e4572e\"", "\"#2040ff\""));
    EXPECT_EQ(golden({"--max-diff-pixels", "2000"}).exit_code, 0);
    EXPECT_EQ(golden({"--max-diff-ratio", "0.1"}).exit_code, 0);
    // Both given: the tighter one decides.
    EXPECT_EQ(golden({"--max-diff-ratio", "0.1", "--max-diff-pixels", "10"}).exit_code, 1);
    EXPECT_EQ(golden({"--tolerance", "1"}).exit_code, 0);
}

// However --dir is written (a trailing slash, as tab completion leaves it), a failure's files
// land beside the goldens; --results inside --dir is refused.
TEST_F(GoldenCliGLTest, ResultsNeverLandAmongTheGoldens) {
    ASSERT_EQ(golden({"--update"}).exit_code, 0);
    write_file(scene_, replace_all(scene_text_, "\"#e4572e\"", "\"#2040ff\""));
    const auto run = run_command({bin, "golden", scene_, "--dir", goldens_ + "/"});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_TRUE(fs::exists(results_ + "/ball/frame_0.actual.png"));
    EXPECT_FALSE(fs::exists(goldens_ + "/golden-results"));
    const auto inside = golden({"--results", goldens_ + "/ball/out"});
    EXPECT_EQ(inside.exit_code, 2);
    EXPECT_EQ(inside.err, "discreel: --results '" + goldens_ + "/ball/out' is inside --dir '" +
                              goldens_ + "': a failure's files never go among the goldens; give "
                              "a directory beside it\n");
}

// A scene's `golden:` block sets its own thresholds, which win over the command line's.
TEST_F(GoldenCliGLTest, ASceneSetsItsOwnThresholds) {
    ASSERT_EQ(golden({"--update"}).exit_code, 0);
    const std::string blue = replace_all(scene_text_, "\"#e4572e\"", "\"#2040ff\"");
    write_file(scene_, blue);
    EXPECT_EQ(golden({}).exit_code, 1);
    write_file(scene_, blue + "golden:\n  max_diff_ratio: 0.1\n");
    EXPECT_EQ(golden({}).exit_code, 0);
    EXPECT_EQ(golden({"--max-diff-ratio", "0"}).exit_code, 0);   // the scene's wins
    write_file(scene_, blue + "golden:\n  max_diff_pixels: 10\n");
    EXPECT_EQ(golden({"--max-diff-ratio", "0.1"}).exit_code, 1);   // the tighter decides
    write_file(scene_, blue + "golden:\n  tolerance: 1\n");
    EXPECT_EQ(golden({}).exit_code, 0);
    // --set reaches the same block: one run made lenient without touching the file.
    write_file(scene_, blue);
    EXPECT_EQ(golden({"--set", "golden.max_diff_ratio=0.1"}).exit_code, 0);
    write_file(scene_, blue + "golden:\n  tolerance: 2\n");
    const auto bad = golden({});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_EQ(bad.err, scene_ + ":33:14: golden.tolerance: must be between 0 and 1, got 2\n");
}

// An update after the clip got shorter leaves no golden of a frame it no longer has, and says
// which it removed; a shard, which sees part of the frames, removes none.
TEST_F(GoldenCliGLTest, AnUpdateRemovesGoldensOfFramesNoLongerListed) {
    ASSERT_EQ(golden({"--update"}).exit_code, 0);
    const std::string g = goldens_ + "/ball/";
    write_file(scene_, replace_all(scene_text_, "duration: 1.25", "duration: 0.5"));
    EXPECT_EQ(golden({"--update", "--shard", "1/2"}).exit_code, 0);
    EXPECT_TRUE(fs::exists(g + "frame_29.png"));
    const auto run = golden({"--update"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.out, "ball frame 0: wrote " + g + "frame_0.png\n"
                       "ball frame 6: wrote " + g + "frame_6.png\n"
                       "ball frame 11: wrote " + g + "frame_11.png\n"
                       "ball frame 15: removed " + g + "frame_15.png (the scene no longer lists "
                       "this frame)\n"
                       "ball frame 29: removed " + g + "frame_29.png (the scene no longer lists "
                       "this frame)\n"
                       "golden: wrote 3 frames of 1 scene to " + goldens_ +
                       ", removed 2 frames\n");
    std::vector<std::string> left;
    for (const auto& entry : fs::directory_iterator(g)) left.push_back(entry.path().filename());
    std::sort(left.begin(), left.end());
    EXPECT_EQ(left, (std::vector<std::string>{"frame_0.png", "frame_11.png", "frame_6.png",
                                              "golden.txt"}));
    EXPECT_EQ(golden({}).exit_code, 0);
}

TEST_F(GoldenCliGLTest, AMissingGoldenSaysHowToCreateIt) {
    const auto check = golden({"--size", "64x48"});
    EXPECT_EQ(check.exit_code, 1);
    EXPECT_EQ(check.out.substr(0, check.out.find('\n')),
              "ball frame 0: FAILED: no golden image " + goldens_ +
                  "/ball/frame_0.png; create it with: discreel golden " + scene_ + " --dir " +
                  goldens_ + " --size 64x48 --update");
}

TEST_F(GoldenCliGLTest, AMismatchOnAnotherRendererSaysSo) {
    ASSERT_EQ(golden({"--update"}).exit_code, 0);
    const std::string metadata_path = goldens_ + "/ball/golden.txt";
    std::string metadata = read_file(metadata_path);
    const auto renderer_at = metadata.find("renderer: ") + 10;
    const auto renderer_end = metadata.find('\n', renderer_at);
    const std::string now = metadata.substr(renderer_at, renderer_end - renderer_at);
    write_file(metadata_path, metadata.replace(renderer_at, renderer_end - renderer_at,
                                               "Imaginary GPU, 9.9 (Core Profile) Mesa 99.0"));
    // Same pixels: the renderer note is not a failure by itself.
    ASSERT_EQ(golden({}).exit_code, 0);

    write_file(scene_, replace_all(scene_text_, "\"#e4572e\"", "\"#2040ff\""));
    const auto check = golden({});
    EXPECT_EQ(check.exit_code, 1);
    const std::string first = check.out.substr(0, check.out.find('\n'));
    const std::string note = "; rendered with a different renderer (stored: Imaginary GPU, 9.9 "
                             "(Core Profile) Mesa 99.0, now: " + now + ")";
    ASSERT_GE(first.size(), note.size());
    EXPECT_NE(first.find(note + "; wrote "), std::string::npos) << first;
    EXPECT_TRUE(first.ends_with("/ball/frame_0.diff.png")) << first;
}

TEST_F(GoldenCliGLTest, ASizeMismatchIsAFailureWithTheActualFrame) {
    ASSERT_EQ(golden({"--update"}).exit_code, 0);
    const auto check = golden({"--size", "320x240"});
    EXPECT_EQ(check.exit_code, 1);
    EXPECT_EQ(check.out.substr(0, check.out.find('\n')),
              "ball frame 0: FAILED: the frame is 320x240 but the golden is 160x120; check at "
              "the golden's size with --size 160x120, or rewrite the goldens with --update; wrote " +
                  results_ + "/ball/frame_0.actual.png");
    EXPECT_TRUE(fs::exists(results_ + "/ball/frame_0.actual.png"));
    EXPECT_FALSE(fs::exists(results_ + "/ball/frame_0.diff.png"));
}

// Goldens made with --size are checked at that size (golden.txt records it) without it.
TEST_F(GoldenCliGLTest, TheRecordedSizeIsUsedWhenNoSizeIsGiven) {
    ASSERT_EQ(golden({"--update", "--size", "320x240"}).exit_code, 0);
    const auto check = golden({});
    EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
    EXPECT_EQ(check.out.substr(0, check.out.find('\n')), "ball frame 0: ok (identical)");
}

// -u is --update; --update=missing writes only the goldens that are not there and leaves the
// others as they were (the same file, not a rewrite); --update=changed writes those missing or
// no longer matching. Both check the rest as usual.
TEST_F(GoldenCliGLTest, UpdateModesWriteOnlyWhatIsMissingOrChanged) {
    const std::string g = goldens_ + "/ball/";
    ASSERT_EQ(golden({"-u"}).exit_code, 0);
    ASSERT_TRUE(fs::remove(g + "frame_15.png"));
    struct stat before{};
    ASSERT_EQ(stat((g + "frame_0.png").c_str(), &before), 0);

    auto run = golden({"--update", "missing"});
    ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
    EXPECT_EQ(run.out, "ball frame 0: ok (identical)\n"
                       "ball frame 15: wrote " + g + "frame_15.png (was: no golden image " + g +
                       "frame_15.png; create it with: discreel golden " + scene_ + " --dir " +
                       goldens_ + " --update)\n"
                       "ball frame 29: ok (identical)\n"
                       "golden: 3 frames of 1 scene: 2 passed, 0 failed, 1 written\n");
    struct stat after{};
    ASSERT_EQ(stat((g + "frame_0.png").c_str(), &after), 0);
    EXPECT_EQ(after.st_ino, before.st_ino);   // untouched, not rewritten with the same bytes

    // Another colour: =missing leaves the changed goldens failing, =changed rewrites them.
    write_file(scene_, replace_all(scene_text_, "#e4572e", "#2e57e4"));
    run = golden({"--update=missing"});
    EXPECT_EQ(run.exit_code, 1) << run.out;
    EXPECT_NE(run.out.find("ball frame 0: FAILED: "), std::string::npos) << run.out;
    run = golden({"-u", "changed"});
    ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
    EXPECT_TRUE(run.out.ends_with("golden: 3 frames of 1 scene: 0 passed, 0 failed, 3 written\n"))
        << run.out;
    EXPECT_FALSE(fs::exists(results_ + "/ball/frame_0.actual.png"));   // the failed check's
    EXPECT_FALSE(fs::exists(results_ + "/ball/frame_0.diff.png"));     // files are gone
    EXPECT_EQ(golden({}).exit_code, 0);

    run = golden({"--update=sometimes"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err.rfind("discreel: --update: ", 0), 0U) << run.err;
}

// --report: one HTML page, self-contained (images inline), with each failing frame's golden,
// actual and difference images and its numbers; a run where everything passes says so.
TEST_F(GoldenCliGLTest, HtmlReportShowsEachFailingFrame) {
    ASSERT_EQ(golden({"--update"}).exit_code, 0);
    const std::string report = dir_ / "report.html";
    auto run = golden({"--report", report});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    std::string html = read_file(report);
    EXPECT_NE(html.find("3 frames of 1 scene: <span class=\"passed\">3 passed</span>"),
              std::string::npos) << html;
    EXPECT_NE(html.find("Every frame matched its golden."), std::string::npos);
    EXPECT_EQ(html.find("data:image/png"), std::string::npos);
    // The passing frames are listed, folded away.
    EXPECT_NE(html.find("<details><summary class=\"passed\">3 frames passed or written"
                        "</summary>"),
              std::string::npos);
    EXPECT_NE(html.find("<li>ball frame_15: identical</li>"), std::string::npos);

    write_file(scene_, replace_all(scene_text_, "#e4572e", "#2e57e4"));
    run = golden({"--report", report});
    ASSERT_EQ(run.exit_code, 1) << run.err;
    html = read_file(report);
    EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0U);
    EXPECT_EQ(html.find("src=\"http"), std::string::npos);   // nothing to fetch
    EXPECT_EQ(html.find("<script"), std::string::npos);
    // Three failing frames, each with three images side by side and the same three in a
    // wipe (golden | actual on a slider, the difference over them on another).
    std::size_t images = 0;
    for (auto at = html.find("src=\"data:image/png;base64,"); at != std::string::npos;
         at = html.find("src=\"data:image/png;base64,", at + 1)) {
        ++images;
    }
    EXPECT_EQ(images, 18u);
    std::size_t wipes = 0;
    for (auto at = html.find("<div class=\"wipe\">"); at != std::string::npos;
         at = html.find("<div class=\"wipe\">", at + 1)) {
        ++wipes;
    }
    EXPECT_EQ(wipes, 3u);
    EXPECT_NE(html.find("type=\"range\""), std::string::npos);
    EXPECT_NE(html.find("<h2 class=\"failed\">ball frame_15</h2>"), std::string::npos);
    EXPECT_NE(html.find(" pixels differ ("), std::string::npos);   // the numbers, as printed
    EXPECT_NE(html.find("<figcaption>actual</figcaption>"), std::string::npos);
}

// More shards than frames: a shard with nothing to check says so and passes.
TEST_F(GoldenCliGLTest, AShardWithNoFramesSaysSo) {
    ASSERT_EQ(golden({"--update"}).exit_code, 0);
    const auto run = golden({"--shard", "5/5", "--junit", dir_ / "empty.xml"});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.out.substr(0, run.out.find('\n')),
              "golden: shard 5/5 has no frames: the run has 3 frames in all, dealt out to 5 "
              "shards");
    EXPECT_NE(read_file(dir_ / "empty.xml").find("tests=\"0\""), std::string::npos);
}

TEST_F(GoldenCliGLTest, BadOptionsAndScenesAreExit2BeforeAnyWork) {
    auto bad = golden({"--tolerance", "1.5"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_EQ(bad.err, "discreel: --tolerance must be between 0 (exact colours) and 1 (any colour)\n");
    bad = golden({"--max-diff-ratio", "-0.5"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_EQ(bad.err, "discreel: --max-diff-ratio must be between 0 and 1\n");

    write_file(dir_ / "broken.yaml", "version: 1\nvideo: {fps: 0}\n");
    bad = run_command({bin, "golden", scene_, dir_ / "broken.yaml", "--dir", goldens_, "--update"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_EQ(bad.out, "");
    EXPECT_FALSE(fs::exists(goldens_));   // the good scene was not rendered either

    fs::create_directories(dir_ / "other");
    write_file(dir_ / "other/ball.yaml", scene_text_);
    bad = run_command({bin, "golden", scene_, dir_ / "other/ball.yaml", "--dir", goldens_});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_EQ(bad.err, "discreel: " + scene_ + " and " + (dir_ / "other/ball.yaml") +
                           " are both named 'ball'; their goldens would share " + goldens_ +
                           "/ball\n");
}

// Every .yaml of `scenes` (a directory of the source tree) against its goldens in `goldens`, at
// 320x180 to keep them small. Tolerance: the defaults (colour distance 0.1, no differing pixel
// beyond anti-aliasing), since llvmpipe renders bit-identically run to run; the anti-aliasing
// allowance absorbs edge shading of another Mesa/LLVM. Refresh with the command in
// docs/golden.md.
void expect_scenes_match_goldens(const fs::path& scenes, const fs::path& goldens,
                                 std::size_t at_least) {
    std::vector<std::string> argv{bin, "golden"};
    for (const auto& entry : fs::directory_iterator(source_dir / scenes))
        if (entry.path().extension() == ".yaml") argv.push_back(entry.path().string());
    std::sort(argv.begin() + 2, argv.end());
    ASSERT_GE(argv.size(), at_least + 2);
    TempDir dir;
    // The goldens are copied so that the run works as a user's would (a failure's .actual.png,
    // .diff.png and report in golden-results beside them) in a temporary directory, not in the
    // source tree; the output names them.
    fs::copy(source_dir / goldens, dir.path() / "goldens", fs::copy_options::recursive);
    const std::string copied = dir / "goldens";
    argv.insert(argv.end(), {"--dir", copied, "--size", "320x180"});
    const auto run = run_command(argv);
    EXPECT_EQ(run.exit_code, 0) << run.out << run.err;
    EXPECT_EQ(run.err, "");
    if (run.exit_code != 0) {
        // Keep the evidence: the temporary directory is removed when the test ends.
        const fs::path keep = fs::path(DISCREEL_BINARY_DIR) /
                              ("golden-" + goldens.filename().string() + "-mismatch");
        fs::remove_all(keep);
        fs::copy(dir.path(), keep, fs::copy_options::recursive);
        ADD_FAILURE() << "goldens, and the .actual.png, .diff.png and report.html of "
                         "golden-results, kept in " << keep;
    }
}

// The project's own rendering regressions: every shipped scene.
TEST(GoldenConfigsGLTest, EveryShippedSceneMatchesItsGoldens) {
    expect_scenes_match_goldens("configs", "tests/golden/configs", 8);   // the demo and gallery
}

// One small scene per look a frame must have (tests/data/looks: trails across respawns and of
// shapes, arrows after contacts and on light bodies, the fitted camera), each against goldens
// looked at before they were pinned.
TEST(GoldenLooksGLTest, EveryLookMatchesItsGoldens) {
    expect_scenes_match_goldens("tests/data/looks", "tests/golden/looks", 4);
}

// The <testcase classname=... name=...> opening tags of a JUnit file, sorted.
std::vector<std::string> junit_cases(const std::string& path) {
    const std::string xml = read_file(path);
    std::vector<std::string> cases;
    for (auto at = xml.find("<testcase "); at != std::string::npos;
         at = xml.find("<testcase ", at + 1)) {
        cases.push_back(xml.substr(at, xml.find(" time=", at) - at));
    }
    std::sort(cases.begin(), cases.end());
    return cases;
}

// Playwright's --shard=K/N: N runs split the frames between them, and their JUnit files hold
// one full run's cases, each once.
TEST(GoldenShardsGLTest, ShardsTogetherCheckEveryFrameOnce) {
    std::vector<std::string> argv{bin, "golden"};
    for (const char* name : {"billiards", "cradle", "shapes"}) {
        argv.push_back((source_dir / "configs" / (std::string(name) + ".yaml")).string());
    }
    argv.insert(argv.end(), {"--dir", (source_dir / "tests/golden/configs").string(), "--size",
                             "320x180"});
    TempDir dir;
    auto full = argv;
    full.insert(full.end(), {"--junit", dir / "full.xml"});
    const auto run = run_command(full);
    ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
    const auto all = junit_cases(dir / "full.xml");
    ASSERT_GE(all.size(), 5u);
    std::vector<std::string> together;
    for (int k = 1; k <= 3; ++k) {
        auto shard = argv;
        const std::string junit = dir / ("shard" + std::to_string(k) + ".xml");
        shard.insert(shard.end(), {"--shard", std::to_string(k) + "/3", "--junit", junit});
        const auto part = run_command(shard);
        ASSERT_EQ(part.exit_code, 0) << part.out << part.err;
        const auto cases = junit_cases(junit);
        EXPECT_GE(cases.size(), all.size() / 3) << "shard " << k;
        EXPECT_LE(cases.size(), all.size() / 3 + 1) << "shard " << k;
        together.insert(together.end(), cases.begin(), cases.end());
    }
    std::sort(together.begin(), together.end());
    EXPECT_EQ(together, all);

    for (const char* bad : {"0/3", "4/3", "3", "a/b", "1/0"}) {
        auto refused = argv;
        refused.insert(refused.end(), {"--shard", bad});
        const auto result = run_command(refused);
        EXPECT_EQ(result.exit_code, 2) << bad;
        EXPECT_NE(result.err.find("expected K/N with 1 <= K <= N, e.g. 2/4, got '" +
                                  std::string(bad) + "'"),
                  std::string::npos)
            << result.err;
    }
}

}  // namespace
}  // namespace discreel
