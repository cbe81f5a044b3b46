#pragma once
// Pieces `render` and `simulate` share: printing scene diagnostics, and the optional trace and
// events files that both can write alongside their main work.
#include <cstdint>
#include <optional>
#include <ostream>
#include <span>
#include <vector>

#include "commands.hpp"
#include "discreel/physics.hpp"
#include "discreel/scene.hpp"
#include "trace.hpp"

namespace discreel::app {

// The most resident memory this process has used so far (VmHWM), in bytes; nullopt where
// /proc does not say.
std::optional<std::int64_t> peak_resident_bytes();

// Prints every diagnostic as `file:line:column: message`; returns whether the scene loaded.
bool report_diagnostics(const scene::LoadResult& loaded, std::ostream& err);

class SideOutputs {
public:
    // Opens the requested files (under temporary names); prints the problem and returns nullopt
    // when one cannot be created.
    static std::optional<SideOutputs> open(const OutputFiles& files, const scene::Scene& scene,
                                           std::ostream& err);

    void record(int frame, double t, std::span<const physics::DiscState> discs,
                std::span<const physics::ContactEvent> events);
    Status commit();

private:
    std::optional<TraceWriter> trace_;
    std::optional<EventWriter> events_;
};

}  // namespace discreel::app
