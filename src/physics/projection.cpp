// Positional correction. Overlap that the resting stage could not prevent (unconverged
// iterations in a tall pile, a squeeze it capped to avoid adding energy) is removed by moving
// positions only, so it never turns into velocity and kinetic energy.
#include <algorithm>

#include "substep.hpp"

namespace discreel::physics::detail {

bool PositionProjector::push_apart(Substep& s, const Contact& c) {
    Body& a = s.bodies[c.a];
    Body& b = s.bodies[c.b];
    const double k = normal_mass_inverse(a, b);
    if (k == 0.0) return false;
    const Feature* f = s.feature_of(c);
    // A sliver of overlap is left alone, so touching pairs are not nudged every substep.
    const double slop = 1e-4 * std::min(a.radius, f ? a.radius : b.radius);
    if (!f && certainly_farther((a.x - b.x).squaredNorm(), a.radius + b.radius, -slop)) {
        return false;
    }
    const Proximity p = f ? disc_feature(a.x, a.radius, *f) : disc_disc(a.x, a.radius, b.x, b.radius);
    if (p.gap >= -slop) return false;
    const double push = 0.8 * (-p.gap - slop) / k;
    a.x += p.normal * (push * a.inv_mass);
    b.x -= p.normal * (push * b.inv_mass);
    return true;
}

void PositionProjector::project(Substep& s, int iterations) {
    // Almost every pair of a pile is within the slop, so only the first sweep visits them all;
    // later sweeps revisit the pairs that overlapped, in the same order.
    overlapping_.clear();
    for (const std::uint32_t index : s.active) {
        if (push_apart(s, s.contacts[index])) overlapping_.push_back(index);
    }
    for (int it = 1; it < iterations; ++it) {
        for (const std::uint32_t index : overlapping_) push_apart(s, s.contacts[index]);
    }
}

}  // namespace discreel::physics::detail
