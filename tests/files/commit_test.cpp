// Outputs committed together (all or none), bounded reads and file identity: the mechanisms
// every command's outputs and inputs go through.
#include "discreel/commit.hpp"

#include <sys/stat.h>

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "discreel/file_identity.hpp"
#include "discreel/output_file.hpp"
#include "discreel/read_file.hpp"
#include "test_support.hpp"

namespace discreel {
namespace {

namespace fs = std::filesystem;
using testing::directory_entries;
using testing::read_file;
using testing::TempDir;
using testing::write_file;

OutputFile written(const std::string& path, const std::string& text) {
    auto file = OutputFile::create(path);
    EXPECT_TRUE(file) << file.error().message;
    EXPECT_TRUE(file->write_all(text.data(), text.size()));
    return std::move(*file);
}

TEST(CommitTest, AllTargetsChangeTogether) {
    TempDir dir;
    write_file(dir / "a", "old a");
    OutputFile a = written(dir / "a", "new a");
    OutputFile b = written(dir / "b", "new b");
    OutputFile* files[] = {&a, &b};
    ASSERT_TRUE(commit_together(files));
    EXPECT_EQ(read_file(dir / "a"), "new a");
    EXPECT_EQ(read_file(dir / "b"), "new b");
    EXPECT_EQ(directory_entries(dir.path()), (std::vector<std::string>{"a", "b"}));
}

// The third rename fails (its target became a directory after the file was created): the two
// targets already replaced get their old contents back, the new one is removed again.
TEST(CommitTest, ARenameThatFailsPutsBackEveryTargetAlreadyReplaced) {
    TempDir dir;
    write_file(dir / "a", "old a");
    OutputFile a = written(dir / "a", "new a");
    OutputFile b = written(dir / "b", "new b");
    OutputFile c = written(dir / "c", "new c");
    fs::create_directory(dir / "c");
    write_file(dir / "c/inside", "keeps the directory from being replaced");
    OutputFile* files[] = {&a, &b, &c};
    const Status committed = commit_together(files);
    ASSERT_FALSE(committed);
    EXPECT_EQ(committed.error().message.rfind("cannot write '" + (dir / "c") + "': ", 0), 0U);
    EXPECT_EQ(read_file(dir / "a"), "old a");
    EXPECT_FALSE(fs::exists(dir / "b"));
    EXPECT_TRUE(fs::is_directory(dir / "c"));
}

TEST(CommitTest, TemporaryFilesAndBackupsAreGoneAfterAFailedCommit) {
    TempDir dir;
    write_file(dir / "a", "old a");
    {
        OutputFile a = written(dir / "a", "new a");
        OutputFile c = written(dir / "c", "new c");
        fs::create_directory(dir / "c");
        write_file(dir / "c/inside", "x");
        OutputFile* files[] = {&a, &c};
        ASSERT_FALSE(commit_together(files));
    }
    EXPECT_EQ(directory_entries(dir.path()), (std::vector<std::string>{"a", "c"}));
}

TEST(CommitTest, ADirectoryTargetIsRefusedAtCreation) {
    TempDir dir;
    fs::create_directory(dir / "out.mp4");
    const auto file = OutputFile::create(dir / "out.mp4");
    ASSERT_FALSE(file);
    EXPECT_EQ(file.error().message,
              "cannot write '" + (dir / "out.mp4") + "': it is a directory; name a file inside it");
}

TEST(CommitTest, ALinkIsFollowedAndKept) {
    TempDir dir;
    write_file(dir / "real", "old");
    fs::create_symlink("real", dir / "link");
    OutputFile file = written(dir / "link", "new");
    ASSERT_TRUE(file.commit());
    EXPECT_TRUE(fs::is_symlink(dir / "link"));
    EXPECT_EQ(read_file(dir / "real"), "new");
}

TEST(CommitTest, ASpecialFileIsWrittenInPlace) {
    auto file = OutputFile::create("/dev/null");
    ASSERT_TRUE(file) << file.error().message;
    EXPECT_TRUE(file->direct());
    EXPECT_TRUE(file->write_all("x", 1));
    EXPECT_TRUE(file->commit());
    struct stat info {};
    ASSERT_EQ(stat("/dev/null", &info), 0);
    EXPECT_TRUE(S_ISCHR(info.st_mode));
}

TEST(ReadFileBoundedTest, ReadsAtMostTheLimitAndOneByte) {
    const auto zero = read_file_bounded("/dev/zero", 1000);
    ASSERT_TRUE(zero);
    EXPECT_TRUE(zero->too_large);
    EXPECT_EQ(zero->bytes.size(), 1001U);

    TempDir dir;
    write_file(dir / "f", "12345");
    const auto exact = read_file_bounded(dir / "f", 5);
    ASSERT_TRUE(exact);
    EXPECT_FALSE(exact->too_large);
    EXPECT_EQ(exact->bytes, "12345");
    const auto over = read_file_bounded(dir / "f", 4);
    ASSERT_TRUE(over);
    EXPECT_TRUE(over->too_large);

    const auto directory = read_file_bounded(dir.path().string(), 10);
    ASSERT_FALSE(directory);
    EXPECT_EQ(directory.error().message, "this is a directory, not a file");
}

TEST(FileIdentityTest, SameFileThroughLinksAndSpellings) {
    TempDir dir;
    write_file(dir / "a", "x");
    fs::create_directory(dir / "sub");
    fs::create_symlink(dir / "a", dir / "sub/link");
    EXPECT_TRUE(same_file(dir / "a", dir / "sub/link"));
    EXPECT_TRUE(same_file(dir / "a", dir / "sub/../a"));
    EXPECT_FALSE(same_file(dir / "a", dir / "b"));
    // Neither exists yet: the same path all the same, so two outputs would collide.
    EXPECT_TRUE(same_file(dir / "new", dir / "sub/../new"));
    // A link to a file not there yet is that file.
    fs::create_symlink("target", dir / "dangling");
    EXPECT_TRUE(same_file(dir / "dangling", dir / "target"));

    const auto clash = find_clash({{"the scene", dir / "a"}},
                                  {{"-o", dir / "out"}, {"--trace", dir / "sub/link"}});
    ASSERT_TRUE(clash);
    EXPECT_EQ(*clash, "--trace '" + (dir / "sub/link") + "' is the same file as the scene '" +
                          (dir / "a") + "', which it would overwrite; write to another file");
    EXPECT_FALSE(find_clash({{"the scene", dir / "a"}}, {{"-o", dir / "out"}}));
}

}  // namespace
}  // namespace discreel
