// Determinism.*GivesTheSameBitsEveryRun without GoogleTest, for builds that have none
// (DISCREEL_PHYSICS_ONLY: the `arch` tests build it for aarch64 and without the AVX2 clones).
// Runs the busy scene (the disc solver), the mixed scene (the manifold solver), the
// heavy-light scene (the disc solver's direct islands) and the resting scene (the manifold
// solver's kept contacts) and the joint scene twice each and prints their hashes;
// exits 0 only if every run gives the pinned one.
#include <cinttypes>
#include <cstdint>
#include <cstdio>

#include "busy_scene.hpp"

namespace {

constexpr const char* target =
#if defined(__x86_64__)
    "x86-64";
#elif defined(__aarch64__)
    "aarch64";
#else
    "another target";
#endif

bool check(const char* name, std::uint64_t (*run)(), std::uint64_t pinned) {
    const std::uint64_t first = run();
    const std::uint64_t second = run();
    std::printf("%s on %s: %" PRIu64 ", pinned: %" PRIu64 "\n", name, target, first, pinned);
    if (second != first) {
        std::printf("FAILED: a second run gave %" PRIu64 "\n", second);
        return false;
    }
    if (first != pinned) {
        std::printf("FAILED: not the pinned hash (tests/physics/busy_scene.hpp)\n");
        return false;
    }
    return true;
}

}  // namespace

int main() {
    using namespace discreel::physics::testing;
    const bool busy = check("busy scene", run_busy_scene, busy_scene_hash);
    const bool mixed = check("mixed scene", run_mixed_scene, mixed_scene_hash);
    const bool heavy_light =
        check("heavy-light scene", run_heavy_light_scene, heavy_light_scene_hash);
    const bool resting = check("resting scene", run_resting_scene, resting_scene_hash);
    const bool joints = check("joint scene", run_joint_scene, joint_scene_hash);
    if (!busy || !mixed || !heavy_light || !resting || !joints) return 1;
    std::printf("OK\n");
    return 0;
}
