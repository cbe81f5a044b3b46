#include <sys/prctl.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <memory>
#include <sstream>

#include "build_world.hpp"
#include "commands.hpp"
#include "discreel/commit.hpp"
#include "discreel/encode.hpp"
#include "discreel/printable.hpp"
#include "discreel/render.hpp"
#include "exit_codes.hpp"
#include "frame_scene.hpp"
#include "run_support.hpp"
#include "pipeline.hpp"
#include "progress.hpp"
#include "signals.hpp"
#include "stepper.hpp"
#include "trace.hpp"

namespace discreel::app {
namespace {

struct FrameRange {
    int first = 0;
    int last = 0;   // inclusive
};

// A .png output is one still; everything else (a numbered .png sequence included) is the
// whole clip.
std::optional<FrameRange> pick_frames(const RenderOptions& o, const scene::Scene& scene,
                                      const encode::OutputDescription& output,
                                      std::ostream& err) {
    const int count = scene.video.frame_count();
    if (!output.one_frame) {
        if (o.frame || o.at) {
            err << (output.format == "png sequence"
                        ? "discreel: --frame and --at select a still; a numbered .png name "
                          "writes every frame\n"
                        : "discreel: --frame and --at select a still; use them with a .png "
                          "output\n");
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
        // Checked as a number before it becomes a frame index, which it could overflow. The
        // clip's end (t = duration) shows its last frame.
        const double duration = scene.video.duration;
        if (!std::isfinite(*o.at) || *o.at < 0 || *o.at > duration) {
            std::string text = "--at must be a time in the clip, 0 to ";
            append_number(text, duration);
            report_error(err, text + " seconds");
            return std::nullopt;
        }
        frame = std::min(count - 1, static_cast<int>(std::lround(*o.at * scene.video.fps)));
    }
    if (frame < 0 || frame >= count) {
        err << "discreel: frame " << frame << " is outside the clip, which has " << count
            << " frames (0.." << count - 1 << ")\n";
        return std::nullopt;
    }
    return FrameRange{frame, frame};
}

// The colours frames are drawn in; a GIF palette starts with them so they come out exact.
std::vector<encode::Rgb> scene_colours(const scene::Scene& scene) {
    std::vector<encode::Rgb> colours;
    const auto add = [&](const scene::Color& c) { colours.push_back({c.r, c.g, c.b}); };
    add(scene.video.background);
    for (const auto& wall : scene.walls) add(wall.color);
    for (const auto& disc : scene.discs) add(disc.color);
    return colours;
}

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string describe_encoder(const encode::SinkDef& def) {
    std::ostringstream text;
    text << "codec " << (def.codec.empty() ? "default" : def.codec) << ", crf ";
    if (def.crf) {
        text << *def.crf;
    } else {
        text << "default";
    }
    text << ", preset " << (def.preset.empty() ? "veryfast" : def.preset) << ", "
         << def.threads << " encoder threads";
    return text.str();
}

// --verbose: where the time went and how much memory the process needed at most.
void report_details(const PipelineResult& run, int frames, std::ostream& err) {
    const auto per_frame = [&](double seconds) {
        std::ostringstream text;
        text << std::fixed << std::setprecision(2) << seconds << " s ("
             << (frames > 0 ? 1000.0 * seconds / frames : 0.0) << " ms/frame)";
        return text.str();
    };
    err << "discreel: renderer: " << run.renderer_info << '\n';
    err << "discreel: busy: simulate " << per_frame(run.busy.simulate) << ", render "
        << per_frame(run.busy.render) << ", encode " << per_frame(run.busy.encode) << '\n';
    if (const auto peak = peak_resident_bytes()) {
        err << "discreel: peak memory: " << std::fixed << std::setprecision(1)
            << static_cast<double>(*peak) / (1024.0 * 1024.0) << " MiB (VmHWM)\n";
    }
}

// Up to 720p, six slots (3.5 MiB each at 720p) let the simulate and render stages, which
// yield to the encoder (PipelineDef::encoder_first), work several frames ahead in the cycles
// x264 leaves idle. Above 720p a slot is 8 MiB or more and two keep a 1080p render under
// 300 MB (docs/performance.md); the encoder still has the next frame ready, because drawing
// and simulating a frame take a fraction of the time it needs.
int slots_for(int width, int height) {
    return static_cast<long>(width) * height > 1280L * 720L ? 2 : 6;
}

}  // namespace

int run_render(const RenderOptions& o, std::ostream& out, std::ostream& err) {
    const auto started = Clock::now();
    // The encoder's threads keep most of the cores busy; llvmpipe's rasterizer threads would
    // compete with them and cost more CPU than they save, so the render stage draws on its own
    // thread (docs/performance.md). Set here, before any thread starts; LP_NUM_THREADS in the
    // environment still wins.
    render::set_rasterizer_threads(0);
    // libx264 asks for transparent huge pages on its frame buffers, which rounds each one up to
    // whole 2 MiB pages of resident memory: 11-13 MiB at 1080p, at no measurable cost in speed.
    // Best effort (a kernel without the setting just keeps the default).
    prctl(PR_SET_THP_DISABLE, 1, 0, 0, 0);
    scene::LoadResult loaded = load_scene_or_demo(o.scene_path, o.limits);
    if (!report_diagnostics(loaded, err)) return exit_bad_input;
    scene::Scene& scene = loaded.scene;
    if (auto problem = apply_overrides(scene, o.video, o.limits)) {
        report_error(err, *problem);
        return exit_bad_input;
    }

    const auto output = encode::describe_output(o.output, o.stream_container);
    if (!output) {
        report_error(err, output.error().message);
        return exit_bad_input;
    }
    const encode::SinkDef sink_def{.path = o.output,
                                   .width = scene.video.width,
                                   .height = scene.video.height,
                                   .fps = scene.video.fps,
                                   .crf = o.crf,
                                   .preset = o.preset,
                                   .codec = o.codec,
                                   .pixel_format = o.pixel_format,
                                   .lossless = o.lossless,
                                   .stream_container = o.stream_container,
                                   .key_colours = scene_colours(scene)};
    if (Status settings = encode::check_settings(sink_def); !settings) {
        report_error(err, settings.error().message);
        return exit_bad_input;
    }
    if (output->to_stdout && isatty(STDOUT_FILENO)) {
        err << "discreel: -o - writes video to standard output, which is a terminal; pipe it "
               "into another program or redirect it to a file\n";
        return exit_bad_input;
    }
    const bool still = output->one_frame;
    const std::optional<FrameRange> frames = pick_frames(o, scene, *output, err);
    if (!frames) return exit_bad_input;
    // With -o - standard output carries the video, so the summary goes to standard error.
    std::ostream& summary = output->to_stdout ? err : out;

    std::vector<NamedPath> inputs, output_paths;
    if (o.scene_path) inputs.push_back({"the scene", *o.scene_path});
    if (!output->to_stdout) output_paths.push_back({"-o", o.output});
    add_output_paths(o.files, output_paths);
    if (!check_distinct_files(inputs, output_paths, err)) return exit_bad_input;

    auto outputs = SideOutputs::open(o.files, scene, err);
    if (!outputs) return exit_runtime_failure;
    auto sink = encode::open_sink(sink_def);
    if (!sink) {
        report_error(err, sink.error().message);
        return exit_runtime_failure;
    }

    const int to_write = frames->last - frames->first + 1;
    if (o.verbose) {
        err << "discreel: " << scene.video.width << 'x' << scene.video.height << ", "
            << scene.video.fps << " fps, frames " << frames->first << ".." << frames->last
            << ", " << scene.discs.size() << " discs; " << output->format << ", "
            << describe_encoder(sink_def) << "; "
            << (o.sequential ? "one thread" : "simulate, render and encode threads") << '\n';
    }

    const Timeline timeline{scene.video.fps, scene.physics.rate, scene.video.frame_count()};
    physics::World world(build_world(scene));
    FrameStepper stepper(world, timeline, scene);
    FrameSceneBuilder frame_builder(scene);
    ProgressMeter progress(err,
                           pick_progress_style(o.quiet, o.progress, isatty(STDERR_FILENO) == 1),
                           to_write);
    Status simulated;   // the physics' failure, which stops the run like a signal
    const PipelineStages stages{
        .simulate = [&](int frame) -> const render::FrameScene* {
            simulated = stepper.advance_to(frame);
            if (!simulated) return nullptr;
            outputs->record(frame, timeline.time_of_frame(frame), world.discs(),
                            stepper.take_events());
            if (frame < frames->first) {
                frame_builder.observe(frame, world.discs());   // trails and follow camera
                return nullptr;
            }
            return &frame_builder.build(frame, world.discs());
        },
        .encode = [&](const ImageView& image) { return (*sink)->write(image); },
        .encoded = [&](int done) { progress.update(done, seconds_since(started)); },
        .should_stop = [&] { return !simulated || stop_signal() != 0; },
    };
    const PipelineResult run = run_pipeline(
        {.frame_count = frames->last + 1,
         .renderer = {.width = scene.video.width, .height = scene.video.height},
         .threaded = !o.sequential,
         .slots = slots_for(scene.video.width, scene.video.height),
         .encoder_first = true},
        stages);
    progress.finish();
    // A signal is checked first: the write it broke (SIGPIPE's EPIPE) is not the story. One
    // during the last frames may arrive after the simulate stage stopped polling.
    const auto interrupted = [&] {
        err << "discreel: interrupted; "
            << (output->to_stdout ? "the stream on standard output ends early"
                                  : "nothing was written")
            << '\n';
        return exit_interrupted_base + stop_signal();
    };
    if (stop_signal() != 0) return interrupted();
    if (!simulated) {
        report_error(err, simulated.error().message);
        return exit_runtime_failure;
    }
    if (!run.status) {
        report_error(err, run.status.error().message);
        return exit_runtime_failure;
    }
    if (run.stopped) return interrupted();
    // The video, trace and events become visible together, or none of them.
    Status sealed = (*sink)->seal();
    if (sealed) sealed = outputs->seal();
    if (stop_signal() != 0) return interrupted();
    if (sealed) {
        std::vector<OutputFile*> files = (*sink)->files();
        for (OutputFile* file : outputs->files()) files.push_back(file);
        sealed = commit_together(files);
    }
    if (!sealed) {
        report_error(err, sealed.error().message);
        return exit_runtime_failure;
    }

    const double seconds = seconds_since(started);
    if (o.verbose) report_details(run, to_write, err);
    if (o.quiet) return exit_ok;
    summary << "wrote " << printable(o.output) << ": " << to_write << (to_write == 1 ? " frame" : " frames")
        << ", " << scene.video.width << 'x' << scene.video.height;
    if (!still) {
        summary << ", " << std::fixed << std::setprecision(2) << scene.video.duration << " s at "
            << scene.video.fps << " fps";
    } else {
        summary << ", frame " << frames->first;
    }
    summary << std::fixed << std::setprecision(1) << " (" << seconds << " s, "
        << (seconds > 0 ? to_write / seconds : 0.0) << " frames/s)\n";
    return exit_ok;
}

}  // namespace discreel::app
