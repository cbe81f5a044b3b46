// job::plan_render: a render request resolved against its scene, for every front end.
#include "discreel/render_plan.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string_view>

#include "discreel/parse_number.hpp"
#include "discreel/printable.hpp"

namespace discreel::job {
namespace {

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
    const std::string_view all = text;
    const auto first = parse_whole(all.substr(0, dash));
    const auto last = dash + 1 == text.size() ? std::optional<int>(count - 1)
                                              : parse_whole(all.substr(dash + 1));
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
Expected<FrameRange> pick_frames(const RenderRequest& o, const scene::Scene& scene,
                                 const encode::OutputDescription& output) {
    const int count = scene.video.frame_count();
    if (o.frames && (o.frame || o.at)) {
        return Error{"give either --frames or a single --frame or --at, not both"};
    }
    if (o.frames) {
        const auto range = parse_range(*o.frames, count);
        if (!range) return range.error();
        if (output.one_frame && range->last != range->first) {
            return Error{"a .png name is one still; for frames " + *o.frames +
                         " give a numbered name such as frame_%04d.png"};
        }
        return *range;
    }
    if (!output.one_frame) {
        if (o.frame || o.at) {
            return Error{output.format == "png sequence"
                             ? "--frame and --at select a still; a numbered .png name writes "
                               "every frame (--frames A-B writes some)"
                             : "--frame and --at select a still; use them with a .png output, "
                               "or --frames A-B for part of the clip"};
        }
        return FrameRange{0, count - 1};
    }
    if (o.frame && o.at) return Error{"give either --frame or --at, not both"};
    int frame = 0;
    if (o.frame) frame = *o.frame < 0 ? count + *o.frame : *o.frame;   // -1: the last
    if (o.at) {
        // Checked as a number before it becomes a frame index, which it could overflow. The
        // clip's end (t = duration) shows its last frame.
        const double duration = scene.video.duration;
        if (!std::isfinite(*o.at) || *o.at < 0 || *o.at > duration) {
            std::string text = "--at must be a time in the clip, 0 to ";
            append_number(text, duration);
            return Error{text + " seconds"};
        }
        frame = std::min(count - 1, static_cast<int>(std::lround(*o.at * scene.video.fps)));
    }
    if (frame < 0 || frame >= count) return Error{outside_clip(o.frame ? *o.frame : frame, count)};
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
std::string crf_codec(const RenderRequest& o, const encode::OutputDescription& output) {
    if (o.lossless) return {};
    if (!o.codec.empty()) return o.codec == "h264" || o.codec == "vp9" ? o.codec : "";
    if (output.format == "mp4" || output.format == "mkv") return "h264";
    if (output.format == "webm") return "vp9";
    return {};
}

// The request's size, fps and crf with the quality preset filled in where they were not given.
struct Settings {
    VideoOverrides video;
    std::optional<int> crf;
};

Settings settings_for(const RenderRequest& o, const scene::Scene& scene,
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

}  // namespace

std::optional<std::string> apply_overrides(scene::Scene& scene, const VideoOverrides& o,
                                           const scene::Limits& limits) {
    if (o.width) {
        if (*o.width < 16 || *o.width > 7680 || *o.height < 16 || *o.height > 4320) {
            return "--size must be between 16x16 and 7680x4320";
        }
        scene.video.width = *o.width;
        scene.video.height = *o.height;
    }
    if (o.fps) {
        if (*o.fps < 1 || *o.fps > 240) return "--fps must be between 1 and 240";
        scene.video.fps = *o.fps;
    }
    if (o.duration) {
        if (!(*o.duration > 0 && *o.duration <= limits.duration)) {
            std::string limit;
            append_number(limit, limits.duration);
            return "--duration must be greater than 0 and at most " + limit +
                   " seconds (raise the limit with --max-duration)";
        }
        scene.video.duration = *o.duration;
    }
    // A longer clip or another frame rate is more work than the file asked for.
    return scene::check_work(scene, limits);
}

Expected<RenderPlan> plan_render(scene::Scene scene, const RenderRequest& o,
                                 const scene::Limits& limits) {
    // A segment is a file in the directory -o names, of the format --format names.
    std::string path = o.output;
    std::string container = o.stream_container;
    if (o.segment) {
        if (container.empty()) container = "mp4";
        if (container != "mp4" && container != "mkv" && container != "webm") {
            return Error{"--format of a segment is mp4, mkv or webm, not '" + container + "'"};
        }
        if (o.frame || o.at) return Error{"--segment renders part of a video; --frame and --at "
                                          "select a still"};
        path = (std::filesystem::path(o.output) / "segment.").string() + container;
        container.clear();
    }
    auto output = encode::describe_output(path, container);
    if (!output) return output.error();
    const Settings settings = settings_for(o, scene, *output);
    if (auto problem = apply_overrides(scene, settings.video, limits)) return Error{*problem};
    // Video in yuv420p stores colour at half resolution both ways: its sides must be even.
    // PNG, GIF, yuv444p and lossless video (FFV1 or H.264 in full colour) take any size; the
    // encoder checks what it is given in any case.
    const bool halved = (output->format == "mp4" || output->format == "mkv" ||
                         output->format == "webm") &&
                        !o.lossless && o.codec != "ffv1" && o.pixel_format != "yuv444p";
    if (halved &&
        (scene.video.width % 2 != 0 || scene.video.height % 2 != 0)) {
        return Error{(o.video.width ? "--size " : "video.size ") +
                     std::to_string(scene.video.width) + "x" + std::to_string(scene.video.height) +
                     ": " + output->format +
                     " video (yuv420p) stores colour at half resolution, so its width and "
                     "height must be even; PNG, GIF and --pix-fmt yuv444p take any size"};
    }
    RenderPlan plan;
    // A GIF plays at the scene's speed only at a frame rate its delays can express.
    if (output->format == "gif" && !gif_can_show(scene.video.fps)) {
        if (o.video.fps) {
            return Error{"a GIF cannot play at " + std::to_string(scene.video.fps) +
                         " fps (its frame delays are whole hundredths of a second); use --fps "
                         "50, 25, 20 or 10"};
        }
        plan.gif_fps_from = scene.video.fps;
        scene.video.fps = *std::find_if(gif_rates.begin(), gif_rates.end(),
                                        [&](int fps) { return fps <= scene.video.fps; });
        if (auto problem = scene::check_work(scene, limits)) return Error{*problem};
    }
    // Only PNG keeps a transparent background; the others show its colour, opaque.
    if (scene.video.background.a < 255 && !output->alpha) {
        plan.drawn_opaque = true;
        scene.video.background.a = 255;
    }
    plan.sink = encode::SinkDef{.path = path,
                                .width = scene.video.width,
                                .height = scene.video.height,
                                .fps = scene.video.fps,
                                .crf = settings.crf,
                                .preset = o.preset,
                                .codec = o.codec,
                                .pixel_format = o.pixel_format,
                                .lossless = o.lossless,
                                .stream_container = container,
                                .key_colours = {},     // the job's: the scene's colours
                                .first_number = 0,     // the job's: the first frame
                                .keyint = 0};          // the job's: a segment's length
    if (Status checked = encode::check_settings(plan.sink); !checked) return checked.error();
    auto frames = pick_frames(o, scene, *output);
    if (!frames) return frames.error();
    plan.frames = *frames;
    // Sound goes into video files (and is all a .wav holds).
    plan.audio = o.audio.value_or(scene.audio.enabled);
    if (plan.audio && !segmented(*output) && !output->to_stdout && output->format != "wav") {
        if (o.audio) {
            return Error{"--audio: " + output->format +
                         " carries no sound; write .mp4, .mkv, .webm, - or .wav"};
        }
        plan.audio = false;   // the scene's sound where the format has none: the pictures only
    }
    if (output->format == "wav") plan.audio = false;
    if (segmented(*output)) plan.segments = segment_count(scene.video, plan.frames);
    if (o.segment) {
        if (*o.segment < 0 || *o.segment >= plan.segments) {
            return Error{"--segment " + std::to_string(*o.segment) + " is past the end: the clip has " +
                         std::to_string(plan.segments) +
                         (plan.segments == 1 ? " segment (0)" : " segments (0.." +
                                                                  std::to_string(plan.segments - 1) + ")")};
        }
        plan.segment = o.segment;
        plan.sink.path = (std::filesystem::path(o.output) /
                          encode::segment_file_name(*o.segment, plan.segments, output->format))
                             .string();
        output->path = plan.sink.path;
    }
    plan.output = std::move(*output);
    plan.scene = std::move(scene);
    return plan;
}

}  // namespace discreel::job
