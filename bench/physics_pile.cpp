// The pile scene: N discs of radius 0.5 and density 1 on a grid with small seeded velocities,
// in a box of side 1.4 ceil(sqrt N) m, g = -9.8, friction 0.6, restitution 0.5, at 480 Hz.
// Prints CPU time per simulated second and the overlap at the end, one thread.
//     physics_bench [seconds=5] [N...]     (DISCREEL_SUBSTEPS=k overrides the world's default)
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "discreel/physics.hpp"

namespace {

using namespace discreel;

// splitmix64: seeded, identical on every platform.
double uniform(std::uint64_t& state, double lo, double hi) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return lo + (hi - lo) * static_cast<double>(z >> 11) * 0x1.0p-53;
}

physics::WorldDef pile(int n, int substeps) {
    const double r = 0.5, spacing = 1.4;
    const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
    physics::WorldDef def;
    def.gravity = {0, -9.8};
    def.rate = 480;
    def.substeps = substeps;
    physics::WallDef box;
    box.shape = physics::WallDef::Shape::box;
    box.a = {0, 0};
    box.b = {spacing * columns, spacing * columns};
    box.restitution = 0.5;
    box.friction = 0.6;
    def.walls.push_back(box);
    std::uint64_t seed = 12345;
    for (int k = 0; k < n; ++k) {
        physics::DiscDef d;
        d.position = {spacing * (0.5 + k % columns), spacing * (0.5 + k / columns)};
        d.velocity = {uniform(seed, -0.5, 0.5), uniform(seed, -0.5, 0.5)};
        d.radius = r;
        d.mass = 3.141592653589793 * r * r;
        d.restitution = 0.5;
        d.friction = 0.6;
        def.discs.push_back(d);
    }
    return def;
}

}  // namespace

int main(int argc, char** argv) {
    const double seconds = argc > 1 ? std::atof(argv[1]) : 5.0;
    std::vector<int> sizes;
    for (int k = 2; k < argc; ++k) sizes.push_back(std::atoi(argv[k]));
    if (sizes.empty()) sizes = {100, 1000, 10000};

    const char* env = std::getenv("DISCREEL_SUBSTEPS");
    const int substeps = env ? std::atoi(env) : 0;  // 0: the world's default
    std::printf("pile scene, %.1f simulated s at 480 Hz, one thread\n", seconds);
    std::printf("%8s %12s %16s %16s %10s\n", "N", "substeps", "CPU ms / sim s", "max overlap %r",
                "contacts");
    for (const int n : sizes) {
        physics::World world(pile(n, substeps));
        const auto steps = static_cast<std::int64_t>(std::llround(seconds * 480));
        const std::clock_t start = std::clock();
        for (std::int64_t k = 0; k < steps; ++k) world.step();
        const double cpu = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
        const physics::WorldStats s = world.stats();
        std::printf("%8d %12d %16.1f %16.3f %10zu\n", n, substeps > 0 ? substeps : 1, 1000.0 * cpu / seconds,
                    100.0 * s.max_overlap_ratio, s.contact_count);
    }
    return 0;
}
