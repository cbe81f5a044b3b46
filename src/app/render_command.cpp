#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <memory>

#include "build_world.hpp"
#include "commands.hpp"
#include "discreel/encode.hpp"
#include "discreel/render.hpp"
#include "exit_codes.hpp"
#include "frame_scene.hpp"
#include "run_support.hpp"
#include "stepper.hpp"

namespace discreel::app {
namespace {

struct FrameRange {
    int first = 0;
    int last = 0;   // inclusive
};

// A .png output is one still; everything else is the whole clip.
std::optional<FrameRange> pick_frames(const RenderOptions& o, const scene::Scene& scene,
                                      bool still, std::ostream& err) {
    const int count = scene.video.frame_count();
    if (!still) {
        if (o.frame || o.at) {
            err << "discreel: --frame and --at select a still; use them with a .png output\n";
            return std::nullopt;
        }
        return FrameRange{0, count - 1};
    }
    if (o.frame && o.at) {
        err << "discreel: give either --frame or --at, not both\n";
        return std::nullopt;
    }
    int frame = 0;
    if (o.frame) frame = *o.frame;
    if (o.at) {
        if (!std::isfinite(*o.at)) {
            err << "discreel: --at must be a number of seconds\n";
            return std::nullopt;
        }
        frame = static_cast<int>(std::lround(*o.at * scene.video.fps));
    }
    if (frame < 0 || frame >= count) {
        err << "discreel: frame " << frame << " is outside the clip, which has " << count
            << " frames (0.." << count - 1 << ")\n";
        return std::nullopt;
    }
    return FrameRange{frame, frame};
}

}  // namespace

int run_render(const RenderOptions& o, std::ostream& out, std::ostream& err) {
    const auto started = std::chrono::steady_clock::now();
    scene::LoadResult loaded = load_scene_or_demo(o.scene_path);
    if (!report_diagnostics(loaded, err)) return exit_bad_input;
    scene::Scene& scene = loaded.scene;
    if (auto problem = apply_overrides(scene, o.video)) {
        err << "discreel: " << *problem << '\n';
        return exit_bad_input;
    }

    const std::string extension = std::filesystem::path(o.output).extension().string();
    if (extension != ".mp4" && extension != ".png") {
        err << "discreel: cannot tell the output format from '" << o.output
            << "': use a name ending in .mp4 (H.264 video) or .png (one frame)\n";
        return exit_bad_input;
    }
    const bool still = extension == ".png";
    const std::optional<FrameRange> frames = pick_frames(o, scene, still, err);
    if (!frames) return exit_bad_input;

    auto outputs = SideOutputs::open(o.files, scene, err);
    if (!outputs) return exit_runtime_failure;

    auto renderer = render::Renderer::create({.width = scene.video.width,
                                              .height = scene.video.height});
    if (!renderer) {
        err << "discreel: " << renderer.error().message << '\n';
        return exit_runtime_failure;
    }
    auto sink = encode::open_sink({.path = o.output,
                                   .width = scene.video.width,
                                   .height = scene.video.height,
                                   .fps = scene.video.fps,
                                   .crf = o.crf,
                                   .preset = o.preset});
    if (!sink) {
        err << "discreel: " << sink.error().message << '\n';
        return exit_runtime_failure;
    }

    const Timeline timeline{scene.video.fps, scene.physics.rate, scene.video.frame_count()};
    physics::World world(build_world(scene));
    FrameStepper stepper(world, timeline);
    FrameSceneBuilder frame_builder(scene);
    for (int frame = 0; frame <= frames->last; ++frame) {
        stepper.advance_to(frame);
        outputs->record(frame, timeline.time_of_frame(frame), world.discs(),
                        stepper.take_events());
        if (frame < frames->first) continue;
        auto image = renderer->draw(frame_builder.build(world.discs()));
        if (!image) {
            err << "discreel: " << image.error().message << '\n';
            return exit_runtime_failure;
        }
        if (Status written = (*sink)->write(*image); !written) {
            err << "discreel: " << written.error().message << '\n';
            return exit_runtime_failure;
        }
    }
    if (Status done = (*sink)->finish(); !done) {
        err << "discreel: " << done.error().message << '\n';
        return exit_runtime_failure;
    }
    if (Status done = outputs->commit(); !done) {
        err << "discreel: " << done.error().message << '\n';
        return exit_runtime_failure;
    }

    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const int written = frames->last - frames->first + 1;
    out << "wrote " << o.output << ": " << written << (written == 1 ? " frame" : " frames")
        << ", " << scene.video.width << 'x' << scene.video.height;
    if (!still) {
        out << ", " << std::fixed << std::setprecision(2) << scene.video.duration << " s at "
            << scene.video.fps << " fps";
    } else {
        out << ", frame " << frames->first;
    }
    out << std::fixed << std::setprecision(1) << " (" << seconds << " s, "
        << (seconds > 0 ? written / seconds : 0.0) << " frames/s)\n";
    return exit_ok;
}

}  // namespace discreel::app
