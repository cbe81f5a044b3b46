#pragma once
// What the solver stages of one substep share: the bodies, the contacts near enough to matter
// in this substep, and the substep's length.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "body.hpp"
#include "contact.hpp"
#include "geometry.hpp"

namespace discreel::physics::detail {

struct Substep {
    std::vector<Body>& bodies;
    std::size_t disc_count;
    const std::vector<Feature>& features;
    std::vector<Contact>& contacts;
    std::uint64_t contacts_version;            // changes whenever contact indices do
    std::uint64_t bodies_version;              // changes whenever a body's mass may have
    // Indices into contacts: those listed at the start of the substep, in pair order, then
    // those the impact stage adds when an impact speeds a body up (see ImpactResolver).
    std::vector<std::uint32_t>& active;
    const std::vector<double>& reach;          // metres per body: its travel bound when listed
    V2 gravity;                                // m/s^2
    double h;                                  // seconds

    V2 gravity_on(const Body& b) const { return b.falls() ? gravity : V2(V2::Zero()); }
    const Feature* feature_of(const Contact& c) const {
        return c.b >= disc_count ? &features[c.b - disc_count] : nullptr;
    }
};

// A pair already touching at the start of the substep (gap under this fraction of the smaller
// radius) is part of a heap or a row, not a flight ending in a collision: the impacts stage
// leaves it to the resting stage unless its bounce would show, and the disc solver's direct
// islands are made of such pairs.
inline constexpr double touching_gap = 0.005;

// Applies impulse p (N s) at the contact between a and b with normal n (b towards a):
// + p to a at -r_a n from its centre, - p to b at +r_b n from its centre.
inline void apply_impulse(Body& a, Body& b, const V2& n, const V2& p) {
    const V2 t = perp(n);
    const double pt = p.dot(t);
    a.v += p * a.inv_mass;
    b.v -= p * b.inv_mass;
    a.omega -= a.radius * pt * a.inv_inertia;
    b.omega -= b.radius * pt * b.inv_inertia;
}

inline double normal_mass_inverse(const Body& a, const Body& b) { return a.inv_mass + b.inv_mass; }
inline double tangent_mass_inverse(const Body& a, const Body& b) {
    return a.inv_mass + b.inv_mass + a.radius * a.radius * a.inv_inertia +
           b.radius * b.radius * b.inv_inertia;
}

}  // namespace discreel::physics::detail
