#pragma once
// The CLI's verbs, callable without a process (tests use them directly). Each returns an
// ExitCode and reports problems to `err`.
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "discreel/render.hpp"
#include "progress.hpp"
#include "scene_source.hpp"

namespace discreel::app {

struct OutputFiles {
    std::optional<std::string> trace;    // CSV, one row per disc per frame
    std::optional<std::string> events;   // CSV, one row per new contact
    std::optional<std::string> joints;   // CSV, one row per joint per frame
    // Ground truth (render; simulate takes shapes only): docs/cli.md, "Ground truth".
    std::optional<std::string> shapes;   // JSON, every body's shape per set
    std::optional<std::string> camera;   // CSV, world-to-pixel per drawn frame
    std::optional<std::string> masks;    // directory of mask_NNNNN.png
    std::optional<std::string> boxes;    // CSV, pixel boxes per drawn frame
};

// A renderer kept between the renders of one process (a batch's range of lines): its context
// and compiled shaders are reused. Made for the first render's frame size, again when the size
// changes. The bytes are the same either way.
struct WarmRenderer {
    std::optional<render::Renderer> renderer;
};

struct RenderOptions {
    std::optional<std::string> scene_path;   // none: the built-in demo
    // What to render and how: -o, --frame, --at, --frames, --quality, --size, --fps,
    // --duration, --crf, --preset, --codec, --pix-fmt, --lossless, --format. The service's
    // requests fill the same struct (job::plan_render resolves both alike).
    job::RenderRequest request;
    scene::Limits limits;                    // --max-bodies, --max-duration, --max-scene-bytes
    std::vector<scene::Override> overrides;  // --set KEY=VALUE, in order
    OutputFiles files;
    bool sequential = false;                 // every stage on one thread: same bytes, slower
    int jobs = 0;                            // --jobs: segments at once; 0: one per core
    bool dry_run = false;                    // print the plan as KEY=VALUE lines, render nothing
    ProgressRequest progress = ProgressRequest::none;   // --progress [json]
    bool no_overwrite = false;               // refuse an existing output
    bool quiet = false;                      // errors only: no progress, no summary
    bool verbose = false;                    // settings, stage timings and peak memory too
    WarmRenderer* warm = nullptr;            // none: the render makes its own renderer
};

struct SimulateOptions {
    std::string scene_path;
    scene::Limits limits;
    std::vector<scene::Override> overrides;  // --set KEY=VALUE, in order
    std::optional<double> duration;
    OutputFiles files;
};

struct ValidateOptions {
    std::vector<std::string> scene_paths;
    scene::Limits limits;
    std::vector<scene::Override> overrides;  // --set KEY=VALUE, for every scene
};

struct ServeOptions {
    std::string listen = "127.0.0.1:8080";   // ADDRESS:PORT; port 0 picks a free one
    std::string data_dir = "discreel-data";
    int workers = 1;
    std::size_t max_queue = 64;
    std::optional<std::string> token_file;
    std::vector<std::string> allow_hosts;    // Host names accepted besides the address
    std::vector<std::string> cors_origins;   // --cors: web origins whose pages may call it
    std::optional<double> keep_seconds = 7.0 * 24 * 3600;   // --keep; nullopt: never
    std::optional<std::uint64_t> keep_bytes;                // --keep-bytes
    std::vector<std::string> callback_allow;  // --callback-allow: hosts callbacks may go to
    double job_timeout = 600;                // seconds
    scene::Limits limits;
    std::string version;                     // discreel's, part of every job id
};

struct ConcatOptions {
    std::string dir;                         // segments written by render --segment
    std::string output;                      // -o
    bool quiet = false;
};

int run_concat(const ConcatOptions& options, std::ostream& out, std::ostream& err);
int run_render(const RenderOptions& options, std::ostream& out, std::ostream& err);
int run_validate(const ValidateOptions& options, std::ostream& out, std::ostream& err);
int run_simulate(const SimulateOptions& options, std::ostream& out, std::ostream& err);
int run_serve(const ServeOptions& options, std::ostream& out, std::ostream& err);

}  // namespace discreel::app
