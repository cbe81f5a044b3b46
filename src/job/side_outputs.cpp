#include "side_outputs.hpp"

namespace discreel::job {

Expected<SideOutputs> SideOutputs::open(const std::optional<std::string>& trace,
                                        const std::optional<std::string>& events,
                                        const std::optional<std::string>& joints,
                                        const scene::Scene& scene,
                                        const GroundTruthPaths& truth) {
    SideOutputs outputs;
    if (trace) {
        auto writer = TraceWriter::create(*trace, scene);
        if (!writer) return writer.error();
        outputs.trace_.emplace(std::move(*writer));
    }
    if (events) {
        auto writer = EventWriter::create(*events, scene);
        if (!writer) return writer.error();
        outputs.events_.emplace(std::move(*writer));
    }
    if (joints) {
        auto writer = JointWriter::create(*joints, scene);
        if (!writer) return writer.error();
        outputs.joints_.emplace(std::move(*writer));
    }
    if (truth.shapes) {
        auto file = AtomicTextFile::create(*truth.shapes);
        if (!file) return file.error();
        outputs.shapes_.emplace(std::move(*file));
        outputs.shapes_->write(shapes_json(scene));
    }
    auto views = ViewWriter::open(truth, scene);
    if (!views) return views.error();
    outputs.views_.emplace(std::move(*views));
    return outputs;
}

void SideOutputs::record(int frame, double t, const physics::World& world,
                         std::span<const physics::ContactEvent> events) {
    if (trace_) trace_->write_frame(frame, t, world.bodies(), world.respawns_applied());
    if (events_) events_->write(events);
    if (joints_) joints_->write_frame(frame, t, world.joints());
}

Status SideOutputs::record_view(int frame, double t, const render::FrameScene& view) {
    return views_ ? views_->record(frame, t, view) : Status{};
}

Status SideOutputs::seal() {
    if (trace_) {
        if (Status s = trace_->file().seal(); !s) return s;
    }
    if (events_) {
        if (Status s = events_->file().seal(); !s) return s;
    }
    if (joints_) {
        if (Status s = joints_->file().seal(); !s) return s;
    }
    if (shapes_) {
        if (Status s = shapes_->seal(); !s) return s;
    }
    if (views_) return views_->seal();
    return {};
}

std::vector<OutputFile*> SideOutputs::files() {
    std::vector<OutputFile*> files;
    if (trace_) files.push_back(&trace_->file().file());
    if (events_) files.push_back(&events_->file().file());
    if (joints_) files.push_back(&joints_->file().file());
    if (shapes_) files.push_back(&shapes_->file());
    if (views_) {
        for (OutputFile* file : views_->files()) files.push_back(file);
    }
    return files;
}

}  // namespace discreel::job
