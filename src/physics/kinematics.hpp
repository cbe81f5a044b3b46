#pragma once
// Kinematic bodies (KinematicDef): held like a grabbed body (infinitely heavy to the others,
// unmoved by contacts or gravity) and put on their motion exactly at every step: a constant
// velocity and spin, or a path of poses. Each step starts with the body at its pose at t0 and
// the velocities that bring it to its pose at t1, which is where the step's end puts it, so
// rounding never accumulates: a windmill's angle at t is omega t to rounding.
#include <cstddef>
#include <vector>

#include "body.hpp"
#include "discreel/physics.hpp"

namespace discreel::physics::detail {

class Kinematics {
public:
    explicit Kinematics(const std::vector<BodyDef>& bodies);
    bool empty() const { return moving_.empty(); }
    // Takes hold of the kinematic bodies of `bodies`, at their pose at t = 0.
    void start(std::vector<Body>& bodies) const;
    // For the step [t0, t1]: each body at its pose at t0, with the velocities to its pose at t1.
    // True when some body's velocity changed or one was put somewhere else since the last step
    // (a looping path's new lap): the solver then forgets what it kept of the step before.
    bool begin_step(double t0, double t1, std::vector<Body>& bodies);
    // Each body exactly at its pose at t1.
    void end_step(double t1, std::vector<Body>& bodies) const;

private:
    struct Moving {
        std::size_t body = 0;
        KinematicDef def;          // a path starts at t = 0 (the body's start is prepended)
        V2 start = V2::Zero();     // metres, at t = 0
        double start_angle = 0;    // radians
    };
    struct Pose {
        V2 x;
        double angle = 0;
    };
    static Pose pose_at(const Moving& m, double t);
    std::vector<Moving> moving_;
    bool jumped_ = false;          // the last step ended by putting a body on a new lap
};

}  // namespace discreel::physics::detail
