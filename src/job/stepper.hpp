#pragma once
// Drives a physics world frame by frame along a Timeline, collecting the contact events that
// happened on the way. Shared by `render` and `simulate` so both see identical trajectories.
#include <cmath>
#include <functional>
#include <span>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "discreel/expected.hpp"
#include "discreel/job.hpp"
#include "discreel/physics.hpp"
#include "discreel/scene.hpp"
#include "timeline.hpp"

namespace discreel::job {

class FrameStepper {
public:
    FrameStepper(physics::World& world, Timeline timeline, const scene::Scene& scene)
        : world_(world), timeline_(timeline), scene_(scene) {
        // Every moving body that starts inside a box of walls is expected to stay there.
        for (std::size_t w = 0; w < scene.walls.size(); ++w) {
            if (scene.walls[w].shape != scene::Wall::Shape::box) continue;
            for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
                if (!scene.bodies[i].is_static && inside(scene.walls[w], scene.bodies[i].position)) {
                    kept_.push_back({i, w});
                }
            }
        }
    }

    // A copy of `other`'s memory stepping `world`, a copy of other's world (a checkpoint).
    FrameStepper(const FrameStepper& other, physics::World& world)
        : world_(world), timeline_(other.timeline_), scene_(other.scene_), events_(other.events_),
          last_contact_(other.last_contact_), kept_(other.kept_), warnings_(other.warnings_) {}
    FrameStepper(const FrameStepper&) = delete;
    FrameStepper& operator=(const FrameStepper&) = delete;
    FrameStepper(FrameStepper&&) = delete;
    FrameStepper& operator=(FrameStepper&&) = delete;
    ~FrameStepper() = default;

    // Steps the world until it shows frame `frame` (frames must not go backwards). Fails, naming
    // the body and the time, once the world's state is no longer finite; fails with
    // stopped_message when `should_stop`, asked before every physics step, says so (a frame
    // may take many steps: a deadline or a cancellation must not wait for its end).
    [[nodiscard]] Status advance_to(int frame, const std::function<bool()>& should_stop = {}) {
        const std::int64_t target = timeline_.step_for_frame(frame);
        while (world_.step_count() < target && !world_.failure()) {
            if (should_stop && should_stop()) return Error{stopped_message};
            world_.step();
            for (const physics::ContactEvent& e : world_.take_events()) {
                touched(e);
                events_.push_back(e);
            }
        }
        if (const auto failure = world_.failure()) return describe(*failure);
        check_kept();
        return {};
    }

    static constexpr const char* stopped_message = cancelled_message;

    // Warnings since the last call: a body that left the box of walls it started in (once
    // per body), which the physics could not hold and must not lose without a word.
    std::vector<std::string> take_warnings() { return std::exchange(warnings_, {}); }

    // Events since the last call, in the order the world reported them.
    std::vector<physics::ContactEvent> take_events() { return std::exchange(events_, {}); }

    // Per body: the time of its latest contact so far (a sensor's overlaps are not contacts),
    // seconds; -infinity for none. Kept whatever takes the events.
    std::span<const double> last_contacts() const { return last_contact_; }

private:
    void touched(const physics::ContactEvent& e) {
        if (e.kind != physics::ContactEvent::Kind::contact) return;
        if (last_contact_.size() < world_.bodies().size()) {
            last_contact_.resize(world_.bodies().size(), -HUGE_VAL);
        }
        if (e.a < last_contact_.size()) last_contact_[e.a] = e.t;
        if (e.other_kind == physics::ContactEvent::Other::body && e.other < last_contact_.size()) {
            last_contact_[e.other] = e.t;
        }
    }

    Error describe(const physics::NonFiniteState& failure) const {
        std::ostringstream text;
        // A body of `bodies:` (a shape) is a body to its author, not a disc.
        const scene::Body& body = scene_.bodies[failure.body];
        text << "the simulation broke down at t = " << failure.t << " s: "
             << (body.shape ? "body '" : "disc '") << body.id
             << "' has a position, velocity or spin that is no longer a finite number; the "
                "scene asks for more than the solver can represent (docs/physics.md, Limits)";
        return Error{text.str()};
    }

    static bool inside(const scene::Wall& box, Vec2 p) {
        return p.x >= box.a.x && p.x <= box.b.x && p.y >= box.a.y && p.y <= box.b.y;
    }

    void check_kept() {
        const auto bodies = world_.bodies();
        for (auto it = kept_.begin(); it != kept_.end();) {
            if (inside(scene_.walls[it->wall], bodies[it->body].position)) {
                ++it;
                continue;
            }
            const scene::Body& body = scene_.bodies[it->body];
            std::ostringstream text;
            text << (body.shape ? "body '" : "disc '") << body.id << "' left the box of walls["
                 << it->wall << "] by t = " << world_.time()
                 << " s: the physics could not hold it there (docs/physics.md, Limits)";
            warnings_.push_back(text.str());
            it = kept_.erase(it);
        }
    }

    struct Kept {
        std::size_t body, wall;
    };

    physics::World& world_;
    Timeline timeline_;
    const scene::Scene& scene_;
    std::vector<physics::ContactEvent> events_;
    std::vector<double> last_contact_;   // per body, seconds
    std::vector<Kept> kept_;
    std::vector<std::string> warnings_;
};

}  // namespace discreel::job
