#include "run_support.hpp"

#include <fstream>

#include "discreel/printable.hpp"
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

void report_error(std::ostream& err, std::string_view message) {
    err << "discreel: " << printable(message) << '\n';
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
            report_error(err, trace.error().message);
            return std::nullopt;
        }
        outputs.trace_.emplace(std::move(*trace));
    }
    if (files.events) {
        auto events = EventWriter::create(*files.events, scene);
        if (!events) {
            report_error(err, events.error().message);
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

Status SideOutputs::seal() {
    if (trace_) {
        if (Status s = trace_->file().seal(); !s) return s;
    }
    if (events_) {
        if (Status s = events_->file().seal(); !s) return s;
    }
    return {};
}

std::vector<OutputFile*> SideOutputs::files() {
    std::vector<OutputFile*> files;
    if (trace_) files.push_back(&trace_->file().file());
    if (events_) files.push_back(&events_->file().file());
    return files;
}

bool check_distinct_files(const std::vector<NamedPath>& inputs,
                          const std::vector<NamedPath>& outputs, std::ostream& err) {
    const auto clash = find_clash(inputs, outputs);
    if (clash) report_error(err, *clash);
    return !clash;
}

void add_output_paths(const OutputFiles& files, std::vector<NamedPath>& outputs) {
    if (files.trace) outputs.push_back({"--trace", *files.trace});
    if (files.events) outputs.push_back({"--events", *files.events});
}

bool standard_output_ok(std::ostream& out, std::ostream& err) {
    out.flush();
    if (out) return true;
    report_error(err, "cannot write to standard output");
    return false;
}

}  // namespace discreel::app
