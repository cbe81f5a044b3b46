#include <algorithm>
#include <chrono>
#include <iomanip>

#include "commands.hpp"
#include "discreel/job.hpp"
#include "discreel/printable.hpp"
#include "exit_codes.hpp"
#include "run_support.hpp"
#include "signals.hpp"

namespace discreel::app {
namespace {

std::string count_of(std::size_t n, const char* singular, const char* plural) {
    return std::to_string(n) + ' ' + (n == 1 ? singular : plural);
}

}  // namespace

int run_simulate(const SimulateOptions& o, std::ostream& out, std::ostream& err) {
    const auto started = std::chrono::steady_clock::now();
    scene::LoadResult loaded = scene::load_scene_file(o.scene_path, o.limits, o.duration, o.overrides);
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
    if (!make_output_directories(output_paths, err)) return exit_runtime_failure;
    const std::string name = scene.name;
    const std::size_t discs = scene.bodies.size(), walls = scene.walls.size(),
                      throws = scene.throws.size();
    const int fps = scene.video.fps, rate = scene.physics.rate;
    const bool shaped = std::any_of(scene.bodies.begin(), scene.bodies.end(),
                                    [](const scene::Body& d) { return d.shape.has_value(); });
    job::SimulateDef def;
    def.scene = std::move(scene);
    def.trace = o.files.trace;
    def.events = o.files.events;
    def.joints = o.files.joints;
    def.shapes = o.files.shapes;
    def.should_stop = [] { return stop_signal() != 0; };
    def.on_warning = [&err](const std::string& message) {
        err << "discreel: warning: " << message << '\n';
    };
    const auto run = job::simulate(def);
    if (stop_signal() != 0) {
        err << "discreel: interrupted; nothing was written\n";
        return exit_interrupted_base + stop_signal();
    }
    if (!run) {
        report_error(err, run.error().message);
        return exit_runtime_failure;
    }

    out << std::setprecision(6);
    out << "scene     " << printable(name) << ": "
        << (shaped ? count_of(discs, "body", "bodies") : count_of(discs, "disc", "discs")) << ", "
        << count_of(walls, "wall", "walls") << ", " << count_of(throws, "throw", "throws") << '\n';
    out << "frames    " << run->frames << " at " << fps << " fps (" << run->steps
        << " physics steps at " << rate << " Hz, t = " << run->t << " s)\n";
    const int substeps = run->substeps;
    out << "solver    " << (run->manifold_solver ? "manifold, " : "")
        << count_of(static_cast<std::size_t>(substeps), "substep", "substeps")
        << " per step (1/" << rate * substeps << " s" << (substeps > 1 ? " each" : "") << "), "
        << count_of(static_cast<std::size_t>(run->iterations), "iteration", "iterations")
        << " per substep\n";
    out << "contacts  " << run->contacts << " new contacts\n";
    out << "overlap   " << run->deepest.max_overlap << " m at most, "
        << 100 * run->deepest.max_overlap_ratio << " % of the smaller radius\n";
    out << "energy    " << run->energy_start << " J at start, " << run->energy_end
        << " J at end\n";
    // Loading the scene included: what the user waited for.
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    out << std::fixed << std::setprecision(3) << "time      " << seconds << " s wall clock\n";
    return exit_ok;
}

}  // namespace discreel::app
