#include <algorithm>
#include <iostream>
#include <string>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "run_support.hpp"

#include "discreel/printable.hpp"

namespace discreel::app {

int run_validate(const ValidateOptions& o, std::ostream& out, std::ostream& err) {
    bool all_ok = true;
    for (const std::string& path : o.scene_paths) {
        const auto loaded = scene::load_scene_file(path, o.limits, std::nullopt, o.overrides);
        if (report_diagnostics(loaded, err)) {
            const auto& bodies = loaded.scene.bodies;
            const bool shaped = std::any_of(bodies.begin(), bodies.end(),
                                            [](const scene::Body& d) { return d.shape.has_value(); });
            // A scene with warnings is ok: they are printed above, and counted here.
            const std::size_t warned = loaded.warnings.size();
            const std::string warnings =
                warned == 0 ? ""
                            : ", " + std::to_string(warned) + (warned == 1 ? " warning" : " warnings");
            out << printable(path) << ": ok (" << bodies.size() << (shaped ? " bodies, " : " discs, ")
                << loaded.scene.video.frame_count() << " frames" << warnings << ")\n";
        } else {
            all_ok = false;
        }
    }
    if (!standard_output_ok(out, err)) return exit_runtime_failure;
    return all_ok ? exit_ok : exit_bad_input;
}

}  // namespace discreel::app
