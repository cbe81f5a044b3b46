#pragma once
// Ground truth for datasets (docs/cli.md, "Ground truth"): every body's shape, the camera of
// each drawn frame, instance masks and the boxes they give. Written beside a render and
// committed with its other outputs.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "discreel/atomic_text_file.hpp"
#include "discreel/expected.hpp"
#include "discreel/job.hpp"
#include "discreel/output_file.hpp"
#include "discreel/render.hpp"
#include "discreel/scene.hpp"

namespace discreel::job {

// {"bodies": [...], "walls": [...]}: each body once per set it is part of (a respawned set
// adds entries with their own "from" and "to", seconds), in the body's own frame.
std::string shapes_json(const scene::Scene& scene);

// The camera CSV, masks and boxes of the drawn frames.
class ViewWriter {
public:
    static Expected<ViewWriter> open(const GroundTruthPaths& paths, const scene::Scene& scene);
    bool wanted() const { return camera_ || masks_ || boxes_; }
    // Frame `frame` as drawn, at the scene's video size.
    Status record(int frame, double t, const render::FrameScene& view);
    Status seal();
    std::vector<OutputFile*> files();

private:
    ViewWriter(const GroundTruthPaths& paths, const scene::Scene& scene);
    const scene::Scene* scene_;
    std::optional<AtomicTextFile> camera_, boxes_;
    std::optional<std::string> masks_;     // the directory
    std::vector<OutputFile> mask_files_;   // sealed, committed with the rest
    std::string row_;
};

}  // namespace discreel::job
