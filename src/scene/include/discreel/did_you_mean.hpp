#pragma once
// Suggestions for misspelt names: "did you mean 'color'?" for 'colour' in a scene, "did
// you mean '--size'?" for '--sise' on the command line.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace discreel {

// Optimal-string-alignment distance (Levenshtein plus adjacent transpositions), comparing
// letters case-insensitively: "Radius" is one step from nothing, "raduis" one from "radius".
std::size_t edit_distance(std::string_view a, std::string_view b);

// The candidate closest to `word`, if it is close enough to be a plausible typo: at most two
// edits, and fewer edits than half the candidate's length (so "x" does not suggest "at").
// Ties go to the earliest candidate, so the answer does not depend on anything but the list.
std::optional<std::string> closest_match(std::string_view word,
                                         std::span<const std::string_view> candidates);
std::optional<std::string> closest_match(std::string_view word,
                                         std::span<const std::string> candidates);

}  // namespace discreel
