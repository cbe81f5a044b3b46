#pragma once
// Where a bench's steps spent their time, by stage (physics::StepProfile, WorldDef::profile):
// milliseconds of the steady clock per simulated second for each stage, printed as a table
// and appended to bench/results/stage_profile.csv, one row per bench scene. The clock is the
// steady one, not the thread's CPU time the benches' own totals use: on a busy machine the
// stages add up to more than those totals. Asked for with DISCREEL_STAGES=1: the timers' clock
// reads cost about 0.2 ms per simulated second at 480 Hz, a tenth of the 20-box stack's time,
// which the benches' own figures should not carry.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "bench_results.hpp"
#include "discreel/physics.hpp"

namespace discreel::bench {

// Whether DISCREEL_STAGES asks for the stage profile (set, and not "0").
inline bool stages_wanted() {
    const char* value = std::getenv("DISCREEL_STAGES");
    return value != nullptr && *value != '\0' && std::string(value) != "0";
}

class StageTable {
public:
    StageTable()
        : results_("stage_profile", {"bench", "scene", "bodies", "rate", "simulated_s",
                                     "pairs_ms_per_sim_s", "contacts_ms_per_sim_s",
                                     "impacts_ms_per_sim_s", "velocities_ms_per_sim_s",
                                     "positions_ms_per_sim_s", "rest_ms_per_sim_s"}) {}

    void print_header() const {
        std::printf("\nstages, ms per simulated s (steady clock)\n%-15s %8s %9s %8s %11s %10s "
                    "%7s %7s\n",
                    "scene", "pairs", "contacts", "impacts", "velocities", "positions", "rest",
                    "total");
    }

    void add(const std::string& bench, const std::string& scene, std::size_t bodies, int rate,
             double seconds, const physics::StepProfile& p) {
        const double per = 1000.0 / seconds;
        std::printf("%-15s %8.1f %9.1f %8.1f %11.1f %10.1f %7.1f %7.1f\n", scene.c_str(),
                    p.pairs * per, p.contacts * per, p.impacts * per, p.velocities * per,
                    p.positions * per, p.rest * per, p.total() * per);
        results_.append({bench, scene, std::to_string(bodies), std::to_string(rate),
                         csv_number(seconds, 1), csv_number(p.pairs * per, 2),
                         csv_number(p.contacts * per, 2), csv_number(p.impacts * per, 2),
                         csv_number(p.velocities * per, 2), csv_number(p.positions * per, 2),
                         csv_number(p.rest * per, 2)});
    }

private:
    ResultsFile results_;
};

}  // namespace discreel::bench
