#include <gtest/gtest.h>

#include "discreel/encode.hpp"
#include "encode_test_support.hpp"

namespace discreel::encode::test {
namespace {

const std::string supported =
    ".mp4 (H.264), .mkv (H.264, VP9, or FFV1 lossless), .webm (VP9), .gif, .png (one frame, or "
    "every frame for a numbered name such as frame_%04d.png), - (Matroska or fragmented MP4 on "
    "standard output), .wav (the soundtrack alone)";

SinkDef def_for(const std::filesystem::path& path) {
    SinkDef def;
    def.path = path.string();
    def.width = 64;
    def.height = 48;
    def.fps = 30;
    return def;
}

TEST(OpenSinkTest, UnknownExtensionIsRejectedWithTheSupportedList) {
    const auto directory = scratch_directory();
    auto sink = open_sink(def_for(directory / "clip.foo"));
    ASSERT_FALSE(sink.ok());
    EXPECT_EQ(sink.error().message,
              "unsupported output extension '.foo' (supported: " + supported + ")");
    EXPECT_TRUE(directory_entries(directory).empty());
}

TEST(OpenSinkTest, MissingExtensionIsRejected) {
    const auto directory = scratch_directory();
    const auto path = directory / "clip";
    auto sink = open_sink(def_for(path));
    ASSERT_FALSE(sink.ok());
    EXPECT_EQ(sink.error().message,
              "output '" + path.string() + "' has no extension (supported: " + supported + ")");
}

TEST(OpenSinkTest, ExtensionIsCaseInsensitive) {
    const auto directory = scratch_directory();
    auto sink = open_sink(def_for(directory / "SHOUTING.PNG"));
    ASSERT_TRUE(sink.ok()) << sink.error().message;
    ASSERT_TRUE((*sink)->write(solid_image(64, 48, 1, 2, 3).view()).ok());
    ASSERT_TRUE((*sink)->finish().ok());
    EXPECT_EQ(directory_entries(directory), std::vector<std::string>{"SHOUTING.PNG"});
}

TEST(OpenSinkTest, MissingDirectoryIsNamedAndNothingIsCreated) {
    const auto directory = scratch_directory();
    for (const char* name : {"out.mp4", "out.png"}) {
        const auto path = directory / "x" / name;
        auto sink = open_sink(def_for(path));
        ASSERT_FALSE(sink.ok()) << name;
        EXPECT_EQ(sink.error().message, "cannot write '" + path.string() + "': directory '" +
                                            (directory / "x").string() + "' does not exist");
    }
    EXPECT_TRUE(directory_entries(directory).empty());
}

TEST(OpenSinkTest, RelativePathInTheWorkingDirectoryNamesTheDirectory) {
    // "x/y.mp4" relative to the working directory: the message quotes the paths as given.
    auto sink = open_sink(def_for("no-such-directory-for-encode-tests/y.mp4"));
    ASSERT_FALSE(sink.ok());
    EXPECT_EQ(sink.error().message,
              "cannot write 'no-such-directory-for-encode-tests/y.mp4': directory "
              "'no-such-directory-for-encode-tests' does not exist");
}

}  // namespace
}  // namespace discreel::encode::test
