// Every scene shipped in configs/ must be physically sound: with restitution <= 1 the total
// energy (kinetic + rotational + gravitational) may only fall, and discs may not sink into each
// other. Throws and respawns add energy on purpose (a flick sets a velocity, a grab moves a disc
// by force of will, a respawn scatters a new set), so the energy test leaves them out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <vector>

#include "discreel/job.hpp"
#include "discreel/physics.hpp"
#include "discreel/scene.hpp"

namespace discreel::job {
namespace {

std::vector<std::filesystem::path> shipped_scenes() {
    std::vector<std::filesystem::path> scenes;
    for (const auto& entry :
         std::filesystem::directory_iterator(std::filesystem::path(DISCREEL_SOURCE_DIR) / "configs")) {
        if (entry.path().extension() == ".yaml") scenes.push_back(entry.path());
    }
    std::sort(scenes.begin(), scenes.end());
    return scenes;
}

// Runs a shipped scene frame by frame (with its throws, or without them, its respawns and its
// kinematic bodies' motion: each held where it starts, as a static body), handing the world to
// `look` at frame 0 and after every frame.
void run_frames(const std::filesystem::path& path, bool with_throws,
                const std::function<void(int frame, const physics::World& world)>& look) {
    scene::LoadResult loaded = scene::load_scene_file(path);
    ASSERT_TRUE(loaded.ok()) << loaded.diagnostics.front().to_string();
    scene::Scene& s = loaded.scene;
    if (!with_throws) {
        s.throws.clear();
        s.respawns.clear();
        for (scene::Body& b : s.bodies) {
            if (!b.kinematic) continue;
            b.kinematic.reset();
            b.is_static = true;
        }
    }
    job::Playback playback(s);
    const Status played = playback.play(
        {.last = -1, .drawn = {}, .look = false, .should_stop = {}, .until = {}},
        [&](const job::ShownFrame& shown) -> Status {
            look(shown.frame, playback.world());
            return {};
        });
    ASSERT_TRUE(played) << played.error().message;
}

TEST(ConfigsEnergyTest, EnergyNeverRisesBetweenFramesWithoutThrows) {
    const auto scenes = shipped_scenes();
    ASSERT_FALSE(scenes.empty());
    for (const auto& path : scenes) {
        SCOPED_TRACE(path.filename().string());
        double start = 0, previous = 0, worst_rise = 0;
        int worst_frame = 0;
        run_frames(path, false, [&](int frame, const physics::World& world) {
            const double energy = world.energy();
            if (frame == 0) start = energy;
            if (frame > 0 && energy - previous > worst_rise) {
                worst_rise = energy - previous;
                worst_frame = frame;
            }
            previous = energy;
        });
        // 0.1 % of the start value, the bound of every energy test (docs/physics.md); a scene
        // starting at rest at the origin's height has no scale of its own, so 1 mJ is the floor.
        const double allowed_rise = std::max(1e-3 * std::abs(start), 1e-3);
        EXPECT_LE(worst_rise, allowed_rise)
            << "energy rose by " << worst_rise << " J at frame " << worst_frame
            << " (start " << start << " J)";
    }
}

// Nor may discs sink into each other for good: the deepest overlap of each frame (any pair,
// relative to its smaller disc) stays under 2 % of the radius in the median frame and under 20 %
// in every frame, throws included. A transient of a few per cent is a fraction of a pixel at the
// scenes' scale; a pile that settles 2 % deep, or a frame a fifth of a radius deep, is not.
// Galton's beads in their jammed hopper come closest (docs/physics.md gives the figures).
TEST(ConfigsOverlapTest, DiscsDoNotSinkIntoEachOtherInAnyFrame) {
    const auto scenes = shipped_scenes();
    ASSERT_FALSE(scenes.empty());
    for (const auto& path : scenes) {
        SCOPED_TRACE(path.filename().string());
        std::vector<double> deepest;  // per frame after the first
        run_frames(path, true, [&](int frame, const physics::World& world) {
            if (frame > 0) deepest.push_back(world.stats().max_overlap_ratio);
        });
        ASSERT_FALSE(deepest.empty());
        const auto worst = std::max_element(deepest.begin(), deepest.end());
        std::vector<double> sorted = deepest;
        const auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
        std::nth_element(sorted.begin(), middle, sorted.end());
        EXPECT_LE(*middle, 0.02) << "median frame";
        EXPECT_LE(*worst, 0.20) << "at frame " << (worst - deepest.begin()) + 1;
    }
}

}  // namespace
}  // namespace discreel::job
