#pragma once
// Scripted interaction. A flick sets a body's velocity at the first step starting at or after
// its time. A grab holds its body from t = 0: the body becomes kinematic (infinitely heavy to
// the others) and is carried in a straight line from where it starts to the first waypoint,
// arriving at that waypoint's time, so the body is where the path says from then on and never
// jumps; it then moves along the straight segments between waypoints with the path's
// velocity, and is released at the first step starting at or after the last waypoint with the
// `release` velocity, or the last segment's. Throws on static bodies do nothing.
#include <cstddef>
#include <vector>

#include "body.hpp"
#include "discreel/physics.hpp"

namespace discreel::physics::detail {

class Throws {
public:
    explicit Throws(const std::vector<ThrowDef>& defs);

    // Takes hold of the grabbed discs in `bodies`, their state at t = 0; called once, before
    // the first step.
    void start(std::vector<Body>& bodies);

    // For the step [t0, t1]: applies due flicks, starts and ends grabs, and gives held discs
    // their position at t0 and the velocity that brings them to their path point at t1.
    // True when it changed a body.
    bool begin_step(double t0, double t1, std::vector<Body>& bodies);
    // Puts held discs exactly on their paths at t1 (integration would round).
    void end_step(double t1, std::vector<Body>& bodies) const;

private:
    enum class Stage { waiting, holding, done };
    struct Throw {
        ThrowDef def;   // a grab's path starts at t = 0 (the disc's start is prepended)
        Stage stage = Stage::waiting;
    };
    std::vector<Throw> throws_;
};

}  // namespace discreel::physics::detail
