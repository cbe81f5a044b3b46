#pragma once
// What the solver stages of one substep share: the bodies, the contacts near enough to matter
// in this substep, and the substep's length.
#include <cstddef>
#include <cstdint>
#include <optional>
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

inline double normal_mass_inverse(const Body& a, const Body& b) { return a.inv_mass + b.inv_mass; }
inline double tangent_mass_inverse(const Body& a, const Body& b) {
    return a.inv_mass + b.inv_mass + a.radius * a.radius * a.inv_inertia +
           b.radius * b.radius * b.inv_inertia;
}

// Stage 1: impacts. Every approaching pair that meets within the substep gets a restitution
// impulse at its time of impact, from the approach speed at that instant. A class only to keep
// its scratch arrays between substeps.
class ImpactResolver {
public:
    void resolve(Substep& s);

private:
    // The swept test's answer for an active contact in a sweep, reused while neither body has
    // been struck since (the test is the costly part).
    struct FoundImpact {
        int pass = -1;             // the sweep it was computed in; -1: never
        std::optional<Impact> hit;
    };
    void list_contacts_of_bodies(const Substep& s);
    // The approach speed below which contact c is left to the resting stage in this substep.
    double slowest_impact(const Substep& s, const Contact& c, double slow) const;
    // The impact of contact c in this substep, if it approaches faster than slowest_impact.
    std::optional<Impact> find_impact(const Substep& s, const Contact& c, double slow) const;

    std::vector<double> settle_speed_;             // m/s per disc, see impacts.cpp
    std::vector<FoundImpact> found_;               // per active contact
    std::vector<int> queued_;                      // per active contact: last sweep listing it
    std::vector<std::uint32_t> contacts_of_start_;  // per body, into contacts_of_
    std::vector<std::uint32_t> contacts_of_;       // active contact positions, grouped by body
    std::vector<std::uint32_t> fill_;
    std::vector<std::uint32_t> changed_;           // bodies changed in the current sweep
    std::vector<std::uint32_t> lowered_;           // bodies whose next_impact was set
    std::vector<std::uint32_t> candidates_;        // this sweep's pairs, sorted
    std::vector<std::uint32_t> queue_;             // min-heap of pairs still to visit
};

// Stage 2: resting contact. Sequential impulses with accumulated clamping and warm starting,
// acting like forces spread over the substep; then positions are integrated. A class only to
// keep its scratch arrays between substeps.
class ContactSolver {
public:
    void solve(Substep& s, int iterations);

private:
    struct Velocity {
        V2 v = V2::Zero();         // m/s
        double omega = 0.0;        // rad/s
    };
    // One contact, with what stays constant over the substep precomputed.
    struct Row {
        std::uint32_t a = 0, b = 0;    // body indices
        std::uint32_t contact = 0;     // index into Substep::contacts
        V2 normal = V2::UnitY();       // unit, from b towards a, at the predicted end
        double bias = 0.0;             // m/s, lower bound on n.(v_a - v_b)
        double normal_mass = 0.0;      // kg
        double tangent_mass = 0.0;     // kg
        double friction = 0.0;
        double inv_mass_a = 0.0, inv_mass_b = 0.0;    // 1/kg
        double radius_a = 0.0, radius_b = 0.0;        // m
        double spin_a = 0.0, spin_b = 0.0;            // r / I, 1/(kg m)
        double normal_impulse = 0.0;   // N s, accumulated
        double tangent_impulse = 0.0;  // N s, accumulated
    };
    std::vector<Velocity> velocities_;  // per body
    std::vector<Row> rows_;
};

// Stage 3: overlap left by unconverged iterations is removed by moving positions only, so it
// never turns into velocity (and kinetic energy). A class only to keep its scratch array.
class PositionProjector {
public:
    void project(Substep& s, int iterations);

private:
    // Moves a and b of contact c apart by most of their overlap; false if they hardly overlap.
    static bool push_apart(Substep& s, const Contact& c);
    std::vector<std::uint32_t> overlapping_;  // contacts pushed by the first sweep
};

}  // namespace discreel::physics::detail
