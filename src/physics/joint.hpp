#pragma once
// The joints of the manifold solver (body_solver.hpp): each one a few constraint rows between
// two bodies (or a body and the world), solved in the contacts' velocity iterations, warm
// started from the last step, then held to their geometry by a position pass that moves
// positions only, so it adds no kinetic energy (Box2D v2.4's non-linear Gauss-Seidel).
//
// Rows per kind, each in velocities at the anchors:
// - revolute: the anchors' relative velocity (a 2x2 block), a motor and limits on the
//   relative turning speed;
// - distance: the relative velocity along the anchors' line; a rope only while taut (it may
//   shorten freely); a spring pushes by its stiffness from the step's start (explicit, which
//   keeps its frequency and energy; an implicit spring loses amplitude at every step) and damps
//   implicitly (stable at any damping);
// - prismatic: the velocity across the axis and the relative turning (a 2x2 block), a motor
//   and limits along the axis;
// - weld: the anchors' velocity and the turning (a 3x3 block), or the turning by a spring.
// A pin (a revolute joint without motor or limits) is solved as a row of the contacts'
// coloured, eight-wide solve (block_rows.hpp), in both stages; the other joints here, one by
// one in doubles.
// A row that would need a fast spring (2 pi f h above 1/2) is solved soft instead (Box2D's
// soft constraint), which stays stable for any frequency.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "block_rows.hpp"
#include "block_solver.hpp"
#include "discreel/physics.hpp"

namespace discreel::physics::detail {

class Joints {
public:
    Joints() = default;
    // The joints of `defs`, their anchors and axes fixed to the bodies where they are now.
    Joints(std::span<const JointDef> defs, const std::vector<Body>& bodies);

    bool empty() const { return joints_.empty(); }
    // Whether a joint holds body i.
    bool holds(std::uint32_t i) const { return i < held_.size() && held_[i] != 0; }
    // Whether contacts between bodies i < j are left out: a joint joins them without
    // `collide`.
    bool keeps_apart(std::uint32_t i, std::uint32_t j) const;
    // Calls f(a, b) for each joint between two bodies.
    template <class F>
    void for_each_pair(F&& f) const {
        for (const Joint& j : joints_) {
            if (j.a != world && j.b != world) f(j.a, j.b);
        }
    }
    // Calls f(a, b, works) for each joint, an end fixed to the world being `world`; `works`:
    // it has a motor or a spring, which may add energy (the rigid rows never do).
    template <class F>
    void for_each_joint(F&& f) const {
        for (const Joint& j : joints_) f(j.a, j.b, j.motor || j.spring);
    }
    static constexpr std::uint32_t world = 0xffffffffu;

    // The velocity stage: offsets and masses from the bodies' poses now, springs' pushes and
    // last step's impulses applied to `state` (the bodies' velocities, in their order).
    void prepare(const std::vector<Body>& bodies, std::span<BlockBody> state, double dt);
    // The pins' rows after prepare(), their warm start applied: into `out`, whose impulses
    // point at the joints' (valid until the joints change).
    void pins(std::vector<PinRef>& out);
    // Whether any joint is not a pin: solved by solve() and correct().
    bool narrow() const { return narrow_; }
    // One pass over the rows of every joint but the pins.
    void solve(std::span<BlockBody> state);

    // The position stage: one pass over every joint, each moved back to its geometry by moving
    // its bodies (only bodies that move), each move also added to moved[body]: metres and
    // radians. Returns the largest error it found (metres, or radians of an angle).
    struct Moved {
        V2 by = V2::Zero();
        double turn = 0;
    };
    double correct(std::vector<Body>& bodies, std::span<Moved> moved);
    // The pins' position rows: each pin with the displacement that closes it (at most
    // max_shift) as its target, into `out`.
    // Returns the widest gap, metres.
    double pin_gaps(const std::vector<Body>& bodies, std::vector<PinRef>& out);
    // The bodies a joint holds, ascending.
    std::span<const std::uint32_t> held_bodies() const { return held_list_; }

    // Each joint's anchors now and its reaction in the last step, in definition order.
    void states(const std::vector<Body>& bodies, std::vector<JointState>& out) const;

    // Below this error a joint is not moved by the position stage, metres (or radians).
    static constexpr double tolerance = 1e-6;
    // The most one position pass moves a joint's error by, metres and radians.
    static constexpr double max_shift = 0.2, max_turn = 0.14;

private:
    struct Joint {
        JointDef::Kind kind = JointDef::Kind::revolute;
        std::uint32_t a = world, b = world;
        V2 local_a = V2::Zero(), local_b = V2::Zero();   // anchors in each body's frame
        V2 axis = V2::UnitX();     // prismatic: unit, in A's frame
        double reference = 0;      // B's angle less A's at t = 0, radians
        double length = 0;         // distance, metres
        bool rope = false, collide = false;
        bool spring = false;
        double frequency = 0, damping = 0;   // Hz, ratio
        bool limited = false;
        double lower = 0, upper = 0;
        bool motor = false;
        double speed = 0, max_force = 0;
        bool pin = false;          // revolute without motor or limits: solved wide

        // The step's, from prepare():
        V2 ra = V2::Zero(), rb = V2::Zero();   // offsets from the centroids, metres
        V2 u = V2::UnitX(), n = V2::UnitY();   // distance: along; prismatic: axis, across
        double error = 0;          // distance: length less wanted; limits: the angle or travel
        std::array<double, 6> k{};   // the block's symmetric matrix (11 12 13 22 23 33)
        double mass = 0;           // the scalar row's (distance, prismatic axis), kg
        double angular_mass = 0;   // kg m^2
        double gamma = 0, bias = 0, soft_mass = 0;   // a soft or damped row's
        double push = 0;           // the spring's impulse applied at prepare, N s
        double dt = 0;
        // Accumulated impulses, N s (the angular ones N m s): warm start in, reaction out.
        V2 linear = V2::Zero();    // revolute, weld: the point's
        double across = 0;         // prismatic
        double along = 0;          // distance, prismatic: the rigid or damped row's
        double angular = 0;        // prismatic, weld
        double motor_impulse = 0, lower_impulse = 0, upper_impulse = 0;
    };
    BlockBody& at(std::span<BlockBody> state, std::uint32_t i) {
        return i == world ? ground_ : state[i];
    }
    void prepare_joint(Joint& j, const std::vector<Body>& bodies, std::span<BlockBody> state);
    void solve_joint(Joint& j, std::span<BlockBody> state);
    // One joint's motor and limit rows on a relative speed `w` (rad/s or m/s) along which an
    // impulse of 1 is applied by `apply(impulse)`.
    template <class Apply>
    static void solve_axis(Joint& j, double w, double mass, Apply&& apply);
    double correct_joint(const Joint& j, std::vector<Body>& bodies, std::span<Moved> moved);
    // Each held body's cosine and sine of its angle now, into turn_.
    void turn_all(const std::vector<Body>& bodies);
    // A body's pose: the world's end at the origin, and the cosine and sine of its angle, kept
    // in turn_ (one libm call per body, not per joint).
    struct Placed {
        V2 x = V2::Zero();
        double angle = 0, cos = 1, sin = 0;
        double inv_mass = 0, inv_inertia = 0;
    };
    Placed placed(const std::vector<Body>& bodies, std::uint32_t i) const;
    // v, in a body's frame, turned to the world's.
    static V2 turned(const Placed& p, const V2& v) {
        return {p.cos * v.x() - p.sin * v.y(), p.sin * v.x() + p.cos * v.y()};
    }
    // Moves body i by `by` and turns it by `turn` (its cached cosine and sine with it).
    void move(std::vector<Body>& bodies, std::span<Moved> moved, std::uint32_t i, const V2& by,
              double turn);

    std::vector<Joint> joints_;
    std::vector<unsigned char> held_;          // per body
    std::vector<std::uint32_t> held_list_;     // the bodies held, ascending
    std::vector<std::pair<double, double>> turn_;   // per body: cos, sin of its angle
    bool narrow_ = false;                      // a joint is not a pin
    std::vector<std::uint64_t> apart_;         // sorted a << 32 | b of joints without collide
    BlockBody ground_;                         // the world's end: never moves
};

}  // namespace discreel::physics::detail
