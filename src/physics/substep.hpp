#pragma once
// What the solver stages of one substep share: the bodies, the contacts near enough to matter
// in this substep, and the substep's length.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
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
    // Before the active contacts are listed.
    void begin(const Substep& s);
    // Each active contact as it is listed (k: its position in s.active), while it is in cache:
    // the first sweep visits only those that the cheap tests do not rule out.
    void screen(const Substep& s, const Contact& c, std::uint32_t k) {
        if (!surely_no_impact(s, c, slowest_impact(s, c, slow_))) screened_.push_back(k);
    }
    void resolve(Substep& s);

private:
    // A pair already touching at the start of the substep (gap under this fraction of the
    // smaller radius) is part of a heap or a row, not a flight ending in a collision.
    static constexpr double touching_gap = 0.005;
    // The swept test's answer for an active contact in a sweep, reused while neither body has
    // been struck since (the test is the costly part).
    struct FoundImpact {
        int pass = -1;             // the sweep it was computed in; -1: never
        std::optional<Impact> hit;
    };
    void list_contacts_of_bodies(const Substep& s);
    // The approach speed below which contact c is left to the resting stage in this substep.
    double slowest_impact(const Substep& s, const Contact& c, double slow) const {
        const Body& a = s.bodies[c.a];
        const bool wall = c.b >= s.disc_count;
        const double r = wall ? a.radius : std::min(a.radius, s.bodies[c.b].radius);
        if (c.gap > touching_gap * r) return slow;
        return wall ? settle_speed_[c.a] : std::min(settle_speed_[c.a], settle_speed_[c.b]);
    }
    // Cheap tests that rule out most pairs of a pile before the swept test.
    bool surely_no_impact(const Substep& s, const Contact& c, double slow) const {
        const Body& a = s.bodies[c.a];
        const Body& b = s.bodies[c.b];
        if (normal_mass_inverse(a, b) == 0.0) return true;  // two immovable bodies
        // Within the substep the approach speed grows by at most the relative acceleration
        // times h, so a pair slower than `slow` by that much cannot approach faster than `slow`.
        const V2 u = a.v - b.v;
        const bool same_fall = c.b < s.disc_count && a.falls() == b.falls();
        const double margin = slow - (same_fall ? 0.0 : gravity_step_);
        if (margin > 0.0 && u.squaredNorm() <= margin * margin) return true;
        if (!same_fall) return false;
        // No relative acceleration: a pair moving apart along its centre line never meets.
        return ((a.x + a.shift) - (b.x + b.shift)).dot(u) >= 0.0;
    }
    // The impact of contact c in this substep, if it approaches faster than slowest_impact.
    std::optional<Impact> find_impact(const Substep& s, const Contact& c, double slow) const;

    double slow_ = 0.0;                            // m/s, slower approaches are resting contact
    double gravity_step_ = 0.0;                    // m/s, |g| h
    std::vector<std::uint32_t> screened_;          // the first sweep's pairs, from screen()
    std::vector<double> settle_speed_;             // m/s per disc, see impacts.cpp
    double settle_h_ = 0.0;                        // s, the substep settle_speed_ is for
    std::vector<FoundImpact> found_;               // per active contact
    std::vector<std::pair<std::uint32_t, Impact>> first_hits_;  // the first sweep's, in order
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
    // Two doubles, one per row of a pair, in one SSE register (GCC vector extension).
    using Lanes = double __attribute__((vector_size(16)));
    // Two contacts of one colour (they share no moving body, so solving them side by side gives
    // the same result as one after the other), with what stays constant over the substep
    // precomputed. A lane without a contact points both ends at a scratch record, with zero
    // coefficients, so it computes zero impulses.
    struct RowPair {
        std::uint32_t a[2] = {0, 0}, b[2] = {0, 0};  // indices into velocities_
        Lanes normal_x = {}, normal_y = {};  // unit, from b towards a, at the predicted end
        Lanes bias = {};               // m/s, lower bound on n.(v_a - v_b)
        Lanes normal_mass = {};        // kg
        Lanes tangent_mass = {};       // kg
        Lanes friction = {};
        Lanes inv_mass_a = {}, inv_mass_b = {};  // 1/kg
        Lanes radius_a = {}, radius_b = {};      // m
        Lanes spin_a = {}, spin_b = {};          // r / I, 1/(kg m)
        Lanes normal_impulse = {};     // N s, accumulated
        Lanes tangent_impulse = {};    // N s, accumulated
    };
    // What the rows need of a body, in one cache line.
    struct Predicted {
        V2 end = V2::Zero();           // m, its position at the end without contact forces
        V2 v_begin = V2::Zero();       // m/s, see Body
        double radius = 0.0;           // m
        double inv_mass = 0.0;         // 1/kg
        double spin = 0.0;             // r / I, 1/(kg m)
    };
    // A contact to solve: its velocity records and colour (see contact_solver.cpp).
    struct Pending {
        std::uint32_t contact = 0;     // index into Substep::contacts
        std::uint32_t a = 0, b = 0;    // indices into velocities_
        unsigned colour = 0;
    };
    static constexpr std::uint32_t no_contact = ~std::uint32_t{0};
    // Rows whose discs have all 64 colours go to one last group, solved a row at a time.
    static constexpr unsigned overflow = 64;
    void colour_contacts(const Substep& s);
    void load(const RowPair& r, Lanes& avx, Lanes& avy, Lanes& aw, Lanes& bvx, Lanes& bvy,
              Lanes& bw) const;
    void store(const RowPair& r, const Lanes& avx, const Lanes& avy, const Lanes& aw,
               const Lanes& bvx, const Lanes& bvy, const Lanes& bw);

    std::vector<Predicted> predicted_;  // per body
    std::vector<Velocity> velocities_;  // per body, then one per row end on an immovable body
    std::vector<RowPair> rows_;         // grouped by colour: no two rows of one share a disc
    std::vector<std::uint32_t> row_contact_;  // per lane of rows_, index into contacts; or none
    std::vector<Pending> pending_;      // in active order
    std::vector<std::uint64_t> colours_used_;  // per disc, bit c: in a row of colour c
    std::vector<std::uint8_t> colour_of_;      // per contact
    std::uint64_t coloured_version_ = ~std::uint64_t{0};  // the contact list colour_of_ is for
    std::vector<std::uint32_t> colour_start_;
};

// Stage 3: overlap left by unconverged iterations is removed by moving positions only, so it
// never turns into velocity (and kinetic energy). A class only to keep its scratch array.
class PositionProjector {
public:
    void project(Substep& s, int iterations);
    // Puts back discs that crossed a wall the stages did not see: those that moved farther
    // than their reach (metres) from where they started the substep.
    void contain_runaways(Substep& s, const std::vector<V2>& start,
                          const std::vector<double>& reach);

private:
    // Moves a and b of contact c apart by most of their overlap; false if they hardly overlap.
    static bool push_apart(Substep& s, const Contact& c);
    std::vector<std::uint32_t> overlapping_;  // contacts pushed by the first sweep
    std::vector<std::uint32_t> walls_;        // active contacts with a wall
};

}  // namespace discreel::physics::detail
