#pragma once
// The disc solver's first stage of a substep (impacts.cpp).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "disc_islands.hpp"
#include "substep.hpp"

namespace discreel::physics::detail {

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
    // Discs were replaced, perhaps by ones of other radii: the settle speeds are found again.
    void bodies_replaced() { settle_.clear(); }

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

}  // namespace discreel::physics::detail
