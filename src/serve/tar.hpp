#pragma once
// A directory's files as one ustar archive (POSIX tar), so a job's masks are one output: the
// files in name order under `prefix/`, every header's owner, mode and time fixed, so the same
// files give the same bytes.
#include <filesystem>
#include <string>

#include "discreel/expected.hpp"

namespace discreel::serve {

// Writes the regular files directly in `dir` to `archive` as `prefix/<name>`.
Status write_tar(const std::filesystem::path& dir, const std::string& prefix,
                 const std::filesystem::path& archive);

}  // namespace discreel::serve
