// libFuzzer target: arbitrary bytes through the scene loader and validator.
// Whatever the input, load_scene_text must return (no crash, no hang, no unbounded memory,
// no sanitizer report) and its result must be self-consistent; a violation aborts so that
// libFuzzer records the input. Built only by DISCREEL_FUZZ=ON (see tests/fuzz/run.sh).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "discreel/scene.hpp"

namespace {

void require(bool holds) {
    if (!holds) std::abort();
}

void check_scene(const discreel::scene::Scene& scene) {
    using namespace discreel::scene;
    require(scene.bodies.size() <= Limits{}.bodies);
    require(scene.walls.size() <= max_walls);
    require(scene.throws.size() <= max_throws);
    require(scene.golden_frames.size() <= max_golden_frames);
    require(scene.video.frame_count() > 0);
    for (const Body& disc : scene.bodies) {
        require(disc.radius > 0.0 && disc.mass > 0.0 && std::isfinite(disc.inertia));
        if (disc.shape) require(!disc.shape->vertices.empty() && disc.shape->vertices.size() <= 8);
    }
    for (const Respawn& r : scene.respawns) require(r.first + r.bodies.size() <= scene.bodies.size());
    // Physics applies respawns in list order.
    require(std::is_sorted(scene.respawns.begin(), scene.respawns.end(),
                           [](const Respawn& a, const Respawn& b) { return a.at < b.at; }));
    for (const Throw& t : scene.throws) {
        require(t.body < scene.bodies.size());
        require(t.velocity.has_value() != !t.path.empty());
    }
    for (const int frame : scene.golden_frames)
        require(frame >= 0 && frame < scene.video.frame_count());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const auto result = discreel::scene::load_scene_text(text, "fuzz.yaml");
    if (result.ok()) {
        check_scene(result.scene);
    } else {
        for (const auto& diagnostic : result.diagnostics) {
            require(!diagnostic.message.empty());
            require(diagnostic.line >= 0 && diagnostic.column >= 0);
        }
    }
    return 0;
}
