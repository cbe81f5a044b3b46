#pragma once
// Where the CLI gets its scene: a file, or the demo compiled into the binary.
#include <optional>
#include <string>
#include <string_view>

#include "discreel/scene.hpp"

namespace discreel::app {

std::string_view builtin_demo_yaml();

// Loads `path`, or the built-in demo when no path is given. `clip_duration`: --duration, which
// the scene's respawns must cover (scene::load_scene_file).
scene::LoadResult load_scene_or_demo(const std::optional<std::string>& path,
                                     const scene::Limits& limits,
                                     std::optional<double> clip_duration = std::nullopt);

// Overrides from the command line, applied after loading. Returns the problems, in words.
struct VideoOverrides {
    std::optional<int> width, height;   // pixels
    std::optional<int> fps;
    std::optional<double> duration;     // seconds
};
// `limits` bound --duration as they bound video.duration in the file.
std::optional<std::string> apply_overrides(scene::Scene& scene, const VideoOverrides& o,
                                           const scene::Limits& limits);

}  // namespace discreel::app
