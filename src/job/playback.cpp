// Playback: the frame loop every front end shares, and going back to a frame through
// checkpoints of the whole state.
#include <algorithm>
#include <utility>

#include "build_world.hpp"
#include "discreel/job.hpp"
#include "frame_scene.hpp"
#include "stepper.hpp"
#include "timeline.hpp"

namespace discreel::job {
namespace {

// Everything a frame depends on: the world, the stepper's memory (last contacts, bodies
// kept in their walls) and the look's (trails, follow camera), as after showing the frames
// before `next`.
struct State {
    State(const scene::Scene& s, const Timeline& timeline)
        : world(build_world(s)), stepper(world, timeline, s), builder(s) {}
    State(const State& other)
        : world(other.world), stepper(other.stepper, world), builder(other.builder),
          next(other.next), unseen(other.unseen) {}
    State& operator=(const State&) = delete;
    State(State&&) = delete;
    State& operator=(State&&) = delete;
    ~State() = default;

    physics::World world;
    FrameStepper stepper;
    FrameSceneBuilder builder;
    int next = 0;           // the first frame not shown
    bool unseen = false;    // frames were played without their look: none can be drawn
};

}  // namespace

// About what a copy of a world costs per body, walls included (studio_bench: 2.8 MiB for
// galton's 605 discs and 31 walls), bytes.
constexpr double world_bytes_per_body = 4600;

struct Playback::Impl {
    Impl(const scene::Scene& s, PlaybackDef d)
        : scene(s), def(d), every(d.checkpoint_every),
          timeline{s.video.fps, s.physics.rate, s.video.frame_count()},
          live(std::make_unique<State>(s, timeline)) {
        if (def.max_checkpoint_bytes > 0) {
            def.max_checkpoints = static_cast<int>(std::min<double>(
                def.max_checkpoints, def.max_checkpoint_bytes / checkpoint_bytes()));
        }
    }

    double checkpoint_bytes() const {
        const double bodies = static_cast<double>(scene.bodies.size() + scene.walls.size() + 1);
        return world_bytes_per_body * bodies + static_cast<double>(live->builder.trail_bytes());
    }

    // Steps the live state to `frame` (not yet shown), counting the steps.
    Status advance(int frame, const std::function<bool()>& should_stop) {
        const std::int64_t before = live->world.step_count();
        Status done = live->stepper.advance_to(frame, should_stop);
        steps_taken += live->world.step_count() - before;
        return done;
    }

    // Before showing `frame` (the live state's next): a checkpoint where one is due. Frame 0
    // needs none: the scene builds it again.
    void keep_checkpoint(int frame) {
        if (every <= 0 || frame == 0 || frame % every != 0 || def.max_checkpoints <= 0) return;
        if (!checkpoints.empty() && checkpoints.back()->next >= frame) return;
        checkpoints.push_back(std::make_unique<State>(*live));
        if (static_cast<int>(checkpoints.size()) <= def.max_checkpoints) return;
        // Over the bound: every other one goes, and they come half as often.
        every *= 2;
        std::erase_if(checkpoints, [&](const std::unique_ptr<State>& c) {
            return c->next % every != 0;
        });
    }

    // Back to the latest checkpoint at or before `frame`, or to t = 0.
    Status go_back(int frame) {
        if (def.checkpoint_every <= 0) {
            return Error{"frame " + std::to_string(frame) + " comes before frame " +
                         std::to_string(live->next) + ", shown already: frames go forward only"};
        }
        const auto after = std::upper_bound(
            checkpoints.begin(), checkpoints.end(), frame,
            [](int f, const std::unique_ptr<State>& c) { return f < c->next; });
        live = after == checkpoints.begin() ? std::make_unique<State>(scene, timeline)
                                            : std::make_unique<State>(**std::prev(after));
        return {};
    }

    // Forward to the latest checkpoint at or before `frame` when it is ahead of the live
    // state: a frame far ahead of where the playback went back to need not be played again.
    void skip_ahead(int frame) {
        const auto after = std::upper_bound(
            checkpoints.begin(), checkpoints.end(), frame,
            [](int f, const std::unique_ptr<State>& c) { return f < c->next; });
        if (after == checkpoints.begin()) return;
        const State& nearest = **std::prev(after);
        if (nearest.next > live->next) live = std::make_unique<State>(nearest);
    }

    const scene::Scene& scene;
    PlaybackDef def;
    int every;                                         // frames between checkpoints, now
    Timeline timeline;
    std::unique_ptr<State> live;
    std::vector<std::unique_ptr<State>> checkpoints;   // by frame, ascending
    std::int64_t steps_taken = 0;
};

Playback::Playback(const scene::Scene& scene, PlaybackDef def)
    : impl_(std::make_unique<Impl>(scene, def)) {}
Playback::~Playback() = default;
Playback::Playback(Playback&&) noexcept = default;
Playback& Playback::operator=(Playback&&) noexcept = default;

Expected<const render::FrameScene*> Playback::show(int frame, bool drawn,
                                                  const std::function<bool()>& should_stop) {
    Impl& p = *impl_;
    if (frame < 0 || frame >= p.timeline.frame_count) {
        return Error{"frame " + std::to_string(frame) + " is not in the clip, which has " +
                     std::to_string(p.timeline.frame_count) + " frames"};
    }
    if (frame < p.live->next) {
        if (Status back = p.go_back(frame); !back) return back.error();
    } else {
        p.skip_ahead(frame);
    }
    if (drawn && p.live->unseen) {
        return Error{"this playback played frames without their look and draws none"};
    }
    // Trails and the follow camera remember earlier frames: each is observed, in order.
    for (;;) {
        State& s = *p.live;
        const int f = s.next;
        if (Status advanced = p.advance(f, should_stop); !advanced) return advanced.error();
        p.keep_checkpoint(f);
        s.builder.respawned(s.world.respawns_applied());
        s.next = f + 1;
        if (f == frame && drawn) {
            if (s.builder.wants_debug()) {
                const auto joints = s.world.joints();
                s.builder.debug_state({.contacts = s.world.contact_points(),
                                       .sleeping = s.world.sleeping(),
                                       .joints = {joints.begin(), joints.end()}});
            }
            return &s.builder.build(f, s.world.bodies(), s.stepper.last_contacts());
        }
        s.builder.observe(f, s.world.bodies());
        if (f == frame) return nullptr;
    }
}

Status Playback::play(const PlayDef& def, const std::function<Status(const ShownFrame&)>& each) {
    Impl& p = *impl_;
    const int last = def.last < 0 ? p.timeline.frame_count - 1 : def.last;
    for (int frame = p.live->next; frame <= last; ++frame) {
        if (def.until && def.until()) return {};
        const render::FrameScene* view = nullptr;
        if (def.look) {
            const bool drawn = !def.drawn || def.drawn(frame);
            auto shown = show(frame, drawn, def.should_stop);
            if (!shown) return shown.error();
            view = *shown;
        } else {
            if (Status advanced = p.advance(frame, def.should_stop); !advanced) return advanced;
            p.live->next = frame + 1;
            p.live->unseen = true;
        }
        if (Status done = each({.frame = frame, .t = p.timeline.time_of_frame(frame),
                                .view = view});
            !done) {
            return done;
        }
    }
    return {};
}

std::span<const physics::BodyState> Playback::bodies() const {
    return impl_->live->world.bodies();
}

std::vector<physics::ContactEvent> Playback::take_events() {
    return impl_->live->stepper.take_events();
}

std::vector<std::string> Playback::take_warnings() { return impl_->live->stepper.take_warnings(); }

const physics::World& Playback::world() const { return impl_->live->world; }

int Playback::frame_count() const { return impl_->timeline.frame_count; }

double Playback::time_of_frame(int frame) const { return impl_->timeline.time_of_frame(frame); }
std::int64_t Playback::step_of_frame(int frame) const {
    return impl_->timeline.step_for_frame(frame);
}
double Playback::checkpoint_bytes() const { return impl_->checkpoint_bytes(); }

int Playback::next_frame() const { return impl_->live->next; }

std::size_t Playback::checkpoints() const { return impl_->checkpoints.size(); }

std::int64_t Playback::steps_taken() const { return impl_->steps_taken; }

}  // namespace discreel::job
