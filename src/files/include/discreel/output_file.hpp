#pragma once
// A file written atomically: bytes go to a uniquely named temporary file in the target's
// directory (same file system, so the final rename is atomic), and only commit() renames it
// onto the target. Destroyed uncommitted, it deletes the temporary file, so a failed or
// abandoned write leaves the target exactly as it was; a crash deletes it too, in programs
// that call delete_temporary_files_on_crash() (temporary_files.hpp).
//
// The target is what the path names after following symbolic links: writing through a link
// replaces the file it points to and keeps the link. A target that exists and is not a regular
// file (a character device such as /dev/null, a FIFO, a socket) is written directly: such a
// file cannot be replaced by a rename, and replacing it would destroy it. A target that is a
// directory is refused by create(), before any work is done.
#include <cstddef>
#include <string>

#include "discreel/expected.hpp"

namespace discreel {

class OutputFile {
public:
    // Creates the temporary file now (or opens a special file), so a missing or read-only
    // directory, or a target that is a directory, fails before any encoding work is done.
    static Expected<OutputFile> create(const std::string& target_path);

    OutputFile(OutputFile&& other) noexcept;
    OutputFile& operator=(OutputFile&& other) noexcept;
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;
    ~OutputFile();

    // As the caller named it, for messages.
    const std::string& target_path() const { return target_path_; }
    // Where the bytes go now: the temporary file, or the special file itself.
    const std::string& temp_path() const { return temp_path_; }
    // The target is a special file, written directly: nothing to rename, nothing to roll back.
    bool direct() const { return direct_; }

    // For writers that produce the bytes themselves; libavformat opens temp_path() instead.
    Status write_all(const void* data, std::size_t size);

    // Flushes the bytes to disk and closes the file, keeping it under its temporary name: for
    // writers of many files, which cannot hold a descriptor open per file until the end.
    Status seal();

    // Seals the file if that was not done yet, and renames it onto the target.
    Status commit();

private:
    friend Status commit_together(OutputFile* const* files, std::size_t count);

    OutputFile(std::string target_path, std::string real_target, std::string temp_path, int fd,
               bool direct);
    void discard();

    std::string target_path_;
    std::string real_target_;   // target_path_ with its symbolic links followed
    std::string temp_path_;
    int fd_ = -1;          // open until seal or commit, for write_all and the final fsync
    bool direct_ = false;
    bool committed_ = false;
    std::size_t registration_ = 0;   // in the crash handler's list while not committed
};

// "cannot write '<path>': <reason>": the prefix of every error about an output file.
Error write_error(const std::string& path, const std::string& reason);

}  // namespace discreel
