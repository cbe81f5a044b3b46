#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "discreel/encode.hpp"
#include "discreel/job.hpp"
#include "discreel/printable.hpp"
#include "exit_codes.hpp"
#include "progress.hpp"
#include "run_support.hpp"
#include "signals.hpp"

namespace discreel::app {
namespace {

struct FrameRange {
    int first = 0;
    int last = 0;   // inclusive
};

std::string outside_clip(int frame, int count) {
    return "frame " + std::to_string(frame) + " is outside the clip, which has " +
           std::to_string(count) + " frames (0.." + std::to_string(count - 1) +
           ", or -" + std::to_string(count) + "..-1 counted from the end)";
}

// "A-B" or "A-" (to the end) of a clip of `count` frames; a message when it is not one.
Expected<FrameRange> parse_range(const std::string& text, int count) {
    const Error malformed{"--frames takes A-B (frames A to B, inclusive) or A- (A to the end), "
                          "got '" + text + "'"};
    const auto dash = text.find('-');
    if (dash == std::string::npos || dash == 0) return malformed;
    const auto number = [](std::string_view digits) -> std::optional<int> {
        int value = 0;
        const auto [end, problem] =
            std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (digits.empty() || problem != std::errc() || end != digits.data() + digits.size())
            return std::nullopt;
        return value;
    };
    const std::string_view all = text;
    const auto first = number(all.substr(0, dash));
    const auto last = dash + 1 == text.size() ? std::optional<int>(count - 1)
                                              : number(all.substr(dash + 1));
    if (!first || !last) return malformed;
    if (*first >= count) return Error{outside_clip(*first, count)};
    if (*last >= count) return Error{outside_clip(*last, count)};
    if (*last < *first) {
        return Error{"--frames " + text + " ends before it starts; give the first frame first"};
    }
    return FrameRange{*first, *last};
}

// A .png output is one still; everything else (a numbered .png sequence included) is the
// whole clip, or the frames --frames names.
std::optional<FrameRange> pick_frames(const RenderOptions& o, const scene::Scene& scene,
                                      const encode::OutputDescription& output,
                                      std::ostream& err) {
    const int count = scene.video.frame_count();
    if (o.frames && (o.frame || o.at)) {
        report_error(err, "give either --frames or a single --frame or --at, not both");
        return std::nullopt;
    }
    if (o.frames) {
        const auto range = parse_range(*o.frames, count);
        if (!range) {
            report_error(err, range.error().message);
            return std::nullopt;
        }
        if (output.one_frame && range->last != range->first) {
            report_error(err, "a .png name is one still; for frames " + *o.frames +
                                  " give a numbered name such as frame_%04d.png");
            return std::nullopt;
        }
        return *range;
    }
    if (!output.one_frame) {
        if (o.frame || o.at) {
            err << (output.format == "png sequence"
                        ? "discreel: --frame and --at select a still; a numbered .png name "
                          "writes every frame (--frames A-B writes some)\n"
                        : "discreel: --frame and --at select a still; use them with a .png "
                          "output, or --frames A-B for part of the clip\n");
            return std::nullopt;
        }
        return FrameRange{0, count - 1};
    }
    if (o.frame && o.at) {
        err << "discreel: give either --frame or --at, not both\n";
        return std::nullopt;
    }
    int frame = 0;
    if (o.frame) frame = *o.frame < 0 ? count + *o.frame : *o.frame;   // -1: the last
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
        report_error(err, outside_clip(o.frame ? *o.frame : frame, count));
        return std::nullopt;
    }
    return FrameRange{frame, frame};
}

// GIF frame delays are whole hundredths of a second, and readers play delays under 2 as 10:
// the frame rates a GIF shows at their true speed are 100/k for k >= 2 that are whole numbers.
constexpr std::array<int, 8> gif_rates{50, 25, 20, 10, 5, 4, 2, 1};

bool gif_can_show(int fps) {
    return std::find(gif_rates.begin(), gif_rates.end(), fps) != gif_rates.end();
}

// --quality: Manim's -ql/-qm/-qh/-qk. The height, with the width that keeps the scene's aspect
// (rounded to even), a frame rate, and a crf for the codec in use; explicit options win.
struct Quality {
    int height = 720;   // pixels
    int fps = 30;
    int h264_crf = 23;
    int vp9_crf = 32;
};

Quality quality_of(const std::string& name) {
    if (name == "low") return {.height = 480, .fps = 15, .h264_crf = 28, .vp9_crf = 40};
    if (name == "medium") return {.height = 720, .fps = 30, .h264_crf = 23, .vp9_crf = 34};
    if (name == "high") return {.height = 1080, .fps = 60, .h264_crf = 20, .vp9_crf = 31};
    return {.height = 2160, .fps = 60, .h264_crf = 18, .vp9_crf = 24};   // 4k
}

// The codec a render will use, where a crf applies: "h264", "vp9", or empty.
std::string crf_codec(const RenderOptions& o, const encode::OutputDescription& output) {
    if (o.lossless) return {};
    if (!o.codec.empty()) return o.codec == "h264" || o.codec == "vp9" ? o.codec : "";
    if (output.format == "mp4" || output.format == "mkv") return "h264";
    if (output.format == "webm") return "vp9";
    return {};
}

// The command line's size, fps and crf with --quality filled in where they were not given.
struct Settings {
    VideoOverrides video;
    std::optional<int> crf;
};

Settings settings_for(const RenderOptions& o, const scene::Scene& scene,
                      const encode::OutputDescription& output) {
    Settings s{o.video, o.crf};
    if (!o.quality) return s;
    const Quality q = quality_of(*o.quality);
    if (!s.video.width) {
        const double aspect = static_cast<double>(scene.video.width) / scene.video.height;
        s.video.height = q.height;
        s.video.width = 2 * static_cast<int>(std::lround(q.height * aspect / 2));
    }
    if (!s.video.fps) s.video.fps = q.fps;
    if (!s.crf) {
        const std::string codec = crf_codec(o, output);
        if (codec == "h264") s.crf = q.h264_crf;
        if (codec == "vp9") s.crf = q.vp9_crf;
    }
    return s;
}

// --no-overwrite: the first output that already exists, if any.
std::optional<std::string> existing_output(const RenderOptions& o,
                                           const encode::OutputDescription& output,
                                           const FrameRange& frames) {
    std::vector<std::string> paths;
    if (output.format == "png sequence") {
        for (int n = frames.first; n <= frames.last; ++n) paths.push_back(output.frame_path(n));
    } else if (!output.to_stdout) {
        paths.push_back(o.output);
    }
    if (o.files.trace) paths.push_back(*o.files.trace);
    if (o.files.events) paths.push_back(*o.files.events);
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
    scene::LoadResult loaded = load_scene_or_demo(o.scene_path, o.limits, o.video.duration);
    if (!report_diagnostics(loaded, err)) return exit_bad_input;
    scene::Scene& scene = loaded.scene;
    const auto output = encode::describe_output(o.output, o.stream_container);
    if (!output) {
        report_error(err, output.error().message);
        return exit_bad_input;
    }
    const Settings settings = settings_for(o, scene, *output);
    if (auto problem = apply_overrides(scene, settings.video, o.limits)) {
        report_error(err, *problem);
        return exit_bad_input;
    }
    // A GIF plays at the scene's speed only at a frame rate its delays can express.
    std::optional<int> gif_fps_from;   // the frame rate a GIF could not show
    if (output->format == "gif" && !gif_can_show(scene.video.fps)) {
        if (o.video.fps) {
            report_error(err, "a GIF cannot play at " + std::to_string(scene.video.fps) +
                                  " fps (its frame delays are whole hundredths of a second); "
                                  "use --fps 50, 25, 20 or 10");
            return exit_bad_input;
        }
        gif_fps_from = scene.video.fps;
        scene.video.fps = *std::find_if(gif_rates.begin(), gif_rates.end(),
                                        [&](int fps) { return fps <= scene.video.fps; });
        if (auto problem = scene::check_work(scene, o.limits)) {
            report_error(err, *problem);
            return exit_bad_input;
        }
    }
    // Only PNG keeps a transparent background; the others show its colour, opaque.
    if (scene.video.background.a < 255 && !output->alpha) {
        if (!o.quiet) {
            err << "discreel: note: " << output->format
                << " has no alpha channel; the background is drawn opaque (write .png stills "
                   "or a frame_%04d.png sequence for transparency)\n";
        }
        scene.video.background.a = 255;
    }

    const encode::SinkDef sink_def{.path = o.output,
                                   .width = scene.video.width,
                                   .height = scene.video.height,
                                   .fps = scene.video.fps,
                                   .crf = settings.crf,
                                   .preset = o.preset,
                                   .codec = o.codec,
                                   .pixel_format = o.pixel_format,
                                   .lossless = o.lossless,
                                   .stream_container = o.stream_container,
                                   .key_colours = {},     // the job's: the scene's colours
                                   .first_number = 0};    // the job's: the first frame
    if (Status checked = encode::check_settings(sink_def); !checked) {
        report_error(err, checked.error().message);
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
    if (o.no_overwrite) {
        if (const auto existing = existing_output(o, *output, *frames)) {
            report_error(err, "'" + printable(*existing) +
                                  "' exists and --no-overwrite keeps it; nothing was written");
            return exit_bad_input;
        }
    }
    // With -o - standard output carries the video, so the summary goes to standard error.
    std::ostream& summary = output->to_stdout ? err : out;

    std::vector<NamedPath> inputs, output_paths;
    if (o.scene_path) inputs.push_back({"the scene", *o.scene_path});
    if (!output->to_stdout) output_paths.push_back({"-o", o.output});
    add_output_paths(o.files, output_paths);
    if (!check_distinct_files(inputs, output_paths, err)) return exit_bad_input;

    const int to_write = frames->last - frames->first + 1;
    if (o.verbose) {
        err << "discreel: " << scene.video.width << 'x' << scene.video.height << ", "
            << scene.video.fps << " fps, frames " << frames->first << ".." << frames->last
            << ", " << scene.discs.size() << " discs; " << output->format << ", "
            << describe_encoder(sink_def) << "; "
            << (o.sequential ? "one thread" : "simulate, render and encode threads") << '\n';
    }

    const scene::Video video = scene.video;   // the scene itself moves into the job
    ProgressMeter progress(err,
                           pick_progress_style(o.quiet, o.progress, isatty(STDERR_FILENO) == 1),
                           to_write);
    job::RenderDef def;
    def.scene = std::move(scene);
    def.output = sink_def;
    def.frames = {.first = frames->first, .last = frames->last};
    def.trace = o.files.trace;
    def.events = o.files.events;
    def.threaded = !o.sequential;
    def.on_progress = [&](const job::Progress& p) { progress.update(p.frames_done, p.elapsed); };
    def.should_stop = [] { return stop_signal() != 0; };
    const auto run = job::render(def);
    progress.finish();
    // A signal is checked first: the write it broke (SIGPIPE's EPIPE) is not the story. One
    // during the last frames may arrive after the job stopped polling.
    if (stop_signal() != 0) {
        err << "discreel: interrupted; "
            << (output->to_stdout ? "the stream on standard output ends early"
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
    summary << "wrote " << printable(o.output) << ": " << to_write << (to_write == 1 ? " frame" : " frames")
        << ", " << video.width << 'x' << video.height;
    if (!still) {
        const bool whole = to_write == video.frame_count();
        summary << ", " << std::fixed << std::setprecision(2)
                << (whole ? video.duration : static_cast<double>(to_write) / video.fps)
                << " s at " << video.fps << " fps";
        if (gif_fps_from) summary << " (a GIF cannot play " << *gif_fps_from << " fps)";
        if (!whole) {
            summary << ", frames " << frames->first << ".." << frames->last;
        }
    } else {
        summary << ", frame " << frames->first;
    }
    summary << std::fixed << std::setprecision(1) << " (" << seconds << " s, "
        << (seconds > 0 ? to_write / seconds : 0.0) << " frames/s)\n";
    return exit_ok;
}

}  // namespace discreel::app
