#pragma once
// The optional trace, events and joints files that render and simulate write alongside their main
// work, under temporary names until committed with the run's other outputs.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "discreel/expected.hpp"
#include "discreel/output_file.hpp"
#include "discreel/physics.hpp"
#include "discreel/scene.hpp"
#include "ground_truth.hpp"
#include "trace.hpp"

namespace discreel::job {

class SideOutputs {
public:
    static Expected<SideOutputs> open(const std::optional<std::string>& trace,
                                      const std::optional<std::string>& events,
                                      const std::optional<std::string>& joints,
                                      const scene::Scene& scene,
                                      const GroundTruthPaths& truth = {});

    // `respawns`: World::respawns_applied() at that frame.
    void record(int frame, double t, const physics::World& world,
                std::span<const physics::ContactEvent> events);
    // Whether the camera, masks or boxes are asked for: record_view() wants each drawn frame.
    bool views_wanted() const { return views_ && views_->wanted(); }
    Status record_view(int frame, double t, const render::FrameScene& view);
    // Writes what is buffered and seals the files; then files() are ready to be committed
    // together with the run's other outputs.
    Status seal();
    std::vector<OutputFile*> files();

private:
    std::optional<TraceWriter> trace_;
    std::optional<EventWriter> events_;
    std::optional<JointWriter> joints_;
    std::optional<AtomicTextFile> shapes_;
    std::optional<ViewWriter> views_;
};

}  // namespace discreel::job
