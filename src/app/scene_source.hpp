#pragma once
// Where the CLI gets its scene: a file, or the demo compiled into the binary.
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "discreel/render_plan.hpp"
#include "discreel/scene.hpp"

namespace discreel::app {

std::string_view builtin_demo_yaml();

// Loads `path`, or the built-in demo when no path is given. `clip_duration`: --duration, which
// the scene's respawns must cover (scene::load_scene_file).
scene::LoadResult load_scene_or_demo(const std::optional<std::string>& path,
                                     const scene::Limits& limits,
                                     std::optional<double> clip_duration = std::nullopt,
                                     std::span<const scene::Override> overrides = {});

// The command line's --size, --fps and --duration: the job layer's overrides.
using job::VideoOverrides;
using job::apply_overrides;

}  // namespace discreel::app
