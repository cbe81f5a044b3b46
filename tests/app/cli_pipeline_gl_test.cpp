// The render loop's user experience through the real binary: threaded and one-thread output
// are the same bytes, --progress/--quiet/--verbose print what they promise, memory stays flat
// however long the clip, and SIGINT/SIGTERM stop cleanly without leaving files behind.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <regex>
#include <thread>

#include "test_support.hpp"

extern char** environ;

namespace discreel {
namespace {

using testing::read_file;
using testing::run_command;
using testing::TempDir;

const std::string bin = DISCREEL_BIN;
const std::string scenes = std::string(DISCREEL_SOURCE_DIR) + "/tests/data/scenes/";
const std::string short_scene = scenes + "short.yaml";
const std::string gas_scene = scenes + "gas.yaml";
const std::string bounce_scene = scenes + "bounce100.yaml";

TEST(CliPipelineGLTest, ThreadedAndSequentialWriteTheSameBytes) {
    TempDir dir;
    const auto threaded = run_command({bin, "render", short_scene, "-o", dir / "a.mp4"});
    ASSERT_EQ(threaded.exit_code, 0) << threaded.err;
    const auto sequential =
        run_command({bin, "render", short_scene, "-o", dir / "b.mp4", "--sequential"});
    ASSERT_EQ(sequential.exit_code, 0) << sequential.err;
    const std::string a = read_file(dir / "a.mp4");
    EXPECT_GT(a.size(), 1000u);
    EXPECT_TRUE(a == read_file(dir / "b.mp4"));
}

TEST(CliPipelineGLTest, ProgressLinesWhenForcedOnANonTerminal) {
    TempDir dir;
    const auto run = run_command({bin, "render", short_scene, "-o", dir / "a.mp4", "--progress"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    // Plain lines, no carriage returns; the last one reports every frame done.
    EXPECT_EQ(run.err.find('\r'), std::string::npos);
    const std::regex last(R"(frame 30/30 \(100%\), [0-9.]+ fps, elapsed [0-9]+:[0-9]{2}, left 0:00\n$)");
    EXPECT_TRUE(std::regex_search(run.err, last)) << run.err;
    EXPECT_EQ(run.out.rfind("wrote ", 0), 0u);
}

TEST(CliPipelineGLTest, QuietPrintsNothingButErrors) {
    TempDir dir;
    const auto run = run_command({bin, "render", short_scene, "-o", dir / "a.mp4", "--quiet"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.out, "");
    EXPECT_EQ(run.err, "");
    EXPECT_TRUE(std::filesystem::exists(dir / "a.mp4"));

    const auto bad = run_command({bin, "render", short_scene, "-o", dir / "a.avi", "--quiet"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err, "");

    const auto both = run_command({bin, "render", short_scene, "-o", dir / "b.mp4", "-q", "-v"});
    EXPECT_EQ(both.exit_code, 2);
    EXPECT_NE(both.err.find("--quiet excludes --verbose"), std::string::npos) << both.err;
}

TEST(CliPipelineGLTest, VerboseReportsSettingsRendererStagesAndMemory) {
    TempDir dir;
    const auto run = run_command({bin, "render", short_scene, "-o", dir / "a.mp4", "--verbose"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("discreel: 160x120, 24 fps, frames 0..29, 3 discs; mp4, codec "
                           "default, crf default, preset veryfast, 1 encoder thread per "
                           "segment; simulate, render and encode threads; 1 segment of 48 "
                           "frames\n"),
              std::string::npos)
        << run.err;
    EXPECT_NE(run.err.find("discreel: renderer: llvmpipe"), std::string::npos) << run.err;
    EXPECT_TRUE(std::regex_search(
        run.err, std::regex(R"(discreel: busy: simulate [0-9.]+ s \([0-9.]+ ms/frame\), )"
                            R"(render [0-9.]+ s \([0-9.]+ ms/frame\), )"
                            R"(encode [0-9.]+ s \([0-9.]+ ms/frame\)\n)")))
        << run.err;
    EXPECT_TRUE(std::regex_search(run.err,
                                  std::regex(R"(discreel: peak memory: [0-9.]+ MiB \(VmHWM\)\n)")))
        << run.err;
}

double peak_mib(const std::string& err) {
    std::smatch match;
    if (!std::regex_search(err, match, std::regex(R"(peak memory: ([0-9.]+) MiB)"))) return -1;
    return std::stod(match[1]);
}

// Frames are streamed, never held: a 60 s clip needs no more memory than a 10 s one.
TEST(CliPipelineGLTest, PeakMemoryIsBoundedAndFlatInClipLength) {
    TempDir dir;
    const auto render = [&](const std::string& seconds) {
        return run_command({bin, "render", bounce_scene, "-o", dir / (seconds + ".mp4"), "--size",
                            "320x180", "--fps", "60", "--duration", seconds, "--verbose"});
    };
    const auto ten = render("10");
    ASSERT_EQ(ten.exit_code, 0) << ten.err;
    const auto sixty = render("60");   // 3 600 frames
    ASSERT_EQ(sixty.exit_code, 0) << sixty.err;
    EXPECT_EQ(testing::probe_video(dir / "60.mp4")["nb_read_frames"], "3600");

    const double short_peak = peak_mib(ten.err);
    const double long_peak = peak_mib(sixty.err);
    ASSERT_GT(short_peak, 0) << ten.err;
    ASSERT_GT(long_peak, 0) << sixty.err;
    // Most of the peak is Mesa's llvmpipe and LLVM; 3 frame slots at 320x180 are 0.7 MiB. The
    // bound leaves room for other Mesa builds.
    EXPECT_LT(long_peak, 200.0);
    // Holding the clip would add 0.23 MiB per frame, 580 MiB for the extra 2 500 frames. The
    // peak is not flat to the megabyte: measured on an idle machine, 138 MiB for clips of 10,
    // 20 and 40 s, then a one-time step to 145-148 MiB at 60, 120 and 240 s (12.5 MiB above the
    // 10 s clip once under load). 32 MiB allows that step and would still catch one frame in
    // ten kept.
    EXPECT_LT(long_peak - short_peak, 32.0) << short_peak << " MiB vs " << long_peak << " MiB";
}

// The required bound for a 1080p render: 300 MB (286.1 MiB). x264 holds most of it, for every
// input frame in flight; docs/performance.md lists what keeps it under and the current peak.
// Half a second of frames fills every queue and x264's lookahead, and the flat-in-length test
// above covers longer clips.
TEST(CliPipelineGLTest, PeakMemoryOfA1080pRenderIsUnder300MB) {
    TempDir dir;
    const auto run = run_command({bin, "render", gas_scene, "-o", dir / "hd.mp4", "--size",
                                  "1920x1080", "--duration", "0.5", "--verbose"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const double peak = peak_mib(run.err);
    ASSERT_GT(peak, 0) << run.err;
    EXPECT_LT(peak, 300e6 / (1024.0 * 1024.0));
}

// x264 writes its settings into the stream as text. Above 720p the veryfast lookahead is cut
// from 10 to 8 frames for memory; 720p keeps the preset's 10.
TEST(CliPipelineGLTest, X264LookaheadIsShortenedOnlyAbove720p) {
    TempDir dir;
    const auto render = [&](const std::string& size) {
        const auto run = run_command({bin, "render", short_scene, "-o", dir / (size + ".mp4"),
                                      "--size", size, "--duration", "0.1"});
        EXPECT_EQ(run.exit_code, 0) << run.err;
        return read_file(dir / (size + ".mp4"));
    };
    const std::string hd = render("1920x1080");
    EXPECT_NE(hd.find(" rc_lookahead=8 "), std::string::npos);
    const std::string sd = render("1280x720");
    EXPECT_NE(sd.find(" rc_lookahead=10 "), std::string::npos);
}

// Starts `discreel render` of a long clip into `dir` with stderr captured in dir/err.txt.
pid_t start_long_render(const TempDir& dir, const std::string& output) {
    const std::vector<std::string> args{bin,      "render",  gas_scene,  "-o",   output,
                                        "--size", "640x360", "--duration", "600"};
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    const std::string err_path = dir / "err.txt";
    posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT, 0644);
    pid_t pid = -1;
    const int failed = posix_spawn(&pid, bin.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    return failed == 0 ? pid : -1;
}

// A temporary file of the render (".NAME.tmp-XXXXXX", the output's or a segment's) with
// bytes in it, once it is there.
bool temp_file_appears(const TempDir& dir) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (std::chrono::steady_clock::now() < deadline) {
        for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
            const std::string name = entry.path().filename().string();
            // Some bytes in it: the encoder is running, not just the file created.
            if (name.rfind('.', 0) == 0 && name.find(".tmp-") != std::string::npos &&
                entry.file_size() > 0) {
                return true;
            }
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
}

void expect_clean_stop(int signal, int expected_exit_code) {
    TempDir dir;
    testing::write_file(dir / "clip.mp4", "an older render the user wants to keep");
    const pid_t pid = start_long_render(dir, dir / "clip.mp4");
    ASSERT_GT(pid, 0);
    const bool started = temp_file_appears(dir);
    kill(pid, signal);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(started);
    ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status);
    EXPECT_EQ(WEXITSTATUS(status), expected_exit_code);
    EXPECT_EQ(read_file(dir / "err.txt"), "discreel: interrupted; nothing was written\n");

    std::vector<std::string> left;
    for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
        left.push_back(entry.path().filename().string());
    }
    std::sort(left.begin(), left.end());
    EXPECT_EQ(left, (std::vector<std::string>{"clip.mp4", "err.txt"}));
    EXPECT_EQ(read_file(dir / "clip.mp4"), "an older render the user wants to keep");
}

TEST(CliPipelineGLTest, SigintStopsCleanlyWithExitCode130) { expect_clean_stop(SIGINT, 130); }

TEST(CliPipelineGLTest, SigtermStopsCleanlyWithExitCode143) { expect_clean_stop(SIGTERM, 143); }

}  // namespace
}  // namespace discreel
