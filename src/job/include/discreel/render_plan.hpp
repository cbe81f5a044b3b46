#pragma once
// What a render asks for besides its scene, resolved into a job: the `render` command's options
// and a service request go through the same plan, so the same request gives the same bytes
// from either front end.
//     auto plan = job::plan_render(std::move(loaded.scene), request, limits);
//     job::RenderDef def;
//     def.plan = std::move(*plan);
#include <optional>
#include <string>

#include "discreel/encode.hpp"
#include "discreel/expected.hpp"
#include "discreel/job.hpp"
#include "discreel/scene.hpp"

namespace discreel::job {

// Changes to the scene's video settings, applied after loading.
struct VideoOverrides {
    std::optional<int> width, height;   // pixels
    std::optional<int> fps;
    std::optional<double> duration;     // seconds
};

// Applies `o` to `scene`; `limits` bound the duration and the work as they bound the file's.
// Returns the problem, in words, or nullopt.
std::optional<std::string> apply_overrides(scene::Scene& scene, const VideoOverrides& o,
                                           const scene::Limits& limits);

struct RenderRequest {
    std::string output;                      // path: its extension picks the format; "-": stdout
    std::optional<int> frame;                // a .png still; negative counts from the end
    std::optional<double> at;                // seconds, a .png still
    std::optional<std::string> frames;       // "A-B" or "A-": a range of frames, any format
    std::optional<std::string> quality;      // low, medium, high, 4k: size, fps and crf
    VideoOverrides video;
    std::optional<int> crf;                  // none: the codec's default (or the quality's)
    std::string preset;                      // x264 preset; empty: veryfast
    std::string codec;                       // empty: the container's default
    std::string pixel_format;                // empty: yuv420p
    bool lossless = false;                   // FFV1 in Matroska
    // The container of a stream (-o -: "mkv", the default, or "mp4", fragmented) or of a
    // segment (mp4, the default, mkv or webm).
    std::string stream_container;
    // Render only this segment (from 0), into a file in the directory `output` names.
    std::optional<int> segment;
    std::optional<bool> audio;               // --audio / --no-audio; none: the scene's
};

// RenderPlan, what a plan resolves to, is job.hpp's: a RenderDef carries it.


// Resolves `request` against `scene`: the format, the quality preset, the overrides, the GIF
// frame rate, the frames to draw and the encoder settings. The error says what to change, in
// the command line's terms (--size, --frame, ...).
Expected<RenderPlan> plan_render(scene::Scene scene, const RenderRequest& request,
                                 const scene::Limits& limits);

}  // namespace discreel::job
