#include "discreel/output_file.hpp"

#include <sys/stat.h>

#include <csignal>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "discreel/temporary_files.hpp"
#include "test_support.hpp"

namespace discreel {
namespace {

using testing::directory_entries;
using testing::read_file;
using testing::TempDir;
using testing::write_file;

TEST(OutputFileTest, CommitReplacesTheTargetWithOrdinaryPermissions) {
    TempDir dir;
    write_file(dir / "out.txt", "old");
    auto file = OutputFile::create(dir / "out.txt");
    ASSERT_TRUE(file) << file.error().message;
    ASSERT_TRUE(file->write_all("new", 3));
    EXPECT_EQ(read_file(dir / "out.txt"), "old") << "the target changes only at commit";
    ASSERT_TRUE(file->commit());
    EXPECT_EQ(read_file(dir / "out.txt"), "new");
    EXPECT_EQ(directory_entries(dir.path()), std::vector<std::string>{"out.txt"});
    const mode_t mask = umask(0);
    umask(mask);
    struct stat info {};
    ASSERT_EQ(stat((dir / "out.txt").c_str(), &info), 0);
    EXPECT_EQ(info.st_mode & 0777, 0666 & ~mask);
}

TEST(OutputFileTest, DroppedUncommittedLeavesTheTargetAndNoTemporaryFile) {
    TempDir dir;
    write_file(dir / "out.txt", "old");
    {
        auto file = OutputFile::create(dir / "out.txt");
        ASSERT_TRUE(file);
        ASSERT_TRUE(file->write_all("partial", 7));
        EXPECT_EQ(directory_entries(dir.path()).size(), 2u);
    }
    EXPECT_EQ(read_file(dir / "out.txt"), "old");
    EXPECT_EQ(directory_entries(dir.path()), std::vector<std::string>{"out.txt"});
}

TEST(OutputFileTest, MissingDirectoryIsReportedBeforeAnyWrite) {
    TempDir dir;
    auto file = OutputFile::create(dir / "nowhere/out.txt");
    ASSERT_FALSE(file);
    EXPECT_EQ(file.error().message, "cannot write '" + (dir / "nowhere/out.txt") +
                                        "': directory '" + (dir / "nowhere") +
                                        "' does not exist");
}

// The process dies (abort: a failed assertion, std::terminate in a thread) while writing 200
// files, more than the registry's first chunk of slots, some committed and some not: every
// temporary file goes, the committed ones and the file that was there before stay. abort
// rather than a segmentation fault because AddressSanitizer reports and exits on the latter.
TEST(OutputFileDeathTest, ACrashDeletesTheTemporaryFiles) {
    TempDir dir;
    write_file(dir / "keep.txt", "old");
    EXPECT_EXIT(
        {
            delete_temporary_files_on_crash();
            std::vector<OutputFile> open;
            for (int k = 0; k < 200; ++k) {
                std::string name = "f";   // (+ on temporaries trips GCC 12's -Wrestrict)
                name += std::to_string(k);
                name += ".txt";
                auto file = OutputFile::create(dir / name);
                if (!file || !file->write_all("x", 1)) std::exit(2);
                if (k % 50 == 0 && !file->commit()) std::exit(3);
                open.push_back(std::move(*file));
            }
            auto keep = OutputFile::create(dir / "keep.txt");
            if (!keep || !keep->write_all("new", 3)) std::exit(4);
            std::abort();
        },
        ::testing::KilledBySignal(SIGABRT), "");
    EXPECT_EQ(directory_entries(dir.path()),
              (std::vector<std::string>{"f0.txt", "f100.txt", "f150.txt", "f50.txt", "keep.txt"}));
    EXPECT_EQ(read_file(dir / "keep.txt"), "old");
}

}  // namespace
}  // namespace discreel
