// Faults from outside: the output cannot be created, the disk fills up mid-clip, the GL context
// cannot be made, the encoder refuses to open. Each must end with a clear message and the
// documented exit code (3: run-time failure), leave no partial or temporary file, and leave a
// file already at the output path as it was. Through the real binary where the fault can be
// caused from outside it; "GL" in the suite name: these need OSMesa. SIGINT / SIGTERM mid-render
// are tested with the interruption handling itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "video_format.hpp"
#include "video_sink.hpp"

namespace discreel {
namespace {

using testing::directory_entries;
using testing::read_file;
using testing::run_command;
using testing::TempDir;

const std::string bin = DISCREEL_BIN;
const std::string short_scene = std::string(DISCREEL_SOURCE_DIR) + "/tests/data/scenes/short.yaml";

// As Manim and Remotion do: `-o out/a/b.mp4` makes out/a, for every output of the run.
TEST(FaultsGLTest, MissingOutputDirectoriesAreMade) {
    TempDir dir;
    const std::string out = dir / "a/b/clip.png";
    const auto run = run_command({bin, "render", short_scene, "-o", out, "--trace",
                                  dir / "c/trace.csv", "-q"});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_TRUE(std::filesystem::is_regular_file(out));
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "c/trace.csv"));
}

// A run refused before any work makes no directory.
TEST(FaultsGLTest, ARefusedRunMakesNoDirectory) {
    TempDir dir;
    const auto run = run_command({bin, "render", short_scene, "-o", dir / "a/clip.png",
                                  "--set", "physics.sede=1"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "--set physics.sede=1: physics: unknown key 'sede'; did you mean 'seed'?\n");
    EXPECT_TRUE(directory_entries(dir.path()).empty());
}

// The tests run as root in CI, where a chmod'ed directory stops nothing. sysfs refuses to create
// files for everyone, root included: EACCES where it is mounted read-write, EROFS where it is
// mounted read-only (as inside a container build); the message carries whichever the system
// gives. A regular file in the directory's place fails the same way everywhere (ENOTDIR).
TEST(FaultsGLTest, UnwritableOutputDirectoryIsARunTimeFailure) {
    const auto sysfs = run_command({bin, "render", short_scene, "-o", "/sys/discreel-fault.mp4"});
    EXPECT_EQ(sysfs.exit_code, 3);
    const std::string prefix = "discreel: cannot write '/sys/discreel-fault.mp4': ";
    EXPECT_TRUE(sysfs.err == prefix + "Permission denied\n" ||
                sysfs.err == prefix + "Read-only file system\n")
        << sysfs.err;
    EXPECT_FALSE(std::filesystem::exists("/sys/discreel-fault.mp4"));

    TempDir dir;
    testing::write_file(dir / "file", "precious");
    const std::string out = dir / "file/clip.mp4";
    const auto run = run_command({bin, "render", short_scene, "-o", out});
    EXPECT_EQ(run.exit_code, 3);
    EXPECT_EQ(run.err, "discreel: cannot write '" + out + "': '" + (dir / "file") +
                           "' is not a directory\n");
    EXPECT_EQ(read_file(dir / "file"), "precious");
    EXPECT_EQ(directory_entries(dir.path()), std::vector<std::string>{"file"});
}

// A full disk, made small and private: a file-size limit (RLIMIT_FSIZE, set by prlimit for the
// binary alone). With SIGXFSZ ignored, as here (an ignored signal survives exec), a write past
// the limit fails with EFBIG exactly where a full disk fails with ENOSPC.
class IgnoreSigxfsz {
public:
    IgnoreSigxfsz() : previous_(std::signal(SIGXFSZ, SIG_IGN)) {}
    ~IgnoreSigxfsz() { std::signal(SIGXFSZ, previous_); }
    IgnoreSigxfsz(const IgnoreSigxfsz&) = delete;
    IgnoreSigxfsz& operator=(const IgnoreSigxfsz&) = delete;

private:
    void (*previous_)(int);
};

TEST(FaultsGLTest, DiskFullMidClipLeavesNoPartialFileAndTheOldOneStays) {
    TempDir dir;
    testing::write_file(dir / "clip.mp4", "precious");
    const IgnoreSigxfsz ignore;
    // The whole clip is about 17 kB; 4 kB runs out in the middle of it.
    const auto run = run_command(
        {"prlimit", "--fsize=4096", bin, "render", short_scene, "-o", dir / "clip.mp4"});
    EXPECT_EQ(run.exit_code, 3);
    EXPECT_EQ(run.err, "discreel: cannot write '" + (dir / "clip.mp4") +
                           "': writing the trailer failed: File too large\n");
    EXPECT_EQ(read_file(dir / "clip.mp4"), "precious");
    EXPECT_EQ(directory_entries(dir.path()), std::vector<std::string>{"clip.mp4"});
}

// Mesa reads MESA_GL_VERSION_OVERRIDE; capped below 3.3 it cannot give the core-profile context
// the renderer asks for, and OSMesaCreateContextAttribs returns null.
TEST(FaultsGLTest, NoGlContextIsARunTimeFailureAndTheOldFileStays) {
    TempDir dir;
    testing::write_file(dir / "clip.mp4", "precious");
    const auto run = run_command({bin, "render", short_scene, "-o", dir / "clip.mp4"},
                                 {{"MESA_GL_VERSION_OVERRIDE", "3.2"}});
    EXPECT_EQ(run.exit_code, 3);
    EXPECT_EQ(run.err, "discreel: cannot create an OSMesa GL 3.3 core-profile context\n");
    EXPECT_EQ(read_file(dir / "clip.mp4"), "precious");
    EXPECT_EQ(directory_entries(dir.path()), std::vector<std::string>{"clip.mp4"});
}

// Mesa crashes (SIGSEGV inside OSMesaCreateContextAttribs) when GALLIUM_DRIVER names no
// driver. The output's temporary file already exists by then; the crash handler deletes it.
// In a sanitizer build AddressSanitizer reports the crash and exits 1 instead of dying of the
// signal, after the handler has run.
TEST(FaultsGLTest, ACrashInMesaLeavesNoTemporaryFileAndTheOldFileStays) {
    TempDir dir;
    testing::write_file(dir / "clip.mp4", "precious");
    const auto run = run_command({bin, "render", short_scene, "-o", dir / "clip.mp4"},
                                 {{"GALLIUM_DRIVER", "no-such-driver"}});
    EXPECT_TRUE(run.exit_code == 128 + SIGSEGV || run.exit_code == 1) << run.exit_code;
    EXPECT_EQ(read_file(dir / "clip.mp4"), "precious");
    EXPECT_EQ(directory_entries(dir.path()), std::vector<std::string>{"clip.mp4"});
}

// Every encoder option the CLI accepts is checked before anything is opened (a bad one is exit
// 2, see cli_gl_test.cpp), so libav refusing to open the encoder cannot be caused through the
// binary. Here the sink gets an option libx264 rejects only when avcodec_open2 runs.
TEST(EncoderFaultTest, EncoderThatFailsToOpenLeavesNoFileAndTheOldOneStays) {
    TempDir dir;
    testing::write_file(dir / "clip.mp4", "precious");
    encode::SinkDef def;
    def.path = dir / "clip.mp4";
    def.width = 64;
    def.height = 48;
    auto format = encode::mp4_format(def);
    ASSERT_TRUE(format.ok()) << format.error().message;
    for (auto& [name, value] : format->encoder_options)
        if (name == "preset") value = "no-such-preset";
    const auto sink = encode::open_video_sink(def, *format);
    ASSERT_FALSE(sink.ok());
    const std::string expected = "cannot write '" + def.path + "': cannot open the libx264 encoder: ";
    EXPECT_EQ(sink.error().message.rfind(expected, 0), 0u) << sink.error().message;
    EXPECT_EQ(read_file(dir / "clip.mp4"), "precious");
    EXPECT_EQ(directory_entries(dir.path()), std::vector<std::string>{"clip.mp4"});
}

}  // namespace
}  // namespace discreel
