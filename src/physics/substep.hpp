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
    const std::vector<std::uint32_t>& active;  // indices into contacts, in pair order
    V2 gravity;                                // m/s^2
    double h;                                  // seconds

    V2 gravity_on(const Body& b) const { return b.falls() ? gravity : V2(V2::Zero()); }
    const Feature* feature_of(const Contact& c) const {
        return c.b >= disc_count ? &features[c.b - disc_count] : nullptr;
    }
};

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

// Relative velocity of a's contact point against b's, along tangent perp(n).
inline double tangential_speed(const Body& a, const Body& b, const V2& n) {
    return perp(n).dot(a.v - b.v) - a.radius * a.omega - b.radius * b.omega;
}

inline double normal_mass_inverse(const Body& a, const Body& b) { return a.inv_mass + b.inv_mass; }
inline double tangent_mass_inverse(const Body& a, const Body& b) {
    return a.inv_mass + b.inv_mass + a.radius * a.radius * a.inv_inertia +
           b.radius * b.radius * b.inv_inertia;
}

// Stage 1: impacts. Every approaching pair that meets within the substep gets a restitution
// impulse at its time of impact, from the approach speed at that instant.
void resolve_impacts(Substep& s);

// Stage 2: resting contact. Sequential impulses with accumulated clamping and warm starting,
// acting like forces spread over the substep; then positions are integrated.
void solve_contacts(Substep& s, int iterations);

// Stage 3: overlap left by unconverged iterations is removed by moving positions only, so it
// never turns into velocity (and kinetic energy).
void project_positions(Substep& s, int iterations);

}  // namespace discreel::physics::detail
