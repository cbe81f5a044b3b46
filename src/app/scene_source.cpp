#include "scene_source.hpp"

#include "discreel_configs.hpp"
#include "discreel/printable.hpp"

namespace discreel::app {

std::string_view builtin_demo_yaml() { return discreel_configs::demo_yaml; }

scene::LoadResult load_scene_or_demo(const std::optional<std::string>& path,
                                     const scene::Limits& limits,
                                     std::optional<double> clip_duration) {
    if (path) return scene::load_scene_file(*path, limits, clip_duration);
    scene::LoadResult result =
        scene::load_scene_text(builtin_demo_yaml(), "<built-in demo>", limits, clip_duration);
    result.scene.name = "demo";
    return result;
}

std::optional<std::string> apply_overrides(scene::Scene& scene, const VideoOverrides& o,
                                           const scene::Limits& limits) {
    if (o.width) {
        if (*o.width < 16 || *o.width > 7680 || *o.height < 16 || *o.height > 4320) {
            return "--size must be between 16x16 and 7680x4320";
        }
        if (*o.width % 2 != 0 || *o.height % 2 != 0) {
            return "--size must have an even width and height (H.264 in yuv420p halves "
                   "the colour resolution in both directions)";
        }
        scene.video.width = *o.width;
        scene.video.height = *o.height;
    }
    if (o.fps) {
        if (*o.fps < 1 || *o.fps > 240) return "--fps must be between 1 and 240";
        scene.video.fps = *o.fps;
    }
    if (o.duration) {
        if (!(*o.duration > 0 && *o.duration <= limits.duration)) {
            std::string limit;
            append_number(limit, limits.duration);
            return "--duration must be greater than 0 and at most " + limit +
                   " seconds (raise the limit with --max-duration)";
        }
        scene.video.duration = *o.duration;
    }
    // A longer clip or another frame rate is more work than the file asked for.
    return scene::check_work(scene, limits);
}

}  // namespace discreel::app
