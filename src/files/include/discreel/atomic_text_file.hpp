#pragma once
// A text file (trace, events, golden metadata) written through OutputFile: under a temporary
// name until commit() renames it onto its path; dropped without commit(), or in a crash, it
// leaves any existing file untouched. Text is buffered, so rows cost no system call each.
#include <string>
#include <string_view>

#include "discreel/expected.hpp"
#include "discreel/output_file.hpp"

namespace discreel {

class AtomicTextFile {
public:
    static Expected<AtomicTextFile> create(const std::string& path);

    // A failed write is remembered and reported by seal() or commit().
    void write(std::string_view text);
    // Writes what is buffered and seals the file, for commit_together() with other outputs.
    Status seal();
    OutputFile& file() { return file_; }
    Status commit();

private:
    explicit AtomicTextFile(OutputFile file) : file_(std::move(file)) {}
    void flush();

    OutputFile file_;
    std::string buffer_;
    Status written_;   // the first failed write, if any
};

}  // namespace discreel
