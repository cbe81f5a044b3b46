#pragma once
// What the solver stages of one substep share: the bodies, the contacts near enough to matter
// in this substep, and the substep's length.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "body.hpp"
#include "contact.hpp"
#include "discreel/clones.hpp"
#include "disc_islands.hpp"
#include "geometry.hpp"
#include "simd.hpp"

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

// Stage 1: impacts. Every approaching pair that meets within the substep gets a restitution
// impulse at its time of impact, from the approach speed at that instant. A class only to keep
// its scratch arrays between substeps.
class ImpactResolver {
public:
    // Before the active contacts are listed.
    void begin(const Substep& s);
    // The active contacts of a block as they are listed (listed: their indices into
    // s.contacts; first: the first one's position in s.active), while they are in cache: the
    // first predictions cover only those that the cheap tests do not rule out.
    void screen(const Substep& s, std::span<const std::uint32_t> listed, std::size_t first) {
        const Contact* const contacts = s.contacts.data();
        std::uint64_t* const position = position_.data();
        const std::uint64_t stamp = listing_ << 32;
        for (std::size_t j = 0; j < listed.size(); ++j) {
            const Contact& c = contacts[listed[j]];
            const auto k = static_cast<std::uint32_t>(first + j);
            position[listed[j]] = stamp | k;
            if (!surely_no_impact(s, c, slowest_impact(s, c, slow_))) screened_.push_back(k);
        }
    }
    // Impacts, except of the contacts in the direct islands.
    void resolve(Substep& s, const DiscIslands& islands);

private:
    static constexpr std::uint64_t never = ~std::uint64_t{0};  // a stamp none has
    // A predicted impact of active contact k, valid while neither body has been struck since
    // the prediction (their strike counts then).
    struct Event {
        Impact hit;
        std::uint32_t k = 0;
        std::uint32_t strikes_a = 0, strikes_b = 0;
    };
    // Heap order: the earliest impact first, ties by contact position (pair order), so that
    // the order of events never depends on the order of predictions.
    static bool later(const Event& x, const Event& y) {
        return x.hit.t > y.hit.t || (x.hit.t == y.hit.t && x.k > y.k);
    }
    void list_contacts_of_bodies(const Substep& s);
    // Contact k's position in s.active, if it is active in this substep.
    bool active_position(std::uint32_t contact, std::uint32_t& k) const {
        const std::uint64_t p = position_[contact];
        k = static_cast<std::uint32_t>(p);
        return (p >> 32) == listing_;
    }
    // The approach speed below which contact c is left to the resting stage in this substep.
    double slowest_impact(const Substep& s, const Contact& c, double slow) const {
        const Body& a = s.bodies[c.a];
        const bool wall = c.b >= s.disc_count;
        // The pair's smaller disc decides, for the gap and for both speeds (they grow with r).
        const std::uint32_t smaller = wall || a.radius <= s.bodies[c.b].radius ? c.a : c.b;
        const double r = s.bodies[smaller].radius;
        if (c.gap > touching_gap * r) return slow;
        const Settle& settle = settle_[smaller];
        // Slower than bounce / e, its bounce would not show (with e = 0, never: only the
        // closing bound is left).
        const double e = c.restitution;
        const double visible =
            settle.bounce < e * settle.closing ? settle.bounce / e : settle.closing;
        return std::max(slow, visible);
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
    // Applies event e's impulse at its time; false if it no longer holds (one of its bodies
    // was struck since it was predicted).
    bool apply(Substep& s, const Event& e);
    // After body i was struck at time t: its reach over the substep, grown to what its new
    // velocity can travel, lists its pairs of the broad phase that are now within reach.
    void widen_reach(Substep& s, std::uint32_t i, double t);
    // Predicts the impacts of body i's active pairs (each once per event) into the heap.
    void predict_pairs_of(const Substep& s, const DiscIslands& islands, std::uint32_t i,
                          double slow, std::size_t& spent);
    void push(const Substep& s, std::uint32_t k, const Impact& hit) {
        const Contact& c = s.contacts[s.active[k]];
        events_.push_back(Event{hit, k, s.bodies[c.a].strikes, s.bodies[c.b].strikes});
        std::push_heap(events_.begin(), events_.end(), later);
    }

    double slow_ = 0.0;                            // m/s, slower approaches are resting contact
    double gravity_step_ = 0.0;                    // m/s, |g| h
    std::vector<std::uint32_t> screened_;          // the first predictions' pairs, from screen()
    // Per disc, what a touching pair's slowest timed approach is made of (see impacts.cpp).
    struct Settle {
        double bounce = 0.0;   // m/s, leaving this fast it rises visible_bounce radii
        double closing = 0.0;  // m/s, closes closing_step radii in a substep
    };
    std::vector<Settle> settle_;
    double settle_h_ = 0.0;                        // s, the substep settle_ is for
    // Which contacts of the broad phase's list each body is in, rebuilt with the list, so that
    // an impact re-predicts only its bodies' pairs.
    std::vector<std::uint32_t> contacts_of_start_;  // per body, into contacts_of_
    std::vector<std::uint32_t> contacts_of_;       // indices into s.contacts, grouped by body
    std::uint64_t listed_version_ = ~std::uint64_t{0};  // the contact list contacts_of_ is for
    // Per contact: (listing_ << 32) | its position in s.active, for the contacts listed in
    // the listing numbered listing_ (one per substep); older entries are stale.
    std::vector<std::uint64_t> position_;
    std::uint64_t listing_ = 0;
    std::vector<std::uint32_t> fill_;
    std::vector<Event> events_;                    // min-heap by later()
    // Per active contact: the event whose re-predictions last covered it, numbered over all
    // substeps so that no substep has to reset it.
    std::vector<std::uint64_t> predicted_;
    std::uint64_t events_done_ = 0;
    // Per body: its reach (m) grown by impacts, valid where reach_listing_ is listing_.
    std::vector<double> reach_;
    std::vector<std::uint64_t> reach_listing_;
};

// The resting stage's colouring (contact_solver.cpp): greedy, in list order, each contact
// taking the lowest colour that no earlier contact of its discs has, so that no two contacts of
// one colour share a disc (a wall feature, b >= disc_count, takes no colour: no row changes
// it). A contact whose discs already have all overflow_colour colours between them gets
// overflow_colour, which promises nothing. colour_of: per contact; used: scratch, per disc,
// bit c set once it is in a contact of colour c.
inline constexpr unsigned overflow_colour = 64;
void colour_greedily(std::span<const Contact> contacts, std::size_t disc_count,
                     std::vector<std::uint64_t>& used, std::vector<std::uint8_t>& colour_of);

// Stage 2: resting contact. Sequential impulses with accumulated clamping and warm starting,
// acting like forces spread over the substep; then positions are integrated. A class only to
// keep its scratch arrays between substeps.
class ContactSolver {
public:
    // Before the active contacts are listed.
    void begin(const Substep& s);
    // The active contacts of a block as they are listed (their indices into s.contacts), while
    // they are in cache: each one's colour is counted and it is queued for the row build.
    void list(const Substep& s, std::span<const std::uint32_t> listed) {
        const Body* const bodies = s.bodies.data();
        const Contact* const contacts = s.contacts.data();
        const std::uint8_t* const colour_of = colour_of_.data();
        std::uint32_t* const colour_start = colour_start_.data();
        for (const std::uint32_t index : listed) {
            const Contact& c = contacts[index];
            const bool a_moves = bodies[c.a].inv_mass != 0.0;
            const bool b_moves = bodies[c.b].inv_mass != 0.0;
            if (!a_moves && !b_moves) continue;  // two immovable bodies: nothing to solve
            const unsigned colour = colour_of[index];
            ++colour_start[colour + 1];
            Pending p{index, c.a, c.b, colour};
            // A row end on an immovable body gets its own velocity record, appended after the
            // bodies' (all zeros: it never changes, and its velocity is folded into the row),
            // so that rows on one wall do not chain through its record.
            if (!a_moves) p.a = fresh_copy(s);
            if (!b_moves) p.b = fresh_copy(s);
            pending_.push_back(p);
        }
    }
    void solve(Substep& s, int iterations);
    // After the listing, before the impacts stage: plans the direct islands
    // (disc_islands.hpp), whose contacts the impacts stage leaves to solve().
    void plan_islands(Substep& s);
    const DiscIslands& islands() const { return islands_; }

private:
    // Four doubles (see simd.hpp): the row build's geometry, half a block at a time, in
    // double precision. Where this file is not built for AVX, GCC aligns the type to 16 bytes
    // only, so the structs holding it ask for the 32 that AVX loads need.
    using Lanes = simd::Double4;
    // Eight floats, one per row of a block: one AVX register in the AVX2 build of solve_rows,
    // two SSE (or NEON) registers in the baseline one.
    using Floats = simd::Float8;
    using Quad = simd::Float4;  // one velocity record
    static constexpr unsigned width = 8;  // rows per block, the lanes of Floats
    static constexpr unsigned half = 4;   // the lanes of Lanes
    // What the iterations change of a body: the change of its velocity over the iterations,
    // dv.x, dv.y (m/s) and r d(omega) (m/s), with its inverse mass in mass units (see
    // mass_unit_), so that a block gathers each of its records with one aligned load (see
    // load()). The velocities themselves stay in the bodies, in doubles; a row folds its bodies'
    // start velocities into its constants, in doubles, so the floats carry only corrections.
    struct alignas(16) Velocity {
        Quad packed = {};
    };
    // Eight contacts of one colour (they share no moving body, so solving them side by side gives
    // the same result as one after the other), with what stays constant over the substep
    // precomputed in doubles and rounded once. A lane without a contact points both ends at a
    // scratch record, with zero coefficients, so it computes zero impulses.
    struct alignas(32) RowBlock {
        std::uint32_t a[width] = {}, b[width] = {};  // indices into velocities_
        Floats normal_x = {}, normal_y = {};  // unit, from b towards a, at the predicted end
        Floats bias = {};            // m/s, lower bound on n.(dv_a - dv_b)
        Floats slip = {};            // m/s, the contact points' tangential velocity at the start
        Floats normal_mass = {};     // mass units
        Floats tangent_mass = {};    // mass units
        Floats friction = {};
        Floats normal_impulse = {};  // mass units m/s, accumulated
        Floats tangent_impulse = {}; // mass units m/s, accumulated
    };
    // What the row build needs of a body, in one cache line of two records that a half block
    // gathers with a transpose each (see build_rows()).
    struct alignas(32) Predicted {
        Lanes motion = {};  // end x, y (m, where it ends up without contact forces); v_begin x, y
        Lanes now = {};     // v x, y (m/s, after gravity), omega (rad/s), radius (m)
    };
    // A contact to solve: its velocity records and colour (see contact_solver.cpp).
    struct Pending {
        std::uint32_t contact = 0;     // index into Substep::contacts
        std::uint32_t a = 0, b = 0;    // indices into velocities_
        unsigned colour = 0;
    };
    // Rows whose discs have all 64 colours go to one last group, solved a row at a time.
    static constexpr unsigned overflow = overflow_colour;
    void colour_contacts(const Substep& s);
    std::uint32_t fresh_copy(const Substep& s) {
        return static_cast<std::uint32_t>(s.bodies.size() + copies_++);
    }
    // The code that runs on whole blocks, on x86-64 built for AVX2 and for the baseline, the
    // one the CPU can run chosen at load time (DISCREEL_CLONES): the warm start and the
    // iterations over rows_, and the row build.
    DISCREEL_CLONES void solve_rows(int iterations);
    DISCREEL_CLONES void build_rows(const Substep& s, double inv_h);
    [[gnu::always_inline]] static void transpose(const Lanes& r0, const Lanes& r1,
                                                 const Lanes& r2, const Lanes& r3, Lanes& c0,
                                                 Lanes& c1, Lanes& c2, Lanes& c3);
    // Inlined, so that they are built for the caller's instruction set.
    [[gnu::always_inline]] void load(const std::uint32_t (&records)[width], Floats& x,
                                     Floats& y, Floats& u, Floats& inv_mass) const;
    [[gnu::always_inline]] void store(const std::uint32_t (&records)[width], const Floats& x,
                                      const Floats& y, const Floats& u, const Floats& inv_mass);

    std::vector<Predicted> predicted_;  // per body
    // Per body, then one per row end on an immovable body, then the empty lanes' scratch one.
    std::vector<Velocity> velocities_;
    std::vector<RowBlock> rows_;        // grouped by colour: no two rows of one share a disc
    std::vector<Pending> pending_;      // in active order
    std::vector<std::uint32_t> lane_of_;  // per pending row, its lane in rows_
    std::vector<std::uint32_t> pending_of_lane_;  // per lane of rows_, index into pending_
    std::vector<std::uint32_t> empty_lanes_;      // lanes of rows_ without a row
    std::uint32_t copies_ = 0;           // velocity records after the bodies', one per row end
                                         // on an immovable body (all zeros)
    // What a contact's rows need of its bodies' masses, which only change with the contact
    // list or a throw: two divisions per row less in every substep.
    struct Masses {
        float normal = 0.0F;           // mass units
        float tangent = 0.0F;          // mass units
    };
    void compute_masses(const Substep& s);
    std::vector<Masses> masses_;       // per contact
    // The rows' masses and impulses are in units of this many kg, a power of two near the
    // heaviest moving disc's mass (so scaling by it is exact), which keeps them far inside the
    // range of a float whatever the masses of a scene.
    double mass_unit_ = 1.0;
    std::uint64_t massed_contacts_ = ~std::uint64_t{0};  // the versions masses_ is for
    std::uint64_t massed_bodies_ = ~std::uint64_t{0};
    std::vector<std::uint64_t> colours_used_;  // per disc, bit c: in a row of colour c
    std::vector<std::uint8_t> colour_of_;      // per contact

    // The direct islands (disc_islands.hpp), and what their rows need of the row build in
    // double precision, per lane of rows_ (written only while the masses are far apart; the
    // impulse is filled in after the iterations).
    DiscIslands islands_;
    std::vector<IslandRow> geometry_;
    std::vector<std::uint32_t> row_contacts_;  // per pending row, its contact (plan_islands)
    std::vector<IslandRow> island_rows_;
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
    static void contain_runaways(Substep& s, const std::vector<V2>& start,
                                 const std::vector<double>& reach) {
        for (std::size_t i = 0; i < s.disc_count; ++i) {
            contain_runaway(s.bodies, s.disc_count, s.features, i, start[i], reach[i]);
        }
    }
    // The same for disc i alone (each disc is handled on its own), so that the last substep of
    // a step can leave it to the world's pass over the discs at the end of the step.
    static void contain_runaway(std::vector<Body>& bodies, std::size_t disc_count,
                                const std::vector<Feature>& features, std::size_t i,
                                const V2& start, double reach) {
        // Up to a thousandth of its radius beyond the reach is let through (see projection.cpp).
        const Body& a = bodies[i];
        const V2 path = a.x - start;
        const double unseen = reach + 1e-3 * a.radius;
        if (path.squaredNorm() <= unseen * unseen || !a.falls()) return;  // held: scripted
        stop_at_wall(bodies, disc_count, features, i, start);
    }

private:
    // Moves a and b of contact c apart by most of their overlap; false if they hardly overlap.
    static bool push_apart(Substep& s, const Contact& c);
    // contain_runaway's rare case: disc i moved farther than its reach from `start`.
    static void stop_at_wall(std::vector<Body>& bodies, std::size_t disc_count,
                             const std::vector<Feature>& features, std::size_t i, const V2& start);
    std::vector<std::uint32_t> overlapping_;  // contacts pushed by the first sweep
    std::vector<std::uint32_t> walls_;        // active contacts with a wall
};

}  // namespace discreel::physics::detail
