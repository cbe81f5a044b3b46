#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <algorithm>
#include <filesystem>
#include <mutex>
#include <iomanip>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "discreel/encode.hpp"
#include "discreel/job.hpp"
#include "discreel/render_plan.hpp"
#include "discreel/printable.hpp"
#include "exit_codes.hpp"
#include "progress.hpp"
#include "run_support.hpp"
#include "signals.hpp"

namespace discreel::app {
namespace {

// --no-overwrite: the first output that already exists, if any.
std::optional<std::string> existing_output(const RenderOptions& o,
                                           const encode::OutputDescription& output,
                                           const job::FrameRange& frames) {
    std::vector<std::string> paths;
    if (output.format == "png sequence") {
        for (int n = frames.first; n <= frames.last; ++n) paths.push_back(output.frame_path(n));
    } else if (!output.to_stdout) {
        paths.push_back(output.path);
    }
    if (o.files.trace) paths.push_back(*o.files.trace);
    if (o.files.events) paths.push_back(*o.files.events);
    if (o.files.joints) paths.push_back(*o.files.joints);
    if (o.files.shapes) paths.push_back(*o.files.shapes);
    if (o.files.camera) paths.push_back(*o.files.camera);
    if (o.files.boxes) paths.push_back(*o.files.boxes);
    for (const std::string& path : paths) {
        struct stat info{};
        if (lstat(path.c_str(), &info) == 0) return path;
    }
    return std::nullopt;
}

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string describe_encoder(const encode::SinkDef& def, bool segmented) {
    std::ostringstream text;
    text << "codec " << (def.codec.empty() ? "default" : def.codec) << ", crf ";
    if (def.crf) {
        text << *def.crf;
    } else {
        text << "default";
    }
    text << ", preset " << (def.preset.empty() ? "veryfast" : def.preset) << ", ";
    if (segmented) {
        text << "1 encoder thread per segment";
    } else {
        text << def.threads << " encoder threads";
    }
    return text.str();
}

// --verbose: where the time went and how much memory the process needed at most.
void report_details(const job::RenderSummary& run, int frames, std::ostream& err) {
    const auto per_frame = [&](double seconds) {
        std::ostringstream text;
        text << std::fixed << std::setprecision(2) << seconds << " s ("
             << (frames > 0 ? 1000.0 * seconds / frames : 0.0) << " ms/frame)";
        return text.str();
    };
    err << "discreel: renderer: " << run.renderer << '\n';
    err << "discreel: busy: simulate " << per_frame(run.busy.simulate) << ", render "
        << per_frame(run.busy.render) << ", encode " << per_frame(run.busy.encode) << '\n';
    if (const auto peak = peak_resident_bytes()) {
        err << "discreel: peak memory: " << std::fixed << std::setprecision(1)
            << static_cast<double>(*peak) / (1024.0 * 1024.0) << " MiB (VmHWM)\n";
    }
}

}  // namespace

int run_render(const RenderOptions& o, std::ostream& out, std::ostream& err) {
    const auto started = Clock::now();
    scene::LoadResult loaded = load_scene_or_demo(o.scene_path, o.limits, o.request.video.duration,
                                                  o.overrides);
    if (!report_diagnostics(loaded, err, !o.quiet)) return exit_bad_input;
    auto plan = job::plan_render(std::move(loaded.scene), o.request, o.limits);
    if (!plan) {
        report_error(err, plan.error().message);
        return exit_bad_input;
    }
    // The plan is the job's: the render reads it from the RenderDef.
    job::RenderDef def;
    def.plan = std::move(*plan);
    const scene::Scene& scene = def.plan.scene;
    const encode::OutputDescription& output = def.plan.output;
    const encode::SinkDef& sink_def = def.plan.sink;
    const std::optional<int> gif_fps_from = def.plan.gif_fps_from;
    if (def.plan.drawn_opaque && !o.quiet) {
        err << "discreel: note: " << output.format
            << " has no alpha channel; the background is drawn opaque (write .png stills "
               "or a frame_%04d.png sequence for transparency)\n";
    }
    if (output.to_stdout && isatty(STDOUT_FILENO)) {
        err << "discreel: -o - writes video to standard output, which is a terminal; pipe it "
               "into another program or redirect it to a file\n";
        return exit_bad_input;
    }
    const bool still = output.one_frame;
    const job::FrameRange frames =
        def.plan.segment ? job::segment_frames(scene.video, def.plan.frames, *def.plan.segment)
                         : def.plan.frames;
    if (o.dry_run) {
        // For scripts (deploy/slurm/clip.sh asks how many segment tasks to submit).
        out << "output=" << printable(output.path) << "\nformat=" << output.format
            << "\nsize=" << scene.video.width << 'x' << scene.video.height
            << "\nfps=" << scene.video.fps << "\nframes=" << frames.first << '-' << frames.last
            << "\nsegments=" << (job::segmented(output) ? def.plan.segments : 0)
            << "\nsegment_frames=" << (job::segmented(output) ? scene.video.segment_frames() : 0)
            << "\naudio=" << (def.plan.audio || output.format == "wav" ? "yes" : "no") << '\n';
        return standard_output_ok(out, err) ? exit_ok : exit_runtime_failure;
    }
    const OutputFiles& files = o.files;
    const bool truth = files.shapes || files.camera || files.masks || files.boxes;
    if (def.plan.segment && (files.trace || files.events || files.joints || truth)) {
        report_error(err, "--trace, --events, --joints and the ground truth (--shapes, --camera, "
                          "--masks, --boxes) belong to a whole render, not to one segment");
        return exit_bad_input;
    }
    if (output.format == "wav" && (files.trace || files.events || files.joints || truth)) {
        report_error(err, "a .wav soundtrack has no frames: --trace, --events, --joints and "
                          "the ground truth come with a video or images");
        return exit_bad_input;
    }
    if ((files.masks || files.boxes) && scene.bodies.size() >= render::wall_mask_id) {
        report_error(err, "--masks and --boxes number bodies in 16 bits: at most " +
                              std::to_string(render::wall_mask_id - 1) + " bodies, and the scene "
                              "has " + std::to_string(scene.bodies.size()));
        return exit_bad_input;
    }
    // Tasks of one render share the directory of its segments, and make it if need be.
    if (def.plan.segment) {
        std::error_code error;
        std::filesystem::create_directories(o.request.output, error);
        if (error && !std::filesystem::is_directory(o.request.output)) {
            std::string message = "cannot make the directory '";
            message += printable(o.request.output);
            message += "' for the segment: " + error.message();
            report_error(err, message);
            return exit_runtime_failure;
        }
    }
    if (o.no_overwrite) {
        if (const auto existing = existing_output(o, output, frames)) {
            // Built by appending: GCC 12 warns (-Wrestrict) falsely on "'" + std::string here.
            std::string message(1, '\'');
            message += printable(*existing);
            message += "' exists and --no-overwrite keeps it; nothing was written";
            report_error(err, message);
            return exit_bad_input;
        }
    }
    // With -o - standard output carries the video, so the summary goes to standard error.
    std::ostream& summary = output.to_stdout ? err : out;

    std::vector<NamedPath> inputs, output_paths;
    if (o.scene_path) inputs.push_back({"the scene", *o.scene_path});
    if (!output.to_stdout) output_paths.push_back({"-o", output.path});
    add_output_paths(o.files, output_paths);
    if (!check_distinct_files(inputs, output_paths, err)) return exit_bad_input;
    if (!make_output_directories(output_paths, err)) return exit_runtime_failure;

    const int to_write = frames.last - frames.first + 1;
    if (o.verbose) {
        err << "discreel: " << scene.video.width << 'x' << scene.video.height << ", "
            << scene.video.fps << " fps, frames " << frames.first << ".." << frames.last
            << ", " << scene.bodies.size()
            << (std::any_of(scene.bodies.begin(), scene.bodies.end(),
                            [](const scene::Body& b) { return b.shape.has_value(); })
                    ? " bodies; "
                    : " discs; ")
            << output.format << ", "
            << describe_encoder(sink_def, job::segmented(output)) << "; "
            << (o.sequential ? "one thread" : "simulate, render and encode threads");
        if (job::segmented(output)) {
            err << "; " << def.plan.segments
                << (def.plan.segments == 1 ? " segment" : " segments")
                << " of " << scene.video.segment_frames() << " frames";
        }
        err << '\n';
    }

    const scene::Video& video = scene.video;
    ProgressMeter progress(err,
                           pick_progress_style(o.quiet, o.progress, isatty(STDERR_FILENO) == 1),
                           to_write);
    // --jobs beyond what memory holds would only swap or be killed: the job cuts it, and says.
    const int memory_holds = job::segments_memory_holds(video.width, video.height);
    if (o.jobs > memory_holds && job::segmented(output) && def.plan.segments > memory_holds &&
        !o.quiet) {
        err << "discreel: --jobs " << o.jobs << ": rendering " << memory_holds
            << " segments at once, as many as the available memory holds at "
            << video.width << 'x' << video.height << '\n';
    }
    def.jobs = o.jobs;
    def.trace = o.files.trace;
    def.events = o.files.events;
    def.joints = o.files.joints;
    def.truth = {.shapes = files.shapes,
                 .camera = files.camera,
                 .masks = files.masks,
                 .boxes = files.boxes};
    def.threaded = !o.sequential;
    if (o.warm != nullptr) {
        std::optional<render::Renderer>& warm = o.warm->renderer;
        if (!warm || warm->def().width != video.width || warm->def().height != video.height) {
            warm.reset();
            auto made = render::Renderer::create({.width = video.width, .height = video.height});
            if (!made) {
                report_error(err, made.error().message);
                return exit_runtime_failure;
            }
            warm = std::move(*made);
        }
        def.renderer = &*warm;
    }
    def.on_progress = [&](const job::Progress& p) { progress.update(p.frames_done, p.elapsed); };
    def.should_stop = [] { return stop_signal() != 0; };
    // Warnings of the run come from the simulating threads; they are printed once it ends,
    // also in -q: the output is not what the scene asked for.
    std::mutex warned_mutex;
    std::vector<std::string> warned;
    def.on_warning = [&](const std::string& message) {
        std::lock_guard lock(warned_mutex);
        warned.push_back(message);
    };
    const auto run = job::render(def);
    progress.finish();
    for (const std::string& message : warned) err << "discreel: warning: " << message << '\n';
    // A signal is checked first: the write it broke (SIGPIPE's EPIPE) is not the story. One
    // during the last frames may arrive after the job stopped polling.
    if (stop_signal() != 0) {
        err << "discreel: interrupted; "
            << (output.to_stdout ? "the stream on standard output ends early"
                                  : "nothing was written")
            << '\n';
        return exit_interrupted_base + stop_signal();
    }
    if (!run) {
        report_error(err, run.error().message);
        return exit_runtime_failure;
    }
    const double seconds = seconds_since(started);
    progress.done(seconds);
    if (o.verbose) report_details(*run, to_write, err);
    if (o.quiet) return exit_ok;
    if (output.format == "wav") {
        summary << "wrote " << printable(output.path) << ": " << std::fixed << std::setprecision(2)
                << video.duration << " s of sound, 48 kHz stereo (" << std::setprecision(1)
                << seconds << " s)\n";
        return exit_ok;
    }
    summary << "wrote " << printable(output.path) << ": " << to_write
            << (to_write == 1 ? " frame" : " frames")
        << ", " << video.width << 'x' << video.height;
    if (!still) {
        const bool whole = to_write == video.frame_count();
        summary << ", " << std::fixed << std::setprecision(2)
                << (whole ? video.duration : static_cast<double>(to_write) / video.fps)
                << " s at " << video.fps << " fps";
        if (gif_fps_from) summary << " (a GIF cannot play " << *gif_fps_from << " fps)";
        if (!whole) {
            summary << ", frames " << frames.first << ".." << frames.last;
        }
    } else {
        summary << ", frame " << frames.first;
    }
    summary << std::fixed << std::setprecision(1) << " (" << seconds << " s, "
        << (seconds > 0 ? to_write / seconds : 0.0) << " frames/s)\n";
    return exit_ok;
}

}  // namespace discreel::app
