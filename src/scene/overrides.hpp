#pragma once
// `--set KEY=VALUE`: values put into a scene's YAML before it is read, so that they are
// checked exactly as the file's own are and their problems name the option.
#include <span>

#include <yaml-cpp/yaml.h>

#include "diagnostics.hpp"
#include "discreel/scene.hpp"

namespace discreel::scene::detail {

// Puts each override into `document` (a mapping), in order: a later one wins. Each is parsed
// on lines past the end of the file (`first_line`, 1-based, and on), which `diagnostics`
// reports under the override's label. Paths that lead nowhere (an item past a list's end, a
// key under a number) are reported there too; missing mappings are created, and the keys put
// into them are checked by the loader like any other (unknown keys with a suggestion).
void apply_overrides(YAML::Node& document, std::span<const Override> overrides,
                     int first_line, Diagnostics& diagnostics);

}  // namespace discreel::scene::detail
