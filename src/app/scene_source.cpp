#include "scene_source.hpp"

#include "discreel_configs.hpp"

namespace discreel::app {

std::string_view builtin_demo_yaml() { return discreel_configs::demo_yaml; }

scene::LoadResult load_scene_or_demo(const std::optional<std::string>& path,
                                     const scene::Limits& limits,
                                     std::optional<double> clip_duration,
                                     std::span<const scene::Override> overrides) {
    if (path) return scene::load_scene_file(*path, limits, clip_duration, overrides);
    scene::LoadResult result = scene::load_scene_text(builtin_demo_yaml(), "<built-in demo>",
                                                      limits, clip_duration, overrides);
    result.scene.name = "demo";
    return result;
}

}  // namespace discreel::app
