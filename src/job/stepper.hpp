#pragma once
// Drives a physics world frame by frame along a Timeline, collecting the contact events that
// happened on the way. Shared by `render` and `simulate` so both see identical trajectories.
#include <sstream>
#include <vector>

#include "discreel/expected.hpp"
#include "discreel/physics.hpp"
#include "discreel/scene.hpp"
#include "timeline.hpp"

namespace discreel::job {

class FrameStepper {
public:
    FrameStepper(physics::World& world, Timeline timeline, const scene::Scene& scene)
        : world_(world), timeline_(timeline), scene_(scene) {}

    // Steps the world until it shows frame `frame` (frames must not go backwards). Fails, naming
    // the disc and the time, once the world's state is no longer finite.
    [[nodiscard]] Status advance_to(int frame) {
        const std::int64_t target = timeline_.step_for_frame(frame);
        while (world_.step_count() < target && !world_.failure()) {
            world_.step();
            for (const physics::ContactEvent& e : world_.take_events()) events_.push_back(e);
        }
        if (const auto failure = world_.failure()) return describe(*failure);
        return {};
    }

    // Events since the last call, in the order the world reported them.
    std::vector<physics::ContactEvent> take_events() { return std::exchange(events_, {}); }

private:
    Error describe(const physics::NonFiniteState& failure) const {
        std::ostringstream text;
        text << "the simulation broke down at t = " << failure.t << " s: disc '"
             << scene_.discs[failure.disc].id
             << "' has a position, velocity or spin that is no longer a finite number; the "
                "scene asks for more than the solver can represent (docs/physics.md, Limits)";
        return Error{text.str()};
    }

    physics::World& world_;
    Timeline timeline_;
    const scene::Scene& scene_;
    std::vector<physics::ContactEvent> events_;
};

}  // namespace discreel::job
