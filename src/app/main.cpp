// discreel: the command line. Parses arguments and hands over to the commands; all real work
// lives in discreel_app so tests can call it without a process.
#include <CLI/CLI.hpp>

#include <spawn.h>
#include <unistd.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <map>
#include <iostream>
#include <new>
#include <sstream>

#include "commands.hpp"
#include "discreel/did_you_mean.hpp"
#include "discreel/parse_number.hpp"
#include "discreel/temporary_files.hpp"
#include "exit_codes.hpp"
#include "discreel/read_file.hpp"
#include "golden_command.hpp"
#include "manifest.hpp"
#include "run_support.hpp"
#include "signals.hpp"

namespace {

using namespace discreel::app;
using discreel::parse_size;
using discreel::parse_whole;

void add_size_option(CLI::App& cmd, VideoOverrides& video, const std::string& description) {
    cmd.add_option_function<std::string>(
           "--size",
           [&video](const std::string& s) {
               const auto size = parse_size(s);
               if (!size) {
                   throw CLI::ValidationError("--size", "expected WIDTHxHEIGHT, e.g. 1280x720");
               }
               video.width = size->first;
               video.height = size->second;
           },
           description)
        ->option_text("WxH");
}

void add_output_files(CLI::App& cmd, OutputFiles& files) {
    cmd.add_option("--trace", files.trace, "Write one CSV row per body per frame to FILE")
        ->option_text("FILE");
    cmd.add_option("--events", files.events, "Write one CSV row per new contact to FILE")
        ->option_text("FILE");
    cmd.add_option("--joints", files.joints,
                   "Write one CSV row per joint per frame (anchors, force, torque) to FILE")
        ->option_text("FILE");
}

// "7d", "12h", "30m", "90s" or a plain number of seconds; positive and finite.
std::optional<double> parse_duration(const std::string& text) {
    if (text.empty()) return std::nullopt;
    double unit = 1;
    std::string number = text;
    switch (text.back()) {
        case 's': unit = 1; number.pop_back(); break;
        case 'm': unit = 60; number.pop_back(); break;
        case 'h': unit = 3600; number.pop_back(); break;
        case 'd': unit = 86400; number.pop_back(); break;
        default: break;
    }
    try {
        std::size_t used = 0;
        const double value = std::stod(number, &used);
        if (used != number.size() || !(value > 0) || !std::isfinite(value * unit))
            return std::nullopt;
        return value * unit;
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

// "20G", "500M", "64K", "1T" (powers of 1024) or a plain number of bytes.
std::optional<std::uint64_t> parse_bytes(const std::string& text) {
    if (text.empty()) return std::nullopt;
    int shift = 0;
    std::string number = text;
    switch (text.back()) {
        case 'K': shift = 10; number.pop_back(); break;
        case 'M': shift = 20; number.pop_back(); break;
        case 'G': shift = 30; number.pop_back(); break;
        case 'T': shift = 40; number.pop_back(); break;
        default: break;
    }
    const auto value = parse_whole<std::uint64_t>(number);
    if (!value || *value == 0 || *value > (std::uint64_t{1} << (62 - shift))) return std::nullopt;
    return *value << shift;
}

// --set KEY=VALUE, repeatable: values put into the scene before it is read.
void add_set_option(CLI::App& cmd, std::vector<discreel::scene::Override>& overrides) {
    cmd.add_option_function<std::vector<std::string>>(
           "--set",
           [&overrides](const std::vector<std::string>& texts) {
               for (const std::string& text : texts) {
                   auto parsed = discreel::scene::parse_override(text);
                   if (!parsed) throw CLI::ValidationError(parsed.error().message);
                   overrides.push_back(std::move(*parsed));
               }
           },
           "Set a scene value before the scene is read: a dotted path and a YAML value, "
           "e.g. physics.seed=3, video.size=[128,128], discs.0.radius=0.3; repeatable, "
           "the last wins")
        ->option_text("KEY=VALUE")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

// Ground truth for datasets; `views`: the per-frame ones too (render), else shapes only.
void add_ground_truth(CLI::App& cmd, OutputFiles& files, bool views) {
    cmd.add_option("--shapes", files.shapes,
                   "Write every body's shape, colour and mass (each respawned set too) as JSON "
                   "to FILE")
        ->option_text("FILE")
        ->group("Ground truth");
    if (!views) return;
    cmd.add_option("--camera", files.camera,
                   "Write each drawn frame's world-to-pixel transform as CSV to FILE")
        ->option_text("FILE")
        ->group("Ground truth");
    cmd.add_option("--masks", files.masks,
                   "Write each drawn frame's instance mask (16-bit PNG: body index + 1, walls "
                   "65535) into DIR as mask_NNNNN.png")
        ->option_text("DIR")
        ->group("Ground truth");
    cmd.add_option("--boxes", files.boxes,
                   "Write each visible body's pixel bounding box and pixel count per drawn "
                   "frame as CSV to FILE")
        ->option_text("FILE")
        ->group("Ground truth");
}

// A number option that must be finite (CLI11 reads "nan" and "inf" as doubles) and, where
// given, within [low, high].
CLI::Validator finite_number(double low = -std::numeric_limits<double>::max(),
                              double high = std::numeric_limits<double>::max()) {
    return CLI::Validator(
        [low, high](std::string& text) -> std::string {
            double value = 0;
            try {
                std::size_t used = 0;
                value = std::stod(text, &used);
                if (used != text.size()) return "expected a number, got '" + text + "'";
            } catch (const std::exception&) {
                return "expected a number, got '" + text + "'";
            }
            if (!std::isfinite(value)) return "expected a finite number, got '" + text + "'";
            if (value < low || value > high) {
                std::ostringstream range;
                range << "must be between " << low << " and " << high << ", got " << text;
                return range.str();
            }
            return {};
        },
        "NUMBER");
}

// A whole number from `low` to `high`, checked on its text: "-1" never wraps into an unsigned
// option, and a range error names both bounds as numbers a person typed.
CLI::Validator whole_number(long long low, long long high) {
    return CLI::Validator(
        [low, high](std::string& text) -> std::string {
            const auto value = parse_whole<long long>(text);
            const bool digits =
                text.find_first_not_of("0123456789", text.rfind('-', 0) == 0 ? 1 : 0) ==
                    std::string::npos && text != "-" && !text.empty();
            if (!value && !digits) return "expected a whole number, got '" + text + "'";
            if (!value || *value < low || *value > high) {
                return "must be from " + std::to_string(low) + " to " + std::to_string(high) +
                       ", got " + text;
            }
            return {};
        },
        "N");
}

// The protective limits of docs/scene-format.md, raised (or lowered) per run.
void add_limit_options(CLI::App& cmd, discreel::scene::Limits& limits) {
    cmd.add_option("--max-bodies,--max-discs", limits.bodies,
                   "Most bodies (discs and other shapes) a scene may have")
        ->check(whole_number(1, 100'000'000))
        ->capture_default_str()
        ->group("Limits");
    cmd.add_option("--max-duration", limits.duration, "Longest video.duration, seconds")
        ->check(finite_number(1e-9, 1e9))
        ->capture_default_str()
        ->group("Limits");
    cmd.add_option("--max-scene-bytes", limits.file_bytes, "Largest scene file, bytes")
        ->check(whole_number(1, 1LL << 32))
        ->capture_default_str()
        ->group("Limits");
    cmd.add_option("--max-scene-values", limits.values,
                   "Most YAML values (scalars, lists, mappings) a scene file may hold")
        ->check(whole_number(1, 1'000'000'000))
        ->capture_default_str()
        ->group("Limits");
    cmd.add_option("--max-substeps", limits.substeps,
                   "Most physics substeps a run may take (duration x rate x substeps)")
        ->check(whole_number(1, 1'000'000'000'000LL))
        ->capture_default_str()
        ->group("Limits");
}

CLI::CheckedTransformer progress_values() {
    return CLI::CheckedTransformer(std::map<std::string, ProgressRequest>{
        {"lines", ProgressRequest::lines}, {"json", ProgressRequest::json}});
}

// --frame N, negative counting from the end, or `last` (= -1).
void add_frame_option(CLI::App& cmd, std::optional<int>& frame) {
    cmd.add_option_function<std::string>(
           "--frame",
           [&frame](const std::string& text) {
               if (text == "last") {
                   frame = -1;
                   return;
               }
               const auto value = parse_whole(text);
               if (!value) {
                   throw CLI::ValidationError(
                       "--frame", "expected a frame number (negative counts from the end) or "
                                  "'last', got '" + text + "'");
               }
               frame = *value;
           },
           "Frame of a .png still: 0 (default) is the first, -1 or 'last' the last")
        ->option_text("N|last");
}

// Options that take an optional value: `--progress` alone means lines and `--progress json`
// asks for JSON; `--update`/`-u` alone rewrites every golden and `--update=changed` only what
// changed. The value is joined to the option here, so a scene path after a bare option is
// never taken for its value.
std::vector<std::string> normalise_arguments(const std::vector<std::string>& args) {
    struct Optional {
        std::string_view name, fallback;
        std::vector<std::string_view> values;   // also taken as the value when they follow
    };
    const std::vector<Optional> options{{"--progress", "lines", {"lines", "json"}},
                                        {"--update", "all", {"all", "changed", "missing"}},
                                        {"-u", "all", {"all", "changed", "missing"}}};
    std::vector<std::string> out;
    for (std::size_t k = 0; k < args.size(); ++k) {
        if (args[k] == "--") {
            out.insert(out.end(), args.begin() + static_cast<std::ptrdiff_t>(k), args.end());
            break;
        }
        const auto match = std::find_if(options.begin(), options.end(),
                                        [&](const Optional& o) { return args[k] == o.name; });
        if (match == options.end()) {
            out.push_back(args[k]);
            continue;
        }
        const std::string name = match->name == "-u" ? "--update" : std::string(match->name);
        if (k + 1 < args.size() &&
            std::find(match->values.begin(), match->values.end(), args[k + 1]) !=
                match->values.end()) {
            out.push_back(name + "=" + args[++k]);
        } else {
            out.push_back(name + "=" + std::string(match->fallback));
        }
    }
    std::reverse(out.begin(), out.end());   // CLI11 parses a vector from its back
    return out;
}

std::vector<std::string> option_names(const CLI::App& cmd) {
    std::vector<std::string> names;
    for (const CLI::Option* option : cmd.get_options()) {
        for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
    }
    return names;
}

// The first word that is no command or option the command line knows, with a suggestion:
// "unknown command 'rendr'; did you mean 'render'?".
std::optional<std::string> unknown_word(CLI::App& app, const std::vector<std::string>& args) {
    if (args.empty()) return std::nullopt;
    const std::string& first = args.back();   // reversed: the first argument is last
    if (first.empty() || first[0] == '-') return std::nullopt;
    std::vector<std::string> commands;
    for (const CLI::App* sub : app.get_subcommands({})) commands.push_back(sub->get_name());
    if (std::find(commands.begin(), commands.end(), first) != commands.end()) {
        CLI::App* cmd = app.get_subcommand(first);
        const std::vector<std::string> known = option_names(*cmd);
        for (auto it = args.rbegin() + 1; it != args.rend(); ++it) {
            if (*it == "--") break;
            if (it->size() < 3 || it->compare(0, 2, "--") != 0) continue;
            const std::string name = it->substr(0, it->find('='));
            if (name == "--help" ||
                std::find(known.begin(), known.end(), name) != known.end()) {
                continue;
            }
            std::string message = "unknown option '" + name + "' for '" + first + "'";
            if (const auto guess = discreel::closest_match(name, known)) {
                message += "; did you mean '" + *guess + "'?";
            }
            return message + " (discreel " + first + " --help lists its options)";
        }
        return std::nullopt;
    }
    std::string message = "unknown command '" + first + "'";
    if (const auto guess = discreel::closest_match(first, commands)) {
        message += "; did you mean '" + *guess + "'?";
    }
    return message + " (discreel --help lists the commands)";
}

}  // namespace

static int run_words(const std::vector<std::string>& words, const std::string& where,
                     WarmRenderer* warm = nullptr);

struct BatchOptions {
    std::string manifest;
    std::optional<IndexRange> index;
    bool all = false;
    int jobs = 1;
};

// Names the failed lines of a range, after their own messages.
static void report_failed(std::vector<std::size_t> failed, IndexRange range) {
    if (failed.empty()) return;
    std::sort(failed.begin(), failed.end());
    std::string list;
    for (const std::size_t i : failed) list += (list.empty() ? "" : ", ") + std::to_string(i);
    report_error(std::cerr, std::to_string(failed.size()) + " of " +
                                std::to_string(range.last - range.first + 1) +
                                " renders failed (" + (failed.size() == 1 ? "index " : "indexes ") +
                                list + ")");
}

// The renders of `range` in `jobs` processes at once (`batch MANIFEST --index A-B`), each a
// contiguous share of the range on one warm renderer: a process's crash or memory stays its
// own. Each names its own failed lines; the worst exit code is returned.
static int run_batch_processes(const BatchOptions& b, IndexRange range) {
    const std::size_t count = range.last - range.first + 1;
    const std::size_t shares = std::min(count, static_cast<std::size_t>(b.jobs));
    std::vector<pid_t> running;
    int worst = exit_ok;
    for (std::size_t k = 0; k < shares; ++k) {
        const std::size_t first = range.first + count * k / shares;
        const std::size_t last = range.first + count * (k + 1) / shares - 1;
        std::string index = std::to_string(first) + "-" + std::to_string(last);
        std::string self = "/proc/self/exe", verb = "batch", flag = "--index";
        std::string manifest = b.manifest;
        char* argv[] = {self.data(), verb.data(), manifest.data(), flag.data(), index.data(),
                        nullptr};
        pid_t pid = 0;
        if (posix_spawn(&pid, "/proc/self/exe", nullptr, nullptr, argv, environ) != 0) {
            report_error(std::cerr, "cannot start the renders of indexes " + index);
            worst = std::max(worst, static_cast<int>(exit_runtime_failure));
            continue;
        }
        running.push_back(pid);
    }
    // A stop signal sent to this process only (a pod's PID 1, Slurm's scancel of the batch
    // step) is passed on: the shares end as a render ends, nothing half-written left behind.
    bool passed_on = false;
    while (!running.empty()) {
        if (stop_signal() != 0 && !passed_on) {
            for (const pid_t pid : running) kill(pid, stop_signal());
            passed_on = true;
        }
        int status = 0;
        const pid_t pid = waitpid(-1, &status, WNOHANG);
        if (pid <= 0) {
            usleep(50'000);
            continue;
        }
        const auto found = std::find(running.begin(), running.end(), pid);
        if (found == running.end()) continue;
        running.erase(found);
        const bool ended = WIFEXITED(status);
        worst = std::max(worst, ended ? WEXITSTATUS(status) : static_cast<int>(exit_runtime_failure));
    }
    return worst;
}

// Manifest lines, each run as `discreel render` with that line's words, in order in this
// process (one warm renderer for them all) or `jobs` processes at a time; a line's mistakes are
// printed as MANIFEST:LINE: message. A failed line does not stop the others.
static int run_batch(const BatchOptions& b) {
    const auto fail = [](const std::string& message) {
        report_error(std::cerr, message);
        return exit_bad_input;
    };
    auto text = discreel::read_file_bounded(b.manifest, 16u << 20);
    if (!text) return fail("cannot read '" + b.manifest + "': " + text.error().message);
    if (text->too_large) return fail("'" + b.manifest + "' is over 16 MiB: not a manifest");
    const std::size_t count = count_renders(text->bytes);
    std::optional<IndexRange> flag = b.index;
    if (b.all) {
        if (count == 0) return fail(b.manifest + " holds no renders");
        flag = IndexRange{0, count - 1};
    }
    auto range = batch_index(flag, [](const char* name) -> const char* {
        return std::getenv(name);
    });
    if (!range) return fail(range.error().message);
    // A range past the end is refused before any line runs.
    if (range->last >= count) return fail(pick_render(text->bytes, range->last, b.manifest)
                                              .error()
                                              .message);
    if (b.jobs > 1 && range->last > range->first) return run_batch_processes(b, *range);
    WarmRenderer warm;
    int worst = exit_ok;
    std::vector<std::size_t> failed;
    for (std::size_t i = range->first; i <= range->last && stop_signal() == 0; ++i) {
        auto line = pick_render(text->bytes, i, b.manifest);
        int code = exit_bad_input;
        if (!line) {
            report_error(std::cerr, line.error().message);
        } else {
            std::vector<std::string> words{"render"};
            words.insert(words.end(), line->words.begin(), line->words.end());
            code = run_words(words, b.manifest + ":" + std::to_string(line->number) + ": ",
                             &warm);
        }
        if (code != exit_ok) failed.push_back(i);
        worst = std::max(worst, code);
    }
    if (range->last > range->first) report_failed(failed, *range);
    return worst;
}

// Runs one command line (the words after the program's name). A mistake in it is printed after
// `where`: "discreel: " for the process's own, "MANIFEST:LINE: " for a line of a batch, whose
// renders share `warm`.
static int run_words(const std::vector<std::string>& words, const std::string& where,
                     WarmRenderer* warm) {
    CLI::App app{"discreel: renders 2-D rigid-body physics scenes to video, headless and deterministic",
                 "discreel"};
    app.set_version_flag("--version", std::string("discreel ") + DISCREEL_VERSION);
    app.require_subcommand(1);

    RenderOptions render;
    render.warm = warm;
    CLI::App* render_cmd = app.add_subcommand(
        "render", "Render a scene to a video (.mp4 .mkv .webm .gif) or stills (.png)");
    render_cmd->add_option("scene", render.scene_path,
                           "Scene file (YAML); the built-in demo when omitted");
    render_cmd->add_option("-o,--output", render.request.output,
                           "Output file; the extension picks the format: .mp4, .mkv, .webm, "
                           ".gif, .png (a still, or every frame for frame_%04d.png), or - for "
                           "a stream on standard output (Matroska, or fragmented MP4 with "
                           "--format mp4)")
        ->required();
    add_frame_option(*render_cmd, render.request.frame);
    render_cmd->add_option("--at", render.request.at,
                           "Time in seconds for a .png still; the duration gives the last frame")
        ->check(finite_number(0, 1e9));
    render_cmd->add_option("--frames", render.request.frames,
                           "Render frames A to B (inclusive, from 0), or A- to the end, into "
                           "any format")
        ->option_text("A-B|A-");
    render_cmd->add_option("--quality", render.request.quality,
                           "low (480p, 15 fps), medium (720p, 30 fps), high (1080p, 60 fps) or "
                           "4k (2160p, 60 fps), with a crf to match; --size, --fps and --crf "
                           "still win")
        ->option_text("low|medium|high|4k")
        ->check(CLI::IsMember({"low", "medium", "high", "4k"}));
    add_size_option(*render_cmd, render.request.video, "Override the frame size, WIDTHxHEIGHT");
    render_cmd->add_option("--fps", render.request.video.fps, "Override frames per second");
    render_cmd->add_option("--duration", render.request.video.duration,
                           "Override duration in seconds")
        ->check(finite_number(1e-9, 1e9));
    render_cmd->add_option("--crf", render.request.crf,
                           "Quality, lower is better: H.264 0..51 (default 20), VP9 0..63 "
                           "(default 32)");
    render_cmd->add_option("--preset", render.request.preset,
                           "x264 preset, ultrafast .. placebo (default veryfast)");
    render_cmd->add_option("--codec", render.request.codec,
                           "Video codec: h264 (.mp4, .mkv), vp9 (.webm, .mkv), ffv1 (.mkv)");
    render_cmd->add_option("--pix-fmt", render.request.pixel_format,
                           "yuv420p (default) or yuv444p, for crisp colour edges (H.264, VP9)");
    render_cmd->add_option("--format", render.request.stream_container,
                           "Container of -o -: mkv (default) or mp4 (fragmented MP4); of a "
                           "--segment: mp4 (default), mkv or webm")
        ->check(CLI::IsMember({"mkv", "mp4", "webm"}));
    render_cmd->add_option("--jobs", render.jobs,
                           "Segments of a video file rendered at once (default: one per core; "
                           "at most what the available memory holds); the bytes are the same "
                           "for any number")
        ->check(whole_number(1, 1024));
    render_cmd->add_flag_function(
        "--audio,!--no-audio",
        [&render](std::int64_t count) { render.request.audio = count > 0; },
                         "Put the contacts' soundtrack into the video file, or leave it out "
                         "(default: the scene's audio.enabled)");
    render_cmd->add_flag("--dry-run", render.dry_run,
                         "Check everything, print what would be written (output, format, "
                         "frames, segments) as KEY=VALUE lines and render nothing");
    render_cmd->add_option("--segment", render.request.segment,
                           "Render only segment K (from 0) of the video, into the directory -o "
                           "names; join them with discreel concat")
        ->option_text("K")
        ->check(whole_number(0, 1'000'000'000));
    render_cmd->add_flag("--lossless", render.request.lossless,
                         "FFV1 in Matroska (.mkv or -): every pixel's RGB exactly");
    add_output_files(*render_cmd, render.files);
    add_ground_truth(*render_cmd, render.files, true);
    add_set_option(*render_cmd, render.overrides);
    add_limit_options(*render_cmd, render.limits);
    render_cmd->add_option("--progress", render.progress,
                           "Report progress on standard error even when it is not a terminal: "
                           "one line per second, or with 'json' one JSON object per line")
        ->option_text("[json]")
        ->transform(progress_values());
    render_cmd->add_flag("--no-overwrite", render.no_overwrite,
                         "Refuse to replace an existing output file (exit 2, before any work)");
    render_cmd->add_flag("-q,--quiet", render.quiet, "Print nothing but errors");
    render_cmd->add_flag("-v,--verbose", render.verbose,
                         "Also print the settings, the renderer, time per stage and peak memory");
    render_cmd->add_flag("--sequential", render.sequential,
                         "Simulate, render and encode one frame at a time on one thread "
                         "(same output, slower)");
    render_cmd->get_option("--quiet")->excludes("--verbose");
    render_cmd->get_option("--quiet")->excludes("--progress");

    ConcatOptions concat;
    CLI::App* concat_cmd = app.add_subcommand(
        "concat", "Join the segments render --segment wrote into one video, by stream copy");
    concat_cmd->add_option("dir", concat.dir, "Directory of the segments")->required();
    concat_cmd->add_option("-o,--output", concat.output,
                           "Output file, of the segments' format (.mp4, .mkv or .webm)")
        ->required();
    concat_cmd->add_flag("-q,--quiet", concat.quiet, "Print nothing but errors");

    SimulateOptions simulate;
    CLI::App* simulate_cmd =
        app.add_subcommand("simulate", "Run the physics only and print a summary");
    simulate_cmd->add_option("scene", simulate.scene_path, "Scene file (YAML)")->required();
    simulate_cmd->add_option("--duration", simulate.duration, "Override duration in seconds")
        ->check(finite_number(1e-9, 1e9));
    add_output_files(*simulate_cmd, simulate.files);
    add_ground_truth(*simulate_cmd, simulate.files, false);
    add_set_option(*simulate_cmd, simulate.overrides);
    add_limit_options(*simulate_cmd, simulate.limits);

    BatchOptions batch;
    CLI::App* batch_cmd = app.add_subcommand(
        "batch", "Render one line of a manifest (SCENE -o OUT [options] per line): the task's "
                 "index picks it (docs/scale.md)");
    batch_cmd->add_option("manifest", batch.manifest, "Manifest file")->required();
    batch_cmd->add_option_function<std::string>(
                  "--index",
                  [&batch](const std::string& text) {
                      auto range = parse_index_range(text);
                      if (!range) throw CLI::ValidationError("--index", range.error().message);
                      batch.index = *range;
                  },
                  "0-based render to run, or a range A-B run in order; default: "
                  "SLURM_ARRAY_TASK_ID, then JOB_COMPLETION_INDEX")
        ->option_text("I|A-B");
    batch_cmd->add_flag("--all", batch.all, "Run every render of the manifest");
    batch_cmd->add_option("--jobs", batch.jobs,
                          "Processes at once, each rendering a contiguous share of the lines "
                          "in order (default 1: every line in this process)")
        ->check(whole_number(1, 1024));
    batch_cmd->get_option("--all")->excludes("--index");

    ServeOptions serve;
    serve.version = DISCREEL_VERSION;
    // A service holds many requests at once: its default scene size is smaller than a file's.
    serve.limits.file_bytes = 4u << 20;
    CLI::App* serve_cmd = app.add_subcommand(
        "serve", "Render scenes sent over HTTP (docs/serve.md): a job queue with warm workers");
    serve_cmd->add_option("--listen", serve.listen,
                          "ADDRESS:PORT to listen on; port 0 picks a free one (printed)")
        ->capture_default_str();
    serve_cmd->add_option("--data", serve.data_dir, "Directory of the job store and outputs")
        ->capture_default_str();
    serve_cmd->add_option("--workers", serve.workers, "Jobs rendered at once")
        ->check(whole_number(1, 64))
        ->capture_default_str();
    serve_cmd->add_option("--max-queue", serve.max_queue,
                          "Jobs waiting for a worker; beyond it 429 with Retry-After")
        ->check(whole_number(1, 100000))
        ->capture_default_str();
    serve_cmd->add_option("--token-file", serve.token_file,
                          "File holding a bearer token every /v1 request must present")
        ->option_text("FILE");
    serve_cmd->add_option("--allow-host", serve.allow_hosts,
                          "A Host name the server answers for besides its address (and "
                          "localhost); repeat for more. Requests for any other get 421")
        ->option_text("NAME");
    serve_cmd->add_option_function<std::string>(
                 "--keep",
                 [&serve](const std::string& text) {
                     if (text == "never") {
                         serve.keep_seconds.reset();
                         return;
                     }
                     const auto seconds = parse_duration(text);
                     if (!seconds) {
                         throw CLI::ValidationError(
                             "--keep", "expected a time such as 7d, 12h, 30m or 90s, or never; "
                                       "got '" + text + "'");
                     }
                     serve.keep_seconds = *seconds;
                 },
                 "Delete finished jobs and their outputs this long after they were accepted "
                 "(s, m, h, d; never keeps them all); default 7d")
        ->option_text("TIME");
    serve_cmd->add_option_function<std::string>(
                 "--keep-bytes",
                 [&serve](const std::string& text) {
                     const auto bytes = parse_bytes(text);
                     if (!bytes) {
                         throw CLI::ValidationError(
                             "--keep-bytes", "expected a size such as 20G, 500M or 1048576; "
                                             "got '" + text + "'");
                     }
                     serve.keep_bytes = *bytes;
                 },
                 "Also delete the oldest finished jobs while their outputs take more than this "
                 "(K, M, G, T: powers of 1024)")
        ->option_text("SIZE");
    serve_cmd->add_option("--callback-allow", serve.callback_allow,
                          "A host (name or address, as the URL writes it) a job's \"callback\" "
                          "may name; repeat for more. Without it, callbacks are refused")
        ->option_text("HOST")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    serve_cmd->add_option("--cors", serve.cors_origins,
                          "A web origin (scheme://host[:port]) whose pages may call the API "
                          "from a browser: preflights are answered and Access-Control-Allow-"
                          "Origin sent to it only; repeat for more")
        ->option_text("ORIGIN")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    serve_cmd->add_option("--job-timeout", serve.job_timeout,
                          "Seconds one job may render before it fails")
        ->check(finite_number(0.001, 1e7))
        ->capture_default_str();
    add_limit_options(*serve_cmd, serve.limits);

    ValidateOptions validate;
    CLI::App* validate_cmd = app.add_subcommand(
        "validate", "Check scene files and print every problem; exit 2 if any");
    validate_cmd->add_option("scenes", validate.scene_paths, "Scene files (YAML)")->required();
    add_set_option(*validate_cmd, validate.overrides);
    add_limit_options(*validate_cmd, validate.limits);

    GoldenOptions golden;
    CLI::App* golden_cmd = app.add_subcommand(
        "golden", "Render each scene's golden frames and compare them with DIR/<scene>/frame_<n>.png");
    golden_cmd->add_option("scenes", golden.scene_paths, "Scene files (YAML)")->required();
    golden_cmd->add_option("--dir", golden.dir, "Directory of the goldens, one folder per scene")
        ->required();
    golden_cmd->add_option("-u,--update", golden.update,
                           "Write the goldens instead of checking them: every one (all, the "
                           "default), only those that are missing, or those missing or no "
                           "longer matching (changed)")
        ->option_text("[all|changed|missing]")
        ->transform(CLI::CheckedTransformer(
            std::map<std::string, UpdateMode>{{"all", UpdateMode::all},
                                              {"changed", UpdateMode::changed},
                                              {"missing", UpdateMode::missing}}));
    golden_cmd->add_option("--report", golden.report,
                           "Write the self-contained HTML page of the run (each failing frame: "
                           "golden, actual and difference, with the numbers) to this file, "
                           "passing or not; default: DIR/report.html of --results on a failure")
        ->option_text("FILE.html");
    golden_cmd->add_option("--results", golden.results,
                           "Directory for a failure's .actual.png, .diff.png and report "
                           "(default: golden-results beside --dir); never under --dir")
        ->option_text("DIR");
    add_set_option(*golden_cmd, golden.overrides);
    add_limit_options(*golden_cmd, golden.limits);
    golden_cmd->add_option("--progress", golden.progress,
                           "Report progress on standard error even when it is not a terminal: "
                           "one line per second, or with 'json' one JSON object per line")
        ->option_text("[json]")
        ->transform(progress_values());
    golden_cmd->add_option("--tolerance", golden.tolerance,
                           "Perceptual colour distance still counted as equal, 0..1 (default 0.1)")
        ->check(finite_number());
    golden_cmd->add_option("--max-diff-pixels", golden.max_diff_pixels,
                           "Differing pixels allowed per frame (default 0)");
    golden_cmd->add_option("--max-diff-ratio", golden.max_diff_ratio,
                           "Differing pixels allowed per frame, as a fraction of all, 0..1")
        ->check(finite_number());
    golden_cmd->add_option("--junit", golden.junit, "Also write a JUnit XML report to FILE")
        ->option_text("FILE");
    add_size_option(*golden_cmd, golden.video, "Override every scene's frame size, WIDTHxHEIGHT");
    golden_cmd->add_option_function<std::string>(
                  "--shard",
                  [&golden](const std::string& text) {
                      const auto slash = text.find('/');
                      const std::string_view all = text;
                      std::optional<int> k, n;
                      if (slash != std::string::npos) {
                          k = parse_whole(all.substr(0, slash));
                          n = parse_whole(all.substr(slash + 1));
                      }
                      if (!k || !n || *k < 1 || *k > *n) {
                          throw CLI::ValidationError(
                              "--shard",
                              "expected K/N with 1 <= K <= N, e.g. 2/4, got '" + text + "'");
                      }
                      golden.shard = *k;
                      golden.shards = *n;
                  },
                  "Check only the K-th of N shares of the frames (1-based), for parallel CI jobs")
        ->option_text("K/N");

    std::vector<std::string> args = normalise_arguments(words);
    if (const auto unknown = unknown_word(app, args)) {
        std::cerr << where << *unknown << '\n';
        return exit_bad_input;
    }
    try {
        app.parse(args);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // Every message starts with "discreel:", as the commands' own do, and says where
        // help is: the command's own page when one was named.
        std::string command;
        for (const CLI::App* sub : app.get_subcommands({})) {
            if (sub->parsed()) command = " " + sub->get_name();
        }
        std::cerr << where << e.what() << "\nRun 'discreel" << command
                  << " --help' for more information.\n";
        return exit_bad_input;
    }

    if (batch_cmd->parsed()) return run_batch(batch);
    int code = exit_bad_input;
    if (render_cmd->parsed()) code = run_render(render, std::cout, std::cerr);
    if (concat_cmd->parsed()) code = run_concat(concat, std::cout, std::cerr);
    if (simulate_cmd->parsed()) code = run_simulate(simulate, std::cout, std::cerr);
    if (validate_cmd->parsed()) code = run_validate(validate, std::cout, std::cerr);
    if (golden_cmd->parsed()) code = run_golden(golden, std::cout, std::cerr);
    if (serve_cmd->parsed()) code = run_serve(serve, std::cout, std::cerr);
    // What a command printed may still sit in a buffer: a full disk or a closed pipe behind
    // standard output is a failure, not a success with the output silently lost.
    if (code == exit_ok && !standard_output_ok(std::cout, std::cerr)) return exit_runtime_failure;
    return code;
}

// Library code returns its errors; what can still be thrown is the standard library running out
// of memory (a scene within the limits on a machine without that much) or a bug. Either way the
// process reports it and exits 3 rather than aborting without a word; the sinks and side files
// are destroyed on the way out, which deletes their temporary files.
int main(int argc, char** argv) {
    discreel::delete_temporary_files_on_crash();
    try {
        ignore_file_size_signal();
        install_stop_handlers();
        return run_words(std::vector<std::string>(argv + 1, argv + argc), "discreel: ");
    } catch (const std::bad_alloc&) {
        std::cerr << "discreel: out of memory\n";
    } catch (const std::exception& e) {
        std::cerr << "discreel: internal error: " << e.what() << '\n';
    } catch (...) {
        std::cerr << "discreel: internal error\n";
    }
    return exit_runtime_failure;
}
