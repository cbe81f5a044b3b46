#include <utility>

#include "build_world.hpp"
#include "discreel/job.hpp"
#include "frame_scene.hpp"
#include "stepper.hpp"
#include "timeline.hpp"

namespace discreel::job {

struct Playback::Impl {
    explicit Impl(const scene::Scene& s)
        : timeline{s.video.fps, s.physics.rate, s.video.frame_count()},
          world(build_world(s)),
          stepper(world, timeline, s),
          builder(s) {}

    Timeline timeline;
    physics::World world;
    FrameStepper stepper;
    FrameSceneBuilder builder;
};

Playback::Playback(const scene::Scene& scene) : impl_(std::make_unique<Impl>(scene)) {}
Playback::~Playback() = default;
Playback::Playback(Playback&&) noexcept = default;
Playback& Playback::operator=(Playback&&) noexcept = default;

Status Playback::advance_to(int frame, const std::function<bool()>& should_stop) {
    return impl_->stepper.advance_to(frame, should_stop);
}

void Playback::observe(int frame) {
    impl_->builder.respawned(impl_->world.respawns_applied());
    impl_->builder.observe(frame, impl_->world.bodies());
}

const render::FrameScene& Playback::frame_scene(int frame) {
    impl_->builder.respawned(impl_->world.respawns_applied());
    return impl_->builder.build(frame, impl_->world.bodies(), impl_->stepper.last_contacts());
}

std::span<const physics::BodyState> Playback::bodies() const { return impl_->world.bodies(); }

std::vector<physics::ContactEvent> Playback::take_events() { return impl_->stepper.take_events(); }

std::vector<std::string> Playback::take_warnings() { return impl_->stepper.take_warnings(); }

const physics::World& Playback::world() const { return impl_->world; }

int Playback::frame_count() const { return impl_->timeline.frame_count; }

double Playback::time_of_frame(int frame) const { return impl_->timeline.time_of_frame(frame); }

}  // namespace discreel::job
