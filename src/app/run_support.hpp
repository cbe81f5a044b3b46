#pragma once
// Pieces the commands share: printing errors and scene diagnostics, and checking a run's files
// before any work.
#include <cstdint>
#include <optional>
#include <ostream>
#include <string_view>
#include <vector>

#include "commands.hpp"
#include "discreel/file_identity.hpp"
#include "discreel/scene.hpp"

namespace discreel::app {

// The most resident memory this process has used so far (VmHWM), in bytes; nullopt where
// /proc does not say.
std::optional<std::int64_t> peak_resident_bytes();

// Prints "discreel: <message>" on a line of its own, with control bytes escaped (the message
// may quote file names and ids, which come from users).
void report_error(std::ostream& err, std::string_view message);

// Prints every diagnostic as `file:line:column: message`, then (unless `warnings` is false: -q)
// a loaded scene's warnings as `file:line:column: warning: message`; returns whether the scene
// loaded.
bool report_diagnostics(const scene::LoadResult& loaded, std::ostream& err, bool warnings = true);

// Refuses (prints why, returns false) a run that would write one of its inputs, or write two
// of its outputs to the same file. Paths are compared by file identity, through links.
bool check_distinct_files(const std::vector<NamedPath>& inputs,
                          const std::vector<NamedPath>& outputs, std::ostream& err);

// Makes the missing directories above every output (`-o out/a/b.mp4` makes out/a), as Manim
// and Remotion do; called once the run is known to be sound, so a refused run makes none.
// False, with the reason printed, when one cannot be made (a file in its place).
bool make_output_directories(const std::vector<NamedPath>& outputs, std::ostream& err);

// The trace and events files of `files`, named for check_distinct_files.
void add_output_paths(const OutputFiles& files, std::vector<NamedPath>& outputs);

// Flushes standard output; prints why and returns false when what was written there is lost
// (a full disk behind a redirection, a closed pipe).
bool standard_output_ok(std::ostream& out, std::ostream& err);


}  // namespace discreel::app
