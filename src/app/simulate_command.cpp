#include <chrono>
#include <iomanip>

#include "build_world.hpp"
#include "discreel/commit.hpp"
#include "discreel/printable.hpp"
#include "signals.hpp"
#include "commands.hpp"
#include "exit_codes.hpp"
#include "run_support.hpp"
#include "stepper.hpp"

namespace discreel::app {
namespace {

std::string count_of(std::size_t n, const char* singular, const char* plural) {
    return std::to_string(n) + ' ' + (n == 1 ? singular : plural);
}

}  // namespace

int run_simulate(const SimulateOptions& o, std::ostream& out, std::ostream& err) {
    const auto started = std::chrono::steady_clock::now();
    scene::LoadResult loaded = scene::load_scene_file(o.scene_path, o.limits);
    if (!report_diagnostics(loaded, err)) return exit_bad_input;
    scene::Scene& scene = loaded.scene;
    VideoOverrides overrides;
    overrides.duration = o.duration;
    if (auto problem = apply_overrides(scene, overrides, o.limits)) {
        report_error(err, *problem);
        return exit_bad_input;
    }
    std::vector<NamedPath> output_paths;
    add_output_paths(o.files, output_paths);
    if (!check_distinct_files({{"the scene", o.scene_path}}, output_paths, err))
        return exit_bad_input;
    auto outputs = SideOutputs::open(o.files, scene, err);
    if (!outputs) return exit_runtime_failure;

    const Timeline timeline{scene.video.fps, scene.physics.rate, scene.video.frame_count()};
    physics::World world(build_world(scene));
    FrameStepper stepper(world, timeline, scene);
    const double energy_start = world.energy();
    std::size_t contacts = 0;
    physics::WorldStats deepest;   // the frame with the deepest overlap
    for (int frame = 0; frame < timeline.frame_count; ++frame) {
        if (stop_signal() != 0) {
            err << "discreel: interrupted; nothing was written\n";
            return exit_interrupted_base + stop_signal();
        }
        if (Status stepped = stepper.advance_to(frame); !stepped) {
            report_error(err, stepped.error().message);
            return exit_runtime_failure;
        }
        const std::vector<physics::ContactEvent> events = stepper.take_events();
        contacts += events.size();
        outputs->record(frame, timeline.time_of_frame(frame), world.discs(), events);
        const physics::WorldStats stats = world.stats();
        if (stats.max_overlap > deepest.max_overlap) deepest = stats;
    }
    Status done = outputs->seal();
    if (done) done = commit_together(outputs->files());
    if (!done) {
        report_error(err, done.error().message);
        return exit_runtime_failure;
    }
    const double energy_end = world.energy();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

    out << std::setprecision(6);
    out << "scene     " << printable(scene.name) << ": " << count_of(scene.discs.size(), "disc", "discs")
        << ", " << count_of(scene.walls.size(), "wall", "walls") << ", "
        << count_of(scene.throws.size(), "throw", "throws") << '\n';
    out << "frames    " << timeline.frame_count << " at " << scene.video.fps << " fps ("
        << world.step_count() << " physics steps at " << scene.physics.rate << " Hz, t = "
        << world.time() << " s)\n";
    const int substeps = world.substeps();
    out << "solver    " << count_of(static_cast<std::size_t>(substeps), "substep", "substeps")
        << " per step (1/" << scene.physics.rate * substeps << " s" << (substeps > 1 ? " each" : "")
        << "), "
        << count_of(static_cast<std::size_t>(scene.physics.iterations), "iteration", "iterations")
        << " per substep\n";
    out << "contacts  " << contacts << " new contacts\n";
    out << "overlap   " << deepest.max_overlap << " m at most, " << 100 * deepest.max_overlap_ratio
        << " % of the smaller radius\n";
    out << "energy    " << energy_start << " J at start, " << energy_end << " J at end\n";
    out << std::fixed << std::setprecision(3) << "time      " << seconds << " s wall clock\n";
    return exit_ok;
}

}  // namespace discreel::app
