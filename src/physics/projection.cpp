// Positional correction. Overlap that the resting stage could not prevent (unconverged
// iterations in a tall pile, a squeeze it capped to avoid adding energy) is removed by moving
// positions only, so it never turns into velocity and kinetic energy.
#include <algorithm>

#include "discreel/physics.hpp"
#include "projection.hpp"

namespace discreel::physics::detail {
namespace {

// Fractions of the smaller radius (documented in docs/physics.md).
constexpr double tolerated_overlap = 5e-4;
constexpr double kept_overlap = 1e-4;

// push_apart past its cheap test (certainly_tolerated), which project() has just done for
// most pairs: it need not be repeated.
bool push_if_overlapping(Body& a, Body& b, const Feature* f, double smaller) {
    if (normal_mass_inverse(a, b) == 0.0) return false;
    const Proximity p = f ? disc_feature(a.x, a.radius, *f) : disc_disc(a.x, a.radius, b.x, b.radius);
    if (p.gap >= -tolerated_overlap * smaller) return false;
    // Weights by inverse mass, but with the ratio capped: a position correction moves no
    // momentum, and a light disc squeezed between a heavy one and a wall must not take the
    // whole push into the wall.
    constexpr double max_ratio = 4.0;
    double wa = a.inv_mass, wb = b.inv_mass;
    if (wa > 0.0 && wb > 0.0) {
        wa = std::min(wa, max_ratio * wb);
        wb = std::min(wb, max_ratio * wa);
    }
    const double push = 0.8 * (-p.gap - kept_overlap * smaller) / (wa + wb);
    a.x += p.normal * (push * wa);
    b.x -= p.normal * (push * wb);
    return true;
}

// Overlap under tolerated_overlap is left alone, and a push leaves kept_overlap (a fifth of
// it), so a pair of a pile that the unconverged resting stage lets sink a little every substep
// is pushed every few substeps rather than nudged in every one (with one threshold for both,
// most pairs of a pile would be). This test rules out most disc pairs without a square root.
bool certainly_tolerated(const Body& a, const Body& b, double smaller) {
    return certainly_farther((a.x - b.x).squaredNorm(), a.radius + b.radius,
                             -tolerated_overlap * smaller);
}

}  // namespace

bool PositionProjector::push_apart(Substep& s, const Contact& c) {
    Body& a = s.bodies[c.a];
    Body& b = s.bodies[c.b];
    const Feature* f = s.feature_of(c);
    const double smaller = std::min(a.radius, f ? a.radius : b.radius);
    if (!f && certainly_tolerated(a, b, smaller)) return false;
    return push_if_overlapping(a, b, f, smaller);
}

void PositionProjector::project(Substep& s, int iterations) {
    // Almost every pair of a pile is within the slop, so only the first sweep visits them all;
    // later sweeps revisit the pairs that overlapped, in the same order.
    overlapping_.clear();
    walls_.clear();
    Body* const bodies = s.bodies.data();
    for (const std::uint32_t index : s.active) {
        const Contact& c = s.contacts[index];
        bool pushed;
        if (c.b >= s.disc_count) {
            walls_.push_back(index);
            pushed = push_apart(s, c);
        } else {
            // push_apart with the bodies at hand: most pairs stop at the first test.
            Body& a = bodies[c.a];
            Body& b = bodies[c.b];
            const double smaller = std::min(a.radius, b.radius);
            if (certainly_tolerated(a, b, smaller)) continue;
            pushed = push_if_overlapping(a, b, nullptr, smaller);
        }
        if (pushed) overlapping_.push_back(index);
    }
    for (int it = 1; it < iterations; ++it) {
        for (const std::uint32_t index : overlapping_) push_apart(s, s.contacts[index]);
    }
    // Walls win: whatever the pairs did, no disc ends the substep in a wall. A light disc
    // squeezed between a fast heavy one and a wall (more bounces than the impacts stage can
    // time, a squeeze the resting stage cannot stop in a few iterations) would otherwise be
    // driven through it; the overlap it is left with against the heavy disc is resolved
    // over the next substeps.
    for (const std::uint32_t index : walls_) {
        const Contact& c = s.contacts[index];
        Body& a = s.bodies[c.a];
        const Proximity p = disc_feature(a.x, a.radius, *s.feature_of(c));
        if (p.gap < 0.0) a.x += p.normal * -p.gap;
    }
}

void PositionProjector::stop_at_wall(std::vector<Body>& bodies, std::size_t disc_count,
                                     const std::vector<Feature>& features, std::size_t i,
                                     const V2& start) const {
    // The impacts and resting stages only see the walls within a disc's reach at the start of
    // the substep, and the broad phase only those within its margin; a disc sent off much
    // faster (struck by a heavy one) can cross others unseen. Such a disc moved farther than
    // its reach, which is rare and cheap to test (contain_runaway); it is stopped where its
    // straight path first touched a wall it crossed, and bounces off it. Up to a thousandth of
    // its radius beyond the reach is let through (in a wall it saw not at all, it cannot be
    // deeper than that), so a pile's discs, nudged a little farther than they were going by
    // their neighbours, are not tested.
    Body& a = bodies[i];
    const double tolerance = 1e-3 * a.radius;
    const V2 path = a.x - start;
    for (std::size_t k = 0; k < features.size(); ++k) {
        const Feature& f = features[k];
        bool crossed;
        if (f.kind == Feature::Kind::plane) {
            crossed = f.b.dot(a.x - f.a) - a.radius < -tolerance;
        } else {
            // Into a segment, or through it and out on its other side.
            const V2 side = perp(f.b - f.a);
            crossed = disc_feature(a.x, a.radius, f).gap < -tolerance ||
                      (side.dot(start - f.a) * side.dot(a.x - f.a) < 0.0 &&
                       disc_feature(start, a.radius, f).gap > 0.0);
        }
        // A box holds what was inside it; a disc outside one is not pulled in.
        if (!crossed || !feature_applies(f, start)) continue;
        const auto hit =
            impact_disc_feature(Trajectory{start, path, V2::Zero()}, a.radius, f, 0.0, 1.0);
        if (!hit) continue;
        a.x = start + path * hit->t;
        const double vn = hit->normal.dot(a.v);
        if (vn < 0.0) {
            const Body& wall = bodies[disc_count + k];
            a.v -= hit->normal * ((1.0 + mixing_.restitution_of(a.restitution, wall.restitution)) * vn);
        }
    }
}

}  // namespace discreel::physics::detail
