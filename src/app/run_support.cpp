#include "run_support.hpp"

#include <fstream>
#include <string>

namespace discreel::app {

std::optional<std::int64_t> peak_resident_bytes() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line)) {
        if (line.rfind("VmHWM:", 0) == 0) return std::stoll(line.substr(6)) * 1024;   // kB
    }
    return std::nullopt;
}

bool report_diagnostics(const scene::LoadResult& loaded, std::ostream& err) {
    for (const scene::Diagnostic& d : loaded.diagnostics) err << d.to_string() << '\n';
    return loaded.ok();
}

std::optional<SideOutputs> SideOutputs::open(const OutputFiles& files, const scene::Scene& scene,
                                             std::ostream& err) {
    SideOutputs outputs;
    if (files.trace) {
        auto trace = TraceWriter::create(*files.trace, scene);
        if (!trace) {
            err << "discreel: " << trace.error().message << '\n';
            return std::nullopt;
        }
        outputs.trace_.emplace(std::move(*trace));
    }
    if (files.events) {
        auto events = EventWriter::create(*files.events, scene);
        if (!events) {
            err << "discreel: " << events.error().message << '\n';
            return std::nullopt;
        }
        outputs.events_.emplace(std::move(*events));
    }
    return outputs;
}

void SideOutputs::record(int frame, double t, std::span<const physics::DiscState> discs,
                         std::span<const physics::ContactEvent> events) {
    if (trace_) trace_->write_frame(frame, t, discs);
    if (events_) events_->write(events);
}

Status SideOutputs::commit() {
    if (trace_) {
        if (Status s = trace_->commit(); !s) return s;
    }
    if (events_) {
        if (Status s = events_->commit(); !s) return s;
    }
    return {};
}

}  // namespace discreel::app
