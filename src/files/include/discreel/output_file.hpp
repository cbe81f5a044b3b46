#pragma once
// A file written atomically: bytes go to a uniquely named temporary file in the target's
// directory (same file system, so the final rename is atomic), and only commit() renames it
// onto the target. Destroyed uncommitted, it deletes the temporary file, so a failed or
// abandoned write leaves the target exactly as it was; a crash deletes it too, in programs
// that call delete_temporary_files_on_crash() (temporary_files.hpp).
#include <cstddef>
#include <string>

#include "discreel/expected.hpp"

namespace discreel {

class OutputFile {
public:
    // Creates the temporary file now, so a missing or read-only directory fails before any
    // encoding work is done.
    static Expected<OutputFile> create(const std::string& target_path);

    OutputFile(OutputFile&& other) noexcept;
    OutputFile& operator=(OutputFile&& other) noexcept;
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;
    ~OutputFile();

    const std::string& target_path() const { return target_path_; }
    const std::string& temp_path() const { return temp_path_; }

    // For writers that produce the bytes themselves; libavformat opens temp_path() instead.
    Status write_all(const void* data, std::size_t size);

    // Flushes the bytes to disk and closes the file, keeping it under its temporary name: for
    // writers of many files, which cannot hold a descriptor open per file until the end.
    Status seal();

    // Seals the file if that was not done yet, and renames it onto the target.
    Status commit();

private:
    OutputFile(std::string target_path, std::string temp_path, int fd);
    void discard();

    std::string target_path_;
    std::string temp_path_;
    int fd_ = -1;          // open until seal or commit, for write_all and the final fsync
    bool committed_ = false;
    std::size_t registration_ = 0;   // in the crash handler's list while not committed
};

// "cannot write '<path>': <reason>": the prefix of every error about an output file.
Error write_error(const std::string& path, const std::string& reason);

}  // namespace discreel
