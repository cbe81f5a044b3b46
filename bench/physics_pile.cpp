// The pile scene (pile_scene.hpp) through the disc solver, at 480 Hz unless set otherwise
// (below).
// Prints CPU time per simulated second (over the whole run, and second by second: the pile
// costs little while it falls and most once it has landed), one thread, and the deepest overlap
// at the end and after any step of the last simulated second.
//     physics_bench [seconds=5] [N...]
//     DISCREEL_RATE=r        steps per second (default 480)
//     DISCREEL_SUBSTEPS=k    substeps per step (default: the world's, the fewest with h <= 1/480 s)
//     DISCREEL_ITERATIONS=i  resting-contact iterations per substep (default: the world's, 3)
//     DISCREEL_SEED=s        seed of the initial velocities (default 12345)
//     DISCREEL_STAGES=1      also where each pile's time went, by stage (stage_profile.hpp)
// The same settings are physics.rate, physics.substeps and physics.iterations in a scene file.
// Each N's figures are also appended to bench/results/physics_bench.csv (bench_results.hpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "bench_results.hpp"
#include "pile_scene.hpp"
#include "stage_profile.hpp"
#include "discreel/physics.hpp"

namespace {

using namespace discreel;

}  // namespace

int main(int argc, char** argv) {
    const double seconds = argc > 1 ? std::atof(argv[1]) : 5.0;
    std::vector<int> sizes;
    for (int k = 2; k < argc; ++k) sizes.push_back(std::atoi(argv[k]));
    if (sizes.empty()) sizes = {100, 1000, 10000};

    // An unset variable keeps the default; a set one must be a whole number in range.
    const auto setting = [](const char* name, long long fallback, long long lowest) {
        const char* text = std::getenv(name);
        if (!text) return fallback;
        char* end = nullptr;
        const long long value = std::strtoll(text, &end, 10);
        if (end == text || *end != '\0' || value < lowest) {
            std::fprintf(stderr, "physics_bench: %s must be a whole number of at least %lld\n",
                         name, lowest);
            std::exit(2);
        }
        return value;
    };
    bench::PileSettings settings;
    settings.rate = static_cast<int>(setting("DISCREEL_RATE", settings.rate, 1));
    settings.substeps = static_cast<int>(setting("DISCREEL_SUBSTEPS", settings.substeps, 0));
    settings.iterations = static_cast<int>(setting("DISCREEL_ITERATIONS", settings.iterations, 1));
    settings.seed = static_cast<std::uint64_t>(
        setting("DISCREEL_SEED", static_cast<long long>(settings.seed), 0));
    if (!(seconds > 0.0)) {
        std::fprintf(stderr, "physics_bench: seconds must be positive\n");
        return 2;
    }
    std::printf("pile scene, %.1f simulated s at %d Hz, %d iterations, seed %llu, one thread\n",
                seconds, settings.rate, settings.iterations,
                static_cast<unsigned long long>(settings.seed));
    std::printf("%8s %9s %15s %15s %15s %9s   %s\n", "N", "substeps", "CPU ms / sim s",
                "overlap at end", "worst, last s", "contacts", "CPU ms in each simulated second");
    bench::ResultsFile results(
        "physics_bench",
        {"simulated_s", "discs", "rate_hz", "substeps", "iterations", "seed", "cpu_ms_per_sim_s",
         "overlap_end_pct_r", "overlap_worst_last_s_pct_r", "contacts", "cpu_ms_each_sim_s"});
    struct Profiled {
        int discs;
        physics::StepProfile stages;
    };
    std::vector<Profiled> profiled;
    for (const int n : sizes) {
        physics::WorldDef def = bench::pile(n, settings);
        def.profile = bench::stages_wanted();
        physics::World world(def);
        const int rate = settings.rate;
        const auto steps = static_cast<std::int64_t>(std::llround(seconds * rate));
        // The overlap at one instant can be a lucky one (it moves by a factor of two within a
        // quarter of a second while a pile settles), so the worst over the last simulated
        // second is shown too, looked up after every step with the clock stopped.
        const std::int64_t last_second = std::max<std::int64_t>(0, steps - rate);
        double worst_late = 0.0;   // fraction of the radius
        std::clock_t looking = 0;  // CPU time spent looking, left out of the timings
        std::vector<long long> by_second;  // CPU ms
        const std::clock_t start = std::clock();
        std::clock_t second_start = start, second_looking = 0;
        for (std::int64_t k = 0; k < steps; ++k) {
            world.step();
            if (k >= last_second) {
                const std::clock_t before = std::clock();
                worst_late = std::max(worst_late, world.stats().max_overlap_ratio);
                looking += std::clock() - before;
            }
            if ((k + 1) % rate == 0 || k + 1 == steps) {
                const std::clock_t now = std::clock();
                const std::clock_t spent = now - second_start - (looking - second_looking);
                by_second.push_back(
                    std::llround(1000.0 * static_cast<double>(spent) / CLOCKS_PER_SEC));
                second_start = now;
                second_looking = looking;
            }
        }
        const double cpu = static_cast<double>(std::clock() - start - looking) / CLOCKS_PER_SEC;
        const physics::WorldStats s = world.stats();
        std::printf("%8d %9d %15.1f %14.3f%% %14.3f%% %9zu  ", n, world.substeps(),
                    1000.0 * cpu / seconds, 100.0 * s.max_overlap_ratio, 100.0 * worst_late,
                    s.contact_count);
        std::string each;
        for (const long long ms : by_second) {
            std::printf(" %lld", ms);
            if (!each.empty()) each += ' ';
            each += std::to_string(ms);
        }
        std::printf("\n");
        std::fflush(stdout);
        results.append({bench::csv_number(seconds, 1), std::to_string(n),
                        std::to_string(settings.rate), std::to_string(world.substeps()),
                        std::to_string(settings.iterations), std::to_string(settings.seed),
                        bench::csv_number(1000.0 * cpu / seconds, 1),
                        bench::csv_number(100.0 * s.max_overlap_ratio, 3),
                        bench::csv_number(100.0 * worst_late, 3), std::to_string(s.contact_count),
                        each});
        profiled.push_back({n, world.profile()});
    }
    if (bench::stages_wanted()) {
        bench::StageTable stages;
        stages.print_header();
        for (const Profiled& p : profiled) {
            stages.add("physics_bench", "pile/" + std::to_string(p.discs),
                       static_cast<std::size_t>(p.discs), settings.rate, seconds, p.stages);
        }
    }
    if (!results.path().empty()) std::printf("appended to %s\n", results.path().c_str());
    return 0;
}
