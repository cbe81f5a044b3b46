// job::simulate: the physics of a whole clip, without drawing, and its trace and events.
#include <algorithm>
#include <chrono>

#include "discreel/commit.hpp"
#include "discreel/job.hpp"
#include "warnings_once.hpp"
#include "side_outputs.hpp"

namespace discreel::job {

Expected<SimulateSummary> simulate(const SimulateDef& def) {
    const auto started = std::chrono::steady_clock::now();
    const scene::Scene& scene = def.scene;
    GroundTruthPaths truth;
    truth.shapes = def.shapes;
    auto outputs = SideOutputs::open(def.trace, def.events, def.joints, scene, truth);
    if (!outputs) return outputs.error();

    Playback playback(scene);
    WarningsOnce warnings(def.on_warning);
    SimulateSummary summary;
    summary.frames = playback.frame_count();
    summary.energy_start = playback.world().energy();
    const Status played = playback.play(
        {.last = -1, .drawn = {}, .look = false, .should_stop = def.should_stop,
         .until = {}},
        [&](const ShownFrame& shown) -> Status {
            warnings.say(playback.take_warnings());
            const std::vector<physics::ContactEvent> events = playback.take_events();
            summary.contacts += static_cast<std::size_t>(
                std::count_if(events.begin(), events.end(), [](const physics::ContactEvent& e) {
                    return e.kind == physics::ContactEvent::Kind::contact;
                }));
            outputs->record(shown.frame, shown.t, playback.world(), events);
            const physics::WorldStats stats = playback.world().stats();
            if (stats.max_overlap > summary.deepest.max_overlap) summary.deepest = stats;
            return {};
        });
    if (!played) return played.error();
    if (def.should_stop && def.should_stop()) return Error{cancelled_message};
    Status done = outputs->seal();
    if (done) done = commit_together(outputs->files());
    if (!done) return done.error();
    const physics::World& world = playback.world();
    summary.energy_end = world.energy();
    summary.steps = world.step_count();
    summary.t = world.time();
    summary.substeps = world.substeps();
    summary.iterations = world.iterations();
    summary.manifold_solver = world.manifold_solver();
    summary.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return summary;
}

}  // namespace discreel::job
