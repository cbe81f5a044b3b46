#pragma once
// `discreel golden`: renders each scene's golden frames and compares them with the images in
// D/<scene>/frame_<n>.png, or writes those images with --update. See docs/golden.md.
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "progress.hpp"
#include "scene_source.hpp"

namespace discreel::app {

// --update: which goldens a run writes. `changed` and `missing` check the others as usual.
enum class UpdateMode {
    none,      // check every frame
    all,       // write every golden
    changed,   // write the goldens that are missing or no longer match
    missing,   // write the goldens that are missing
};

struct GoldenOptions {
    std::vector<std::string> scene_paths;
    std::string dir;                              // goldens live in dir/<scene name>/
    UpdateMode update = UpdateMode::none;
    double tolerance = 0.1;                       // perceptual colour distance, 0..1
    std::optional<std::int64_t> max_diff_pixels;  // per frame; none (and no ratio): 0
    std::optional<double> max_diff_ratio;         // per frame, of all its pixels, 0..1
    std::optional<std::string> junit;             // write a JUnit XML report here
    std::optional<std::string> report;            // write an HTML report here
    // Where a failure's .actual.png and .diff.png go (RESULTS/<scene>/) and, without --report,
    // its HTML report (RESULTS/report.html); never under `dir`. Default: golden-results beside
    // `dir`.
    std::optional<std::string> results;
    VideoOverrides video;                         // --size only
    ProgressRequest progress = ProgressRequest::none;   // --progress [json]
    scene::Limits limits;                         // --max-bodies, --max-duration, ...
    std::vector<scene::Override> overrides;       // --set KEY=VALUE, for every scene
    // --shard K/N: only the K-th (1-based) of N shares of all the scenes' golden frames. The
    // frames, in scene order and then frame order, are dealt out in turn: frame i to share
    // i mod N + 1, so N runs together check every frame exactly once.
    int shard = 1;
    int shards = 1;
};

// Exit codes: 0 every frame matched (or was written), 1 a frame differs or has no golden,
// 2 bad command line or scene, 3 run-time failure (GL, I/O).
int run_golden(const GoldenOptions& options, std::ostream& out, std::ostream& err);

}  // namespace discreel::app
