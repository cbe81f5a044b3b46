#include "broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "discreel/physics.hpp"

namespace discreel::physics::detail {
namespace {

// How far a body can travel in one step from its current velocity (see widen_threatened for
// the velocity an impact can give it).
double reach(const Body& b, double dt, double gravity) {
    if (!b.moves()) return 0.0;
    const double fall = b.falls() ? 0.5 * gravity * dt * dt : 0.0;
    return b.v.norm() * dt + fall;
}

// A quarter radius of slack: big enough that a settled pile rarely rebuilds, small enough that
// the pair list stays close to the actual contacts.
double base_margin(const Body& b) { return 0.25 * b.radius; }

}  // namespace

bool BroadPhase::update(const std::vector<Body>& bodies, std::size_t disc_count,
                        const std::vector<Feature>& features, double dt, double gravity,
                        std::vector<Contact>& contacts, std::optional<bool> known_valid) {
    if (built_ && (known_valid ? *known_valid : still_valid(bodies, disc_count, dt, gravity))) {
        return false;
    }
    rebuild(bodies, disc_count, features, dt, gravity, contacts);
    return true;
}

void BroadPhase::forget(std::size_t first, std::size_t last, std::vector<Contact>& contacts) {
    built_ = false;
    const bool listed = listed_.size() == contacts.size();
    std::size_t kept = 0;
    for (std::size_t i = 0; i < contacts.size(); ++i) {
        const Contact& c = contacts[i];
        if ((c.a >= first && c.a < last) || (c.b >= first && c.b < last)) continue;
        if (listed) listed_[kept] = listed_[i];
        contacts[kept++] = c;
    }
    contacts.resize(kept);
    // A list this broad phase did not build keeps no history (rebuild's merge).
    if (listed) {
        listed_.resize(kept);
    } else {
        listed_.clear();
    }
}

bool BroadPhase::still_valid(const std::vector<Body>& bodies, std::size_t disc_count, double dt,
                             double gravity) const {
    for (std::size_t i = 0; i < disc_count; ++i) {
        const Body& b = bodies[i];
        if (b.moves() && !keeps(b, i, dt, gravity)) return false;
    }
    return true;
}

bool BroadPhase::widen_threatened(const std::vector<Body>& bodies, double dt, double gravity) {
    // A disc struck by a faster one leaves at up to its own speed plus 2 m_o / (m_o + m) times
    // the other's (the normal part of its velocity is mixed with the other's, e <= 1): its
    // margin covers a step at that speed, so that what it can reach after the impact is listed
    // for the rest of the step. (Impacts within one step that chain through several discs are
    // caught from the next step on.)
    bool widened = false;
    for (const std::uint64_t key : pairs_) {
        const auto i = static_cast<std::uint32_t>(key >> 32);
        const auto j = static_cast<std::uint32_t>(key & 0xffffffffu);
        for (const auto& [struck, other] : {std::pair{i, j}, std::pair{j, i}}) {
            const Body& s = bodies[struck];
            const Body& o = bodies[other];
            if (s.inv_mass == 0.0) continue;  // fixed or held: no impact moves it
            const double share = o.inv_mass == 0.0 ? 1.0 : s.inv_mass / (s.inv_mass + o.inv_mass);
            const double needed =
                base_margin(s) + reach(s, dt, gravity) + 2.0 * share * o.v.norm() * dt;
            if (needed > margin_[struck]) {
                margin_[struck] = needed;
                widened = true;
            }
        }
    }
    return widened;
}

void BroadPhase::find_disc_pairs(const std::vector<Body>& bodies, std::size_t disc_count) {
    circles_.resize(disc_count);
    for (std::size_t i = 0; i < disc_count; ++i) {
        circles_[i] = GridCircle{bodies[i].x, bodies[i].radius + margin_[i], bodies[i].moves()};
    }
    pairs_.clear();
    grid_.find(circles_, pairs_);
}

void BroadPhase::rebuild(const std::vector<Body>& bodies, std::size_t disc_count,
                         const std::vector<Feature>& features, double dt, double gravity,
                         std::vector<Contact>& contacts) {
    built_ = true;
    anchor_.resize(disc_count);
    margin_.resize(disc_count);
    for (std::size_t i = 0; i < disc_count; ++i) {
        anchor_[i] = bodies[i].x;
        // Four steps' travel: a falling crowd would otherwise rebuild every few steps, and the
        // substep's own reach test keeps the extra pairs out of the solver stages.
        margin_[i] = base_margin(bodies[i]) + 4.0 * reach(bodies[i], dt, gravity);
    }
    find_disc_pairs(bodies, disc_count);
    if (widen_threatened(bodies, dt, gravity)) find_disc_pairs(bodies, disc_count);

    for (std::size_t i = 0; i < disc_count; ++i) {
        const Body& b = bodies[i];
        if (!b.moves()) continue;
        for (std::size_t f = 0; f < features.size(); ++f) {
            if (!feature_applies(features[f], b.x)) continue;
            if (disc_feature(b.x, b.radius, features[f]).gap > margin_[i]) continue;
            pairs_.push_back(pair_key(static_cast<std::uint32_t>(i),
                                      static_cast<std::uint32_t>(disc_count + f)));
        }
    }
    sort_pair_keys(pairs_, bodies.size(), sorted_, digit_count_);

    // Merge with the previous list (both sorted) so surviving pairs keep their history. Its
    // pairs are kept as keys too (listed_), which the merge compares without loading a contact.
    merged_.clear();
    merged_.reserve(pairs_.size());
    // (A list this broad phase did not build has no history to keep.)
    const std::size_t old_count = listed_.size() == contacts.size() ? listed_.size() : 0;
    std::size_t old = 0;
    for (const std::uint64_t key : pairs_) {
        while (old < old_count && listed_[old] < key) ++old;
        // Built in place: a contact built on the stack and then copied would be read back
        // before its stores complete, which stalls on store forwarding.
        if (old < old_count && listed_[old] == key) {
            merged_.push_back(contacts[old]);
            continue;
        }
        const auto a = static_cast<std::uint32_t>(key >> 32);
        const auto b = static_cast<std::uint32_t>(key & 0xffffffffu);
        Contact& c = merged_.emplace_back();
        c.a = a;
        c.b = b;
        c.restitution = mixing_.restitution_of(bodies[a].restitution, bodies[b].restitution);
        c.friction = mixing_.friction_of(bodies[a].friction, bodies[b].friction);
    }
    listed_.swap(pairs_);
    contacts.swap(merged_);
}

}  // namespace discreel::physics::detail
