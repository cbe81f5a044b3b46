// What a hostile user tried (docs/reliability.md, "Hostile input"): outputs that would destroy
// inputs or each other, special files, failed runs that must leave every old output as it was,
// signals of every kind, endless or huge inputs, numbers that would wrap, and names that would
// drive the terminal. Each runs the real binary, as the user does; "GL" in the suite name: the
// render and golden commands need OSMesa.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "test_support.hpp"

namespace discreel {
namespace {

namespace fs = std::filesystem;
using testing::directory_entries;
using testing::read_file;
using testing::run_command;
using testing::TempDir;
using testing::write_file;

const std::string bin = DISCREEL_BIN;
const std::string scenes = std::string(DISCREEL_SOURCE_DIR) + "/tests/data/scenes/";
const std::string short_scene = scenes + "short.yaml";
const std::string gas_scene = scenes + "gas.yaml";

// A tiny scene with two golden frames, named `name` (its file's stem).
std::string tiny_scene(const TempDir& dir, const std::string& name,
                       const std::string& colour = "#ff0000") {
    const std::string path = dir / (name + ".yaml");
    write_file(path, "version: 1\n"
                     "video: {size: [64, 36], fps: 10, duration: 1}\n"
                     "walls:\n  - box: [[0, 0], [6.4, 3.6]]\n"
                     "discs:\n  - {id: a, position: [1, 1], radius: 0.3, color: \"" +
                         colour + "\"}\n"
                     "golden: {frames: [0, 5]}\n");
    return path;
}

// Names in `dir` that are temporary or backup files of ours.
std::vector<std::string> leftovers(const fs::path& dir) {
    std::vector<std::string> found;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        if (name.find(".tmp-") != std::string::npos || name.find(".old-") != std::string::npos) {
            found.push_back(name);
        }
    }
    return found;
}

// Starts the binary with stdout to `out` (a file, or -1: /dev/null) and stderr to err_path.
pid_t start(const std::vector<std::string>& args, const std::string& err_path, int out_fd = -1) {
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    if (out_fd >= 0) {
        posix_spawn_file_actions_adddup2(&actions, out_fd, 1);
    } else {
        posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    }
    posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT, 0644);
    // The child starts with every signal at its default, whatever this process inherited.
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t all;
    sigfillset(&all);
    posix_spawnattr_setsigdefault(&attributes, &all);
    sigset_t none;
    sigemptyset(&none);
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
    pid_t pid = -1;
    const int failed = posix_spawn(&pid, bin.c_str(), &actions, &attributes, argv.data(), environ);
    posix_spawnattr_destroy(&attributes);
    posix_spawn_file_actions_destroy(&actions);
    return failed == 0 ? pid : -1;
}

// Waits (at most 30 s) until a temporary file with some bytes in it is in `dir`: the run is
// past its set-up and into its work.
bool working(const fs::path& dir) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (std::chrono::steady_clock::now() < deadline) {
        for (const auto& entry : fs::directory_iterator(dir)) {
            if (entry.path().filename().string().find(".tmp-") != std::string::npos &&
                entry.is_regular_file() && entry.file_size() > 0) {
                return true;
            }
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
}

// The exit status of `pid`, or -1 (and the process killed) when it has not ended in 60 s.
int exit_status_of(pid_t pid) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    int status = 0;
    while (waitpid(pid, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() > deadline) {
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            return -1;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
}

// --- Data lost or corrupted -------------------------------------------------------------------

TEST(HostileInputGLTest, AFailedRunReplacesNoOutput) {
    TempDir dir;
    write_file(dir / "keep.mp4", "the user's older video");
    fs::create_directory(dir / "t.csv");
    const auto run =
        run_command({bin, "render", short_scene, "-o", dir / "keep.mp4", "--trace", dir / "t.csv"});
    EXPECT_EQ(run.exit_code, 3);
    EXPECT_EQ(run.err,
              "discreel: cannot write '" + (dir / "t.csv") + "': it is a directory; name a file "
                                                             "inside it\n");
    EXPECT_EQ(read_file(dir / "keep.mp4"), "the user's older video");
    EXPECT_TRUE(leftovers(dir.path()).empty());
}

TEST(HostileInputGLTest, AFailedSequenceLeavesTheOldFrames) {
    TempDir dir;
    const std::string pattern = dir / "f_%04d.png";
    ASSERT_EQ(run_command({bin, "render", short_scene, "-o", pattern, "-q"}).exit_code, 0);
    const std::string frame1 = read_file(dir / "f_0001.png");
    fs::remove(dir / "f_0005.png");
    fs::create_directory(dir / "f_0005.png");
    const std::string other = tiny_scene(dir, "other", "#00ff00");
    const auto run = run_command({bin, "render", other, "-o", pattern, "--size", "160x120",
                                  "--fps", "24", "--duration", "1.25"});
    EXPECT_EQ(run.exit_code, 3);
    EXPECT_EQ(read_file(dir / "f_0001.png"), frame1);
    EXPECT_TRUE(fs::exists(dir / "f_0000.png"));
    EXPECT_TRUE(fs::exists(dir / "f_0004.png"));
    EXPECT_TRUE(fs::exists(dir / "f_0029.png"));
    EXPECT_TRUE(leftovers(dir.path()).empty());
}

TEST(HostileInputGLTest, GoldenUpdateWritesAllGoldensOrNone) {
    TempDir dir;
    const std::string first = tiny_scene(dir, "first");
    const std::string second = tiny_scene(dir, "second");
    fs::create_directories(dir / "g/first");
    write_file(dir / "g/first/frame_0.png", "old golden");
    // The second scene's folder cannot be made: the run fails after the first scene is done.
    write_file(dir / "g/second", "a file where the folder should be");
    const auto run = run_command({bin, "golden", first, second, "--dir", dir / "g", "--update"});
    EXPECT_EQ(run.exit_code, 3) << run.err;
    EXPECT_EQ(read_file(dir / "g/first/frame_0.png"), "old golden");
    EXPECT_EQ(directory_entries(dir / "g/first"), std::vector<std::string>{"frame_0.png"});
    EXPECT_TRUE(leftovers(dir.path()).empty());
}

TEST(HostileInputGLTest, AnOutputThatIsAnInputOrAnotherOutputIsRefused) {
    TempDir dir;
    const std::string scene = tiny_scene(dir, "sc");
    const std::string text = read_file(scene);
    auto run = run_command({bin, "simulate", scene, "--trace", scene});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: --trace '" + scene + "' is the same file as the scene '" +
                           scene + "', which it would overwrite; write to another file\n");
    EXPECT_EQ(read_file(scene), text);

    // Through a symbolic link, and spelt another way: the same file all the same.
    fs::create_symlink(scene, dir / "link.yaml");
    run = run_command({bin, "render", scene, "-o", dir / "x/../link.yaml"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(read_file(scene), text);

    run = run_command({bin, "render", scene, "-o", dir / "x.mp4", "--trace", dir / "x.mp4"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: --trace '" + (dir / "x.mp4") + "' and -o '" + (dir / "x.mp4") +
                           "' are the same file; give each output its own\n");
    EXPECT_FALSE(fs::exists(dir / "x.mp4"));
}

TEST(HostileInputGLTest, SpecialFilesAreWrittenThroughAndLinksAreFollowed) {
    TempDir dir;
    auto run = run_command({bin, "simulate", short_scene, "--trace", "/dev/null"});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    struct stat info {};
    ASSERT_EQ(stat("/dev/null", &info), 0);
    EXPECT_TRUE(S_ISCHR(info.st_mode)) << "/dev/null must stay a device";
    EXPECT_TRUE(leftovers("/dev").empty());

    fs::create_symlink("real.csv", dir / "link.csv");
    run = run_command({bin, "simulate", short_scene, "--trace", dir / "link.csv"});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_TRUE(fs::is_symlink(dir / "link.csv"));
    EXPECT_EQ(read_file(dir / "real.csv").rfind("frame,t,id,", 0), 0U);
}

// --- Signals ----------------------------------------------------------------------------------

void expect_clean_stop(const std::vector<std::string>& command, int signal_number) {
    TempDir dir;
    write_file(dir / "out.mp4", "kept");
    std::vector<std::string> args{bin};
    for (const std::string& a : command) args.push_back(a == "OUT" ? dir / "out.mp4" : a);
    args.push_back("--trace");
    args.push_back(dir / "t.csv");
    const pid_t pid = start(args, dir / "err.txt");
    ASSERT_GT(pid, 0);
    const bool started = working(dir.path());
    kill(pid, signal_number);
    EXPECT_EQ(exit_status_of(pid), 128 + signal_number);
    ASSERT_TRUE(started);
    EXPECT_EQ(read_file(dir / "err.txt"), "discreel: interrupted; nothing was written\n");
    EXPECT_EQ(directory_entries(dir.path()), (std::vector<std::string>{"err.txt", "out.mp4"}));
    EXPECT_EQ(read_file(dir / "out.mp4"), "kept");
}

TEST(HostileInputGLTest, RenderStopsCleanlyOnEveryTerminatingSignal) {
    for (const int signal_number : {SIGHUP, SIGQUIT, SIGUSR1, SIGALRM, SIGUSR2}) {
        SCOPED_TRACE(strsignal(signal_number));
        expect_clean_stop({"render", gas_scene, "-o", "OUT", "--size", "320x180", "--duration",
                           "600"},
                          signal_number);
    }
}

TEST(HostileInputGLTest, SimulateStopsCleanlyOnSigintAndSigterm) {
    for (const int signal_number : {SIGINT, SIGTERM}) {
        SCOPED_TRACE(strsignal(signal_number));
        expect_clean_stop({"simulate", gas_scene, "--duration", "3000", "--max-substeps",
                           "1000000000"},
                          signal_number);
    }
}

TEST(HostileInputGLTest, AClosedPipeStopsTheStreamAndLeavesNoTemporaryFile) {
    TempDir dir;
    int pipe_fds[2];
    ASSERT_EQ(pipe2(pipe_fds, O_CLOEXEC), 0);   // the child keeps only its standard output
    const pid_t pid = start({bin, "render", gas_scene, "-o", "-", "--size", "320x180",
                             "--duration", "600", "--trace", dir / "t.csv"},
                            dir / "err.txt", pipe_fds[1]);
    close(pipe_fds[1]);
    ASSERT_GT(pid, 0);
    std::vector<char> buffer(100'000);
    std::size_t got = 0;
    while (got < buffer.size()) {   // as `| head -c 100000`
        const ssize_t n = read(pipe_fds[0], buffer.data() + got, buffer.size() - got);
        if (n <= 0) break;
        got += static_cast<std::size_t>(n);
    }
    close(pipe_fds[0]);
    EXPECT_EQ(got, buffer.size());
    EXPECT_EQ(exit_status_of(pid), 128 + SIGPIPE);
    EXPECT_EQ(directory_entries(dir.path()), std::vector<std::string>{"err.txt"});
}

// --- Unbounded work and memory ----------------------------------------------------------------

TEST(HostileInputGLTest, EndlessInputsAreReadOnlyUpToTheLimit) {
    const auto started = std::chrono::steady_clock::now();
    auto run = run_command({bin, "validate", "/dev/zero", "--max-scene-bytes", "1000000"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "/dev/zero: the input holds more than 1000000 bytes, the limit (raise it "
                       "with --max-scene-bytes)\n");
    run = run_command({bin, "validate", "/dev/urandom"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(20));

    // A golden that is an endless device is that frame's failure.
    TempDir dir;
    const std::string scene = tiny_scene(dir, "s");
    ASSERT_EQ(run_command({bin, "golden", scene, "--dir", dir / "g", "--update"}).exit_code, 0);
    fs::remove(dir / "g/s/frame_5.png");
    fs::create_symlink("/dev/zero", dir / "g/s/frame_5.png");
    run = run_command({bin, "golden", scene, "--dir", dir / "g"});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.out.find("s frame 0: ok (identical)\n"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("s frame 5: FAILED: cannot read '" + (dir / "g/s/frame_5.png") +
                           "': not a PNG file; recreate it with: "),
              std::string::npos)
        << run.out;
}

TEST(HostileInputGLTest, WhatCannotBeASceneIsRefusedBeforeItIsParsed) {
    TempDir dir;
    std::string values = "version: 1\nx: [1";
    for (int i = 0; i < 1'300'000; ++i) values += ",1";
    write_file(dir / "values.yaml", values + "]\n");
    auto run = run_command({bin, "validate", dir / "values.yaml"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, dir / "values.yaml" +
                           ":2:1: unknown top-level key 'x', holding more values than any scene "
                           "needs; expected one of: version, video, camera, style, physics, "
                           "walls, discs, bodies, throws, joints, golden\n");

    std::string discs = "version: 1\ndiscs:\n";
    for (int i = 0; i < 1001; ++i) discs += "  - {position: [1, 1], radius: 0.1}\n";
    write_file(dir / "discs.yaml", discs);
    run = run_command({bin, "validate", dir / "discs.yaml", "--max-discs", "1000"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, dir / "discs.yaml" +
                           ":1003:5: discs: more than 1000 entries in 'discs' and 'bodies', and "
                           "each makes at least one body; the limit is 1000 (raise it with "
                           "--max-bodies)\n");

    // Discs and bodies count together, under either name of the option.
    std::string mixed = "version: 1\ndiscs:\n";
    for (int i = 0; i < 600; ++i) mixed += "  - {position: [1, 1], radius: 0.1}\n";
    mixed += "bodies:\n";
    for (int i = 0; i < 401; ++i) mixed += "  - {circle: 0.1, position: [1, 1]}\n";
    write_file(dir / "mixed.yaml", mixed);
    run = run_command({bin, "validate", dir / "mixed.yaml", "--max-bodies", "1000"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, dir / "mixed.yaml" +
                           ":1004:5: bodies: more than 1000 entries in 'discs' and 'bodies', and "
                           "each makes at least one body; the limit is 1000 (raise it with "
                           "--max-bodies)\n");

    run = run_command({bin, "validate", dir / "discs.yaml", "--max-scene-values", "5000"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err.substr(run.err.find(": ") + 2),
              "the file holds more than 5000 YAML values (scalars, lists and mappings), the "
              "limit; raise it with --max-scene-values\n");
}

// Peak resident memory of the children this process has waited for, in bytes.
long children_peak_bytes() {
    struct rusage usage {};
    getrusage(RUSAGE_CHILDREN, &usage);
    return usage.ru_maxrss * 1024L;
}

// Not run under the sanitizers (ctest -E PeakMemory): their shadow memory is most of it.
TEST(HostileInputGLTest, PeakMemoryOfTheLargestSceneAtTheDefaultLimitsIsUnderOneGiB) {
    TempDir dir;
    // 100 000 discs written out one by one, each with an id and a colour: the largest scene
    // the default limits allow, and the most YAML values they let through.
    std::string text = "version: 1\nwalls:\n  - box: [[0, 0], [1000, 1000]]\ndiscs:\n";
    for (int i = 0; i < 100'000; ++i) {
        text += "  - {id: d" + std::to_string(i) + ", position: [" + std::to_string(1 + i % 900) +
                ".5, " + std::to_string(1 + i / 900) + "], radius: 0.2, color: \"#ff0000\"}\n";
    }
    write_file(dir / "big.yaml", text);
    const auto run = run_command({bin, "validate", dir / "big.yaml"});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_LT(children_peak_bytes(), 1L << 30);
}

TEST(HostileInputGLTest, NumbersAreRangeCheckedBeforeTheyAreConverted) {
    TempDir dir;
    const std::string scene = tiny_scene(dir, "s");
    auto run = run_command({bin, "render", scene, "-o", dir / "a.png", "--at", "1e19"});
    EXPECT_EQ(run.exit_code, 2);
    run = run_command({bin, "render", scene, "-o", dir / "a.png", "--at", "1e9"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: --at must be a time in the clip, 0 to 1 seconds\n");
    run = run_command({bin, "simulate", scene, "--max-duration", "nan"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err.rfind("discreel: --max-duration: expected a finite number, got 'nan'", 0),
              0U)
        << run.err;
    run = run_command({bin, "golden", scene, "--dir", dir / "g", "--tolerance", "nan"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_FALSE(fs::exists(dir / "a.png"));

    write_file(dir / "long.yaml", "version: 1\nvideo: {fps: 240, duration: 1e8}\n");
    run = run_command({bin, "validate", dir / "long.yaml", "--max-duration", "1e9"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, dir / "long.yaml" +
                           ":2:29: video.duration: 100000000 seconds at 240 fps is more than "
                           "1000000000 frames, the most a clip may have\n");
}

// Numbers in options are read as the person typed them: "-1" never wraps into an unsigned
// option, and a range error names its bounds as numbers, not a 310-digit double.
TEST(HostileInputGLTest, OptionNumbersNeverWrapAndTheirRangesAreReadable) {
    TempDir dir;
    const std::string scene = tiny_scene(dir, "s");
    const auto refused = [&](std::vector<std::string> args) {
        args.insert(args.begin(), bin);
        const auto run = run_command(args);
        EXPECT_EQ(run.exit_code, 2);
        return run.err.substr(0, run.err.find('\n'));
    };
    EXPECT_EQ(refused({"validate", scene, "--max-scene-bytes", "0"}),
              "discreel: --max-scene-bytes: must be from 1 to 4294967296, got 0");
    EXPECT_EQ(refused({"validate", scene, "--max-scene-bytes", "18446744073709551615"}),
              "discreel: --max-scene-bytes: must be from 1 to 4294967296, got "
              "18446744073709551615");
    EXPECT_EQ(refused({"render", scene, "-o", dir / "p", "--segment", "-1"}),
              "discreel: --segment: must be from 0 to 1000000000, got -1");
    EXPECT_EQ(refused({"render", scene, "-o", dir / "a.mp4", "--jobs", "2000"}),
              "discreel: --jobs: must be from 1 to 1024, got 2000");
    EXPECT_EQ(refused({"batch", dir / "m.txt", "--index", "-1"}),
              "discreel: --index: expected an index I or a range A-B of indexes (A <= B, "
              "from 0), got '-1'");
    EXPECT_EQ(refused({"serve", "--workers", "0"}),
              "discreel: --workers: must be from 1 to 64, got 0");
    // The largest accepted limit reads files as any other does.
    const auto run = run_command({bin, "validate", scene, "--max-scene-bytes", "4294967296"});
    EXPECT_EQ(run.exit_code, 0) << run.err;
}

// --jobs beyond what the available memory holds is cut to it, and the run says so.
TEST(HostileInputGLTest, JobsBeyondWhatMemoryHoldsAreCutAndSaid) {
    TempDir dir;
    // 8K frames: each segment at once holds about 1.6 GB, so 1 024 of them fit no machine.
    write_file(dir / "many.yaml", "version: 1\nvideo: {size: [7680, 4320], fps: 10, duration: "
                                  "100, segment: 0.1}\ndiscs:\n  - {position: [1, 1], radius: "
                                  "0.3}\n");
    // A file stands where the output's directory should be: the run fails once the plan is
    // made, before any work.
    write_file(dir / "file", "");
    const auto run = run_command({bin, "render", dir / "many.yaml", "-o", dir / "file/a.mp4",
                                  "--jobs", "1024"});
    EXPECT_EQ(run.exit_code, 3);
    EXPECT_EQ(run.err.rfind("discreel: --jobs 1024: rendering ", 0), 0u) << run.err;
    EXPECT_NE(run.err.find(" segments at once, as many as the available memory holds at "
                           "7680x4320\n"),
              std::string::npos)
        << run.err;
}

// A run blocked in a call that no signal interrupts (a write to a pipe that nobody reads) still
// ends after one SIGINT: 10 s later, as the first signal asked.
TEST(HostileInputGLTest, OneSignalEndsARunBlockedOnAPipeNobodyReads) {
    TempDir dir;
    int pipe_fds[2];
    ASSERT_EQ(pipe2(pipe_fds, O_CLOEXEC), 0);
    const pid_t pid = start({bin, "render", gas_scene, "-o", "-", "--lossless", "--size",
                             "640x360", "--duration", "600"},
                            dir / "err.txt", pipe_fds[1]);
    close(pipe_fds[1]);
    ASSERT_GT(pid, 0);
    // The pipe fills (64 KiB: part of the first frame) and the writer waits.
    std::this_thread::sleep_for(std::chrono::seconds(2));
    const auto signalled = std::chrono::steady_clock::now();
    kill(pid, SIGINT);
    const int status = exit_status_of(pid);
    const double waited =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count();
    close(pipe_fds[0]);
    EXPECT_EQ(status, 1000 + SIGINT);
    EXPECT_GT(waited, 8.0);
    EXPECT_LT(waited, 14.0);
    EXPECT_EQ(directory_entries(dir.path()), std::vector<std::string>{"err.txt"});
}

TEST(HostileInputGLTest, PhysicsWorkIsBounded) {
    TempDir dir;
    write_file(dir / "work.yaml", "version: 1\nvideo: {duration: 3600}\n"
                                  "physics: {rate: 100000, substeps: 1000}\n"
                                  "discs:\n  - {position: [1, 1], radius: 0.1}\n");
    auto run = run_command({bin, "validate", dir / "work.yaml"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, dir / "work.yaml" +
                           ":3:10: 3600 seconds at 100000 steps per second and 1000 substeps per "
                           "step is 360000000000 physics substeps, more than the limit of "
                           "50000000 (raise it with --max-substeps)\n");
    run = run_command({bin, "validate", dir / "work.yaml", "--max-substeps", "400000000000"});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    // A longer --duration on the command line is held to the same bound.
    run = run_command({bin, "simulate", short_scene, "--duration", "3600", "--max-substeps",
                       "1000000"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: 3600 seconds at 480 steps per second and 1 substep per step is "
                       "1728000 physics substeps, more than the limit of 1000000 (raise it with "
                       "--max-substeps)\n");
}

// --- Messages and faults ----------------------------------------------------------------------

TEST(HostileInputGLTest, AGoldenThatIsNoFileIsThatFramesFailure) {
    TempDir dir;
    const std::string scene = tiny_scene(dir, "s");
    ASSERT_EQ(run_command({bin, "golden", scene, "--dir", dir / "g", "--update"}).exit_code, 0);
    fs::remove(dir / "g/s/frame_0.png");
    fs::create_directory(dir / "g/s/frame_0.png");
    // A header that claims 16000 x 16000 pixels is judged by the header alone.
    std::string huge("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\0\x3e\x80\0\0\x3e\x80\x08\x06\0\0\0", 29);
    write_file(dir / "g/s/frame_5.png", huge);
    const auto started = std::chrono::steady_clock::now();
    const auto run = run_command({bin, "golden", scene, "--dir", dir / "g"});
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(10));
    EXPECT_EQ(run.exit_code, 1) << run.err;
    EXPECT_NE(run.out.find("s frame 0: FAILED: cannot read '" + (dir / "g/s/frame_0.png") +
                           "': this is a directory, not a file;"),
              std::string::npos)
        << run.out;
    EXPECT_NE(run.out.find("s frame 5: FAILED: cannot read '" + (dir / "g/s/frame_5.png") +
                           "': the PNG is 16000x16000, more pixels than the largest frame "
                           "(7680x4320);"),
              std::string::npos)
        << run.out;
    EXPECT_NE(run.out.find("golden: 2 frames of 1 scene: 0 passed, 2 failed\n"),
              std::string::npos);
}

TEST(HostileInputGLTest, ControlBytesInNamesAreEscapedInMessages) {
    TempDir dir;
    write_file(dir / "ids.yaml", "version: 1\ndiscs:\n"
                                 "  - {id: \"a\\e[31mX\\nY\", position: [1, 1], radius: 0.1}\n");
    auto run = run_command({bin, "validate", dir / "ids.yaml"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, dir / "ids.yaml" +
                           ":3:10: discs[0].id: 'a\\x1b[31mX\\nY' is not a valid id; use "
                           "letters, digits, '_', '-' and '.'\n");
    // A file in the place of the output's directory: the message names both.
    write_file(dir / "no\x1b[2Jdir\n", "");
    const std::string evil = dir / "no\x1b[2Jdir\n/out.mp4";
    run = run_command({bin, "render", short_scene, "-o", evil});
    EXPECT_EQ(run.exit_code, 3);
    EXPECT_EQ(run.err.find('\x1b'), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_NE(run.err.find("no\\x1b[2Jdir\\n/out.mp4"), std::string::npos) << run.err;
}

TEST(HostileInputGLTest, AnOutputThatIsADirectoryIsRefusedBeforeAnyWork) {
    TempDir dir;
    fs::create_directory(dir / "clip.mp4");
    const auto started = std::chrono::steady_clock::now();
    const auto run = run_command(
        {bin, "render", gas_scene, "-o", dir / "clip.mp4", "--duration", "600"});
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(10));
    EXPECT_EQ(run.exit_code, 3);
    EXPECT_EQ(run.err, "discreel: cannot write '" + (dir / "clip.mp4") +
                           "': it is a directory; name a file inside it\n");
}

TEST(HostileInputGLTest, TaggedStringsCarriageReturnsAndAFullStandardOutput) {
    TempDir dir;
    write_file(dir / "str.yaml", "version: 1\ndiscs:\n  - {position: [1, 1], radius: !!str 0.1}\n");
    auto run = run_command({bin, "validate", dir / "str.yaml"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, dir / "str.yaml" +
                           ":3:32: discs[0].radius: expected a number, got the text '0.1' "
                           "(tagged !!str); remove the tag\n");

    // Old Mac line ends: the positions are those of a file with ordinary ones.
    write_file(dir / "cr.yaml", "version: 1\rdiscs:\r  - {position: [1, 1], radius: -1}\r");
    write_file(dir / "lf.yaml", "version: 1\ndiscs:\n  - {position: [1, 1], radius: -1}\n");
    run = run_command({bin, "validate", dir / "cr.yaml"});
    const auto lf = run_command({bin, "validate", dir / "lf.yaml"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err.substr(run.err.find(".yaml:")), lf.err.substr(lf.err.find(".yaml:")));
    EXPECT_EQ(lf.err.rfind(dir / "lf.yaml:3:32: discs[0].radius: ", 0), 0U) << lf.err;

    run = run_command({"/bin/sh", "-c", "exec \"$0\" validate \"$1\" > /dev/full", bin,
                       short_scene});
    EXPECT_EQ(run.exit_code, 3);
    EXPECT_EQ(run.err, "discreel: cannot write to standard output\n");
}

}  // namespace
}  // namespace discreel
