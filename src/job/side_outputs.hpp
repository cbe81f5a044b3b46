#pragma once
// The optional trace and events files that render and simulate write alongside their main
// work, under temporary names until committed with the run's other outputs.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "discreel/expected.hpp"
#include "discreel/output_file.hpp"
#include "discreel/physics.hpp"
#include "discreel/scene.hpp"
#include "trace.hpp"

namespace discreel::job {

class SideOutputs {
public:
    static Expected<SideOutputs> open(const std::optional<std::string>& trace,
                                      const std::optional<std::string>& events,
                                      const scene::Scene& scene);

    // `respawns`: World::respawns_applied() at that frame.
    void record(int frame, double t, std::span<const physics::BodyState> discs,
                std::span<const physics::ContactEvent> events, std::size_t respawns);
    // Writes what is buffered and seals the files; then files() are ready to be committed
    // together with the run's other outputs.
    Status seal();
    std::vector<OutputFile*> files();

private:
    std::optional<TraceWriter> trace_;
    std::optional<EventWriter> events_;
};

}  // namespace discreel::job
