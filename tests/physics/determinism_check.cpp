// Determinism.BusySceneGivesTheSameBitsEveryRun without GoogleTest, for builds that have none
// (DISCREEL_PHYSICS_ONLY: the `arch` tests build it for aarch64 and without the AVX2 clones).
// Runs the busy scene twice and prints its hash; exits 0 only if both runs give the pinned one.
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

}  // namespace

int main() {
    using namespace discreel::physics::testing;
    const std::uint64_t first = run_busy_scene();
    const std::uint64_t second = run_busy_scene();
    std::printf("busy scene on %s: %" PRIu64 ", pinned: %" PRIu64 "\n", target, first,
                busy_scene_hash);
    if (second != first) {
        std::printf("FAILED: a second run gave %" PRIu64 "\n", second);
        return 1;
    }
    if (first != busy_scene_hash) {
        std::printf("FAILED: not the pinned hash (tests/physics/busy_scene.hpp)\n");
        return 1;
    }
    std::printf("OK\n");
    return 0;
}
