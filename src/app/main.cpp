// discreel: the command line. Parses arguments and hands over to the commands; all real work
// lives in discreel_app so tests can call it without a process.
#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <limits>
#include <iostream>
#include <new>
#include <sstream>

#include "commands.hpp"
#include "discreel/temporary_files.hpp"
#include "exit_codes.hpp"
#include "golden_command.hpp"
#include "run_support.hpp"
#include "signals.hpp"

namespace {

using namespace discreel::app;

// "1280x720" -> width, height; anything else is rejected with CLI11's usual message.
std::string parse_size(const std::string& text, VideoOverrides& video) {
    const auto x = text.find('x');
    int w = 0, h = 0;
    if (x != std::string::npos) {
        const char* end = text.data() + text.size();
        const auto [pw, ew] = std::from_chars(text.data(), text.data() + x, w);
        const auto [ph, eh] = std::from_chars(text.data() + x + 1, end, h);
        if (ew == std::errc() && eh == std::errc() && pw == text.data() + x && ph == end) {
            video.width = w;
            video.height = h;
            return {};
        }
    }
    return "expected WIDTHxHEIGHT, e.g. 1280x720";
}

void add_size_option(CLI::App& cmd, VideoOverrides& video, const std::string& description) {
    cmd.add_option_function<std::string>(
           "--size",
           [&video](const std::string& s) {
               if (auto problem = parse_size(s, video); !problem.empty()) {
                   throw CLI::ValidationError("--size", problem);
               }
           },
           description)
        ->option_text("WxH");
}

void add_output_files(CLI::App& cmd, OutputFiles& files) {
    cmd.add_option("--trace", files.trace, "Write one CSV row per disc per frame to FILE")
        ->option_text("FILE");
    cmd.add_option("--events", files.events, "Write one CSV row per new contact to FILE")
        ->option_text("FILE");
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

// The protective limits of docs/scene-format.md, raised (or lowered) per run.
void add_limit_options(CLI::App& cmd, discreel::scene::Limits& limits) {
    cmd.add_option("--max-discs", limits.discs, "Most discs a scene may have")
        ->check(CLI::PositiveNumber)
        ->capture_default_str()
        ->group("Limits");
    cmd.add_option("--max-duration", limits.duration, "Longest video.duration, seconds")
        ->check(finite_number(1e-9, 1e9))
        ->capture_default_str()
        ->group("Limits");
    cmd.add_option("--max-scene-bytes", limits.file_bytes, "Largest scene file, bytes")
        ->check(CLI::PositiveNumber)
        ->capture_default_str()
        ->group("Limits");
    cmd.add_option("--max-scene-values", limits.values,
                   "Most YAML values (scalars, lists, mappings) a scene file may hold")
        ->check(CLI::PositiveNumber)
        ->capture_default_str()
        ->group("Limits");
    cmd.add_option("--max-substeps", limits.substeps,
                   "Most physics substeps a run may take (duration x rate x substeps)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str()
        ->group("Limits");
}

}  // namespace

static int run_command_line(int argc, char** argv) {
    CLI::App app{"discreel: renders 2-D disc physics scenes to video, headless and deterministic",
                 "discreel"};
    app.set_version_flag("--version", std::string("discreel ") + DISCREEL_VERSION);
    app.require_subcommand(1);

    RenderOptions render;
    CLI::App* render_cmd = app.add_subcommand(
        "render", "Render a scene to a video (.mp4 .mkv .webm .gif) or stills (.png)");
    render_cmd->add_option("scene", render.scene_path,
                           "Scene file (YAML); the built-in demo when omitted");
    render_cmd->add_option("-o,--output", render.output,
                           "Output file; the extension picks the format: .mp4, .mkv, .webm, "
                           ".gif, .png (a still, or every frame for frame_%04d.png), or - for "
                           "a stream on standard output (Matroska, or fragmented MP4 with "
                           "--format mp4)")
        ->required();
    render_cmd->add_option("--frame", render.frame, "Frame index for a .png still (default 0)");
    render_cmd->add_option("--at", render.at, "Time in seconds for a .png still")
        ->check(finite_number(0, 1e9));
    add_size_option(*render_cmd, render.video, "Override the frame size, WIDTHxHEIGHT");
    render_cmd->add_option("--fps", render.video.fps, "Override frames per second");
    render_cmd->add_option("--duration", render.video.duration, "Override duration in seconds")
        ->check(finite_number(1e-9, 1e9));
    render_cmd->add_option("--crf", render.crf,
                           "Quality, lower is better: H.264 0..51 (default 20), VP9 0..63 "
                           "(default 32)");
    render_cmd->add_option("--preset", render.preset,
                           "x264 preset, ultrafast .. placebo (default veryfast)");
    render_cmd->add_option("--codec", render.codec,
                           "Video codec: h264 (.mp4, .mkv), vp9 (.webm, .mkv), ffv1 (.mkv)");
    render_cmd->add_option("--pix-fmt", render.pixel_format,
                           "yuv420p (default) or yuv444p, for crisp colour edges (H.264, VP9)");
    render_cmd->add_option("--format", render.stream_container,
                           "Container of -o -: mkv (default) or mp4 (fragmented MP4)")
        ->check(CLI::IsMember({"mkv", "mp4"}));
    render_cmd->add_flag("--lossless", render.lossless,
                         "FFV1 in Matroska (.mkv or -): every pixel's RGB exactly");
    add_output_files(*render_cmd, render.files);
    add_limit_options(*render_cmd, render.limits);
    render_cmd->add_flag("--progress", render.progress,
                         "Report progress on standard error even when it is not a terminal "
                         "(one line per second)");
    render_cmd->add_flag("-q,--quiet", render.quiet, "Print nothing but errors");
    render_cmd->add_flag("-v,--verbose", render.verbose,
                         "Also print the settings, the renderer, time per stage and peak memory");
    render_cmd->add_flag("--sequential", render.sequential,
                         "Simulate, render and encode one frame at a time on one thread "
                         "(same output, slower)");
    render_cmd->get_option("--quiet")->excludes("--verbose");
    render_cmd->get_option("--quiet")->excludes("--progress");

    SimulateOptions simulate;
    CLI::App* simulate_cmd =
        app.add_subcommand("simulate", "Run the physics only and print a summary");
    simulate_cmd->add_option("scene", simulate.scene_path, "Scene file (YAML)")->required();
    simulate_cmd->add_option("--duration", simulate.duration, "Override duration in seconds")
        ->check(finite_number(1e-9, 1e9));
    add_output_files(*simulate_cmd, simulate.files);
    add_limit_options(*simulate_cmd, simulate.limits);

    ValidateOptions validate;
    CLI::App* validate_cmd = app.add_subcommand(
        "validate", "Check scene files and print every problem; exit 2 if any");
    validate_cmd->add_option("scenes", validate.scene_paths, "Scene files (YAML)")->required();
    add_limit_options(*validate_cmd, validate.limits);

    GoldenOptions golden;
    CLI::App* golden_cmd = app.add_subcommand(
        "golden", "Render each scene's golden frames and compare them with DIR/<scene>/frame_<n>.png");
    golden_cmd->add_option("scenes", golden.scene_paths, "Scene files (YAML)")->required();
    golden_cmd->add_option("--dir", golden.dir, "Directory of the goldens, one folder per scene")
        ->required();
    golden_cmd->add_flag("--update", golden.update, "Write (or refresh) the goldens instead");
    add_limit_options(*golden_cmd, golden.limits);
    golden_cmd->add_flag("--progress", golden.progress,
                         "Report progress on standard error even when it is not a terminal");
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

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return exit_bad_input;
    }

    ignore_file_size_signal();
    install_stop_handlers();
    int code = exit_bad_input;
    if (render_cmd->parsed()) code = run_render(render, std::cout, std::cerr);
    if (simulate_cmd->parsed()) code = run_simulate(simulate, std::cout, std::cerr);
    if (validate_cmd->parsed()) code = run_validate(validate, std::cout, std::cerr);
    if (golden_cmd->parsed()) code = run_golden(golden, std::cout, std::cerr);
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
        return run_command_line(argc, argv);
    } catch (const std::bad_alloc&) {
        std::cerr << "discreel: out of memory\n";
    } catch (const std::exception& e) {
        std::cerr << "discreel: internal error: " << e.what() << '\n';
    } catch (...) {
        std::cerr << "discreel: internal error\n";
    }
    return exit_runtime_failure;
}
