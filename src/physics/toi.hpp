#pragma once
// Time of impact between two moving shapes by conservative advancement: the distance between
// their surfaces, d, cannot shrink faster than mu = (v_a - v_b) . n + |w_a| R_a + |w_b| R_b
// (n the unit direction between the closest points, R each body's bounding radius), so both
// can be moved on by (d - target) / mu without meeting; repeated, this converges on the first
// touch from the near side. Under translation alone the distance is a convex function of time
// and each advance is exact to first order; spin only makes the bound looser.
#include <optional>

#include "manifold.hpp"
#include "shape.hpp"

namespace discreel::physics::detail {

// A body's motion over part of a step: at time t0 it is at (x0, angle0) and moves at constant
// (v, omega) from there, as the solver's integration moves it.
struct Sweep {
    V2 x0 = V2::Zero();      // metres, the centroid at t0
    double angle0 = 0;       // radians at t0
    V2 v = V2::Zero();       // m/s
    double omega = 0;        // rad/s
    double t0 = 0;           // seconds into the step
    double bound = 0;        // metres, the farthest surface point from the centroid

    V2 x_at(double t) const { return x0 + v * (t - t0); }
    double angle_at(double t) const { return angle0 + omega * (t - t0); }
    Transform at(double t) const { return Transform::of(x_at(t), angle_at(t)); }
};

// The distance between two shapes' surfaces and the unit direction from A's closest point to
// B's; nothing when their cores overlap (then the contact solver owns the pair).
struct Distance {
    double distance = 0;           // metres; negative when the rounded surfaces overlap
    V2 normal = V2::UnitY();       // from A to B
    V2 point = V2::Zero();         // world, midway between the two surfaces' closest points
};
std::optional<Distance> distance(const Polygon& a, const Transform& xa, const Polygon& b,
                                 const Transform& xb);

struct TimeOfImpact {
    enum class Kind {
        apart,      // they do not come within `target` before `t_end`
        touching,   // within `target` (or cores overlapping) already at `t_begin`
        hit,        // within target + tolerance at `t`, nearer than that never before
    };
    Kind kind = Kind::apart;
    double t = 0;                  // seconds into the step
    double gap = 0;                // metres between the surfaces at t
};

struct ImpactQuery {
    double t_begin = 0, t_end = 0;   // seconds into the step
    double target = 0;               // metres between the surfaces to stop at
    double tolerance = 0;            // metres: within target + tolerance is a hit
    int max_iterations = 30;         // a hit at the last safe time once they are spent
};

TimeOfImpact time_of_impact(const Polygon& a, const Sweep& sa, const Polygon& b, const Sweep& sb,
                      const ImpactQuery& q);

// The radius of the largest circle about the centroid inside the shape, metres: how far the
// body can move before a speculative contact made at the start of a step may miss.
double inner_radius(const Polygon& shape);

}  // namespace discreel::physics::detail
