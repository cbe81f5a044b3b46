#pragma once
// The CLI's verbs, callable without a process (tests use them directly). Each returns an
// ExitCode and reports problems to `err`.
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "progress.hpp"
#include "scene_source.hpp"

namespace discreel::app {

struct OutputFiles {
    std::optional<std::string> trace;    // CSV, one row per disc per frame
    std::optional<std::string> events;   // CSV, one row per new contact
};

struct RenderOptions {
    std::optional<std::string> scene_path;   // none: the built-in demo
    std::string output;                      // extension picks the format; "-": stdout
    std::optional<int> frame;                // for a .png still; negative counts from the end
    std::optional<double> at;                // seconds, for a .png still
    std::optional<std::string> frames;       // "A-B" or "A-": a range of frames, any format
    std::optional<std::string> quality;      // low, medium, high, 4k: size, fps and crf
    scene::Limits limits;                    // --max-bodies, --max-duration, --max-scene-bytes
    VideoOverrides video;
    std::optional<int> crf;                  // none: the codec's default
    std::string preset;                      // x264 preset; empty: veryfast
    std::string codec;                       // empty: the container's default
    std::string pixel_format;                // empty: yuv420p
    bool lossless = false;                   // FFV1 in Matroska
    std::string stream_container;            // -o -: "mkv" (empty) or "mp4" (fragmented)
    OutputFiles files;
    bool sequential = false;                 // every stage on one thread: same bytes, slower
    ProgressRequest progress = ProgressRequest::none;   // --progress [json]
    bool no_overwrite = false;               // refuse an existing output
    bool quiet = false;                      // errors only: no progress, no summary
    bool verbose = false;                    // settings, stage timings and peak memory too
};

struct SimulateOptions {
    std::string scene_path;
    scene::Limits limits;
    std::optional<double> duration;
    OutputFiles files;
};

struct ValidateOptions {
    std::vector<std::string> scene_paths;
    scene::Limits limits;
};

struct ServeOptions {
    std::string listen = "127.0.0.1:8080";   // ADDRESS:PORT; port 0 picks a free one
    std::string data_dir = "discreel-data";
    int workers = 1;
    std::size_t max_queue = 64;
    std::optional<std::string> token_file;
    double job_timeout = 600;                // seconds
    scene::Limits limits;
    std::string version;                     // discreel's, part of every job id
};

int run_render(const RenderOptions& options, std::ostream& out, std::ostream& err);
int run_validate(const ValidateOptions& options, std::ostream& out, std::ostream& err);
int run_simulate(const SimulateOptions& options, std::ostream& out, std::ostream& err);
int run_serve(const ServeOptions& options, std::ostream& out, std::ostream& err);

}  // namespace discreel::app
