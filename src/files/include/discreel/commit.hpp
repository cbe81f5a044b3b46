#pragma once
// The outputs of one run (a video with its trace and events, a PNG sequence, a set of goldens)
// become visible together or not at all. Every file is sealed first (fsync), then each existing
// target gets a hard-linked backup, then the temporary files are renamed onto their targets;
// a rename that fails puts every target already replaced back as it was. Catchable signals
// that arrive meanwhile are held until the commit is over (commit_in_progress()), so Ctrl-C
// never leaves half a set. Only a crash or SIGKILL in the middle of the renames can leave a
// mix, and files written directly (special files, OutputFile::direct()) cannot be rolled back.
#include <cstddef>
#include <span>

#include "discreel/expected.hpp"
#include "discreel/output_file.hpp"

namespace discreel {

Status commit_together(OutputFile* const* files, std::size_t count);
inline Status commit_together(std::span<OutputFile* const> files) {
    return commit_together(files.data(), files.size());
}

// True while a commit_together() is renaming: a signal handler that would end the process
// records the signal instead and lets the commit finish. Async-signal-safe.
bool commit_in_progress();

}  // namespace discreel
