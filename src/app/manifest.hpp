#pragma once
// `discreel batch`: a manifest is a text file of renders, one `SCENE -o OUT [options]` per line
// (what follows `discreel render`); blank lines and lines starting with # are not renders.
// A batch task renders the line its index picks: from --index, else SLURM_ARRAY_TASK_ID (a
// Slurm job array), else JOB_COMPLETION_INDEX (a Kubernetes indexed Job).
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "discreel/expected.hpp"

namespace discreel::app {

// Splits a line as a POSIX shell splits words, without expansions: blanks separate words,
// '...' keeps everything, "..." keeps everything but \" and \\, a backslash outside quotes
// keeps the next character. Fails on an unterminated quote or a final backslash.
Expected<std::vector<std::string>> split_words(std::string_view line);

struct ManifestLine {
    int number = 0;                      // 1-based line in the file
    std::vector<std::string> words;
};

// The render at 0-based `index` among the manifest's renders. Errors: "MANIFEST:LINE: ..." for
// a line that cannot be split, and a count of the renders for an index past the end.
Expected<ManifestLine> pick_render(std::string_view text, std::size_t index,
                                  const std::string& manifest);

// How many renders the manifest holds (lines that are neither blank nor comments).
std::size_t count_renders(std::string_view text);

// Renders first..last of a manifest, inclusive and 0-based.
struct IndexRange {
    std::size_t first = 0;
    std::size_t last = 0;
    friend bool operator==(const IndexRange&, const IndexRange&) = default;
};

// "I" or "A-B" (A <= B), as --index takes them.
Expected<IndexRange> parse_index_range(std::string_view text);

// The task's renders: `flag`, else the one the first of SLURM_ARRAY_TASK_ID and
// JOB_COMPLETION_INDEX that is set names (`getenv` returns them). An error names the variable
// that is not a number.
Expected<IndexRange> batch_index(std::optional<IndexRange> flag,
                                 const char* (*getenv)(const char*));

}  // namespace discreel::app
