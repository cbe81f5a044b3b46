#pragma once
// Drives a physics world frame by frame along a Timeline, collecting the contact events that
// happened on the way. Shared by `render` and `simulate` so both see identical trajectories.
#include <vector>

#include "discreel/physics.hpp"
#include "timeline.hpp"

namespace discreel::app {

class FrameStepper {
public:
    FrameStepper(physics::World& world, Timeline timeline) : world_(world), timeline_(timeline) {}

    // Steps the world until it shows frame `frame` (frames must not go backwards).
    void advance_to(int frame) {
        const std::int64_t target = timeline_.step_for_frame(frame);
        while (world_.step_count() < target) {
            world_.step();
            for (const physics::ContactEvent& e : world_.take_events()) events_.push_back(e);
        }
    }

    // Events since the last call, in the order the world reported them.
    std::vector<physics::ContactEvent> take_events() { return std::exchange(events_, {}); }

private:
    physics::World& world_;
    Timeline timeline_;
    std::vector<physics::ContactEvent> events_;
};

}  // namespace discreel::app
