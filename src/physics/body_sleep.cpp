// Sleeping islands (body_solver.hpp). A settled pile costs a step of full work per physics step
// for nothing: every body at rest, every contact solved to the same impulses. An island (bodies
// joined by contacts with points, walls not joining) that presses on a wall or a fixed body and
// whose bodies have all moved slower than `sleep_speed` for `sleep_after` seconds is put to
// sleep: its bodies stop exactly, drop out of the solve and keep their contacts parked, as they
// were, for the warm start and the events when they wake. An island wakes whole when an awake
// body comes within the reach of a contact of one of its bodies (the pair's manifold in the
// step would have a point), when a throw moves one of them, or when one of them is replaced. Every decision depends on the state alone, in index
// order: same input, same sleep.
#include <algorithm>
#include <cmath>

#include "body_solver.hpp"

namespace discreel::physics::detail {
namespace {

bool by_pair(const auto& x, const auto& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; }

}  // namespace

bool BodySolver::wake_flagged(std::vector<Body>& bodies, const V2& kick) {
    bool woke = false;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        Body& b = bodies[i];
        if (!b.asleep || !waking_[b.island]) continue;
        b.asleep = false;
        still_for_[i] = 0;
        if (b.inv_mass > 0) b.v += kick;
        --asleep_count_;
        woke = true;
    }
    std::fill(waking_.begin(), waking_.end(), 0);
    return woke;
}

bool BodySolver::wake_moved(std::vector<Body>& bodies) {
    if (asleep_count_ == 0) return true;
    waking_.assign(bodies.size(), 0);
    bool stirring = false;
    // Moved by a throw (a flick's velocity, a grab) or by an impact in the last step.
    for (const Body& b : bodies) {
        if (b.asleep && (b.motion == Motion::held || b.v != V2::Zero() || b.omega != 0)) {
            waking_[b.island] = 1;
        }
        stirring = stirring || stirs(b);
    }
    return wake_flagged(bodies, V2::Zero()) || stirring;
}

void BodySolver::count_parked() {
    const auto touched = [](const PairContact& pc) { return pc.touched; };
    parked_touching_ = static_cast<std::size_t>(std::count_if(parked_.begin(), parked_.end(), touched));
}

void BodySolver::wake_reached(std::vector<Body>& bodies, const V2& gravity, double dt) {
    if (asleep_count_ == 0) {
        // Every island woke (a throw moved one of each): their contacts rejoin.
        unpark(bodies);
        return;
    }
    // Again while islands wake, as a woken island may reach others; begin_step left the woken
    // bodies out, so they start the step as the awake ones did.
    for (;;) {
        for (const std::uint64_t key : pairs_) {
            const auto i = static_cast<std::uint32_t>(key >> 32);
            const auto j = static_cast<std::uint32_t>(key & 0xffffffffu);
            const Body& a = bodies[i];
            const Body& b = bodies[j];
            if (!a.asleep && !b.asleep) continue;
            // The other one is awake and can move: the step lists no other pairs.
            const std::uint32_t island = (a.asleep ? a : b).island;
            if (waking_[island]) continue;
            if (collide(shapes_[i], transforms_[i], shapes_[j], transforms_[j], margin_[i] + margin_[j])
                    .count > 0) {
                waking_[island] = 1;
            }
        }
        if (!wake_flagged(bodies, gravity * dt)) break;
        list_pairs(bodies);
    }
    unpark(bodies);
}

void BodySolver::unpark(const std::vector<Body>& bodies) {
    // A parked contact joins two bodies of one island, or one and a wall: it rejoins the
    // step's, in pair order, once its island is awake.
    const std::size_t before = contacts_.size();
    std::erase_if(parked_, [&](PairContact& pc) {
        if (!stirs(bodies[pc.a]) && !stirs(bodies[pc.b])) return false;
        contacts_.push_back(std::move(pc));
        return true;
    });
    if (contacts_.size() == before) return;
    std::inplace_merge(contacts_.begin(), contacts_.begin() + static_cast<std::ptrdiff_t>(before),
                       contacts_.end(), by_pair<PairContact, PairContact>);
    count_parked();
}

void BodySolver::fall_asleep(std::vector<Body>& bodies, double dt) {
    if (!def_.sleep) return;
    const std::size_t n = bodies.size();
    const double slow = def_.sleep_speed;
    for (std::size_t i = 0; i < n; ++i) {
        const Body& b = bodies[i];
        if (b.asleep) continue;
        // A jointed body stays awake: its joints' other bodies would have to sleep with it.
        const bool still = b.motion == Motion::dynamic && b.v.squaredNorm() < slow * slow &&
                           std::abs(b.omega) * b.radius < slow &&
                           !joints_.holds(static_cast<std::uint32_t>(i));
        still_for_[i] = still ? still_for_[i] + dt : 0;
    }
    // The islands: union-find by the lower index, over contacts with points between bodies
    // that move (a held body joins its island and keeps it awake).
    parent_.resize(n);
    lightest_.resize(n);   // here: the shortest time at rest in the island, s
    for (std::size_t i = 0; i < n; ++i) {
        parent_[i] = static_cast<std::uint32_t>(i);
        lightest_[i] = still_for_[i];
    }
    // Only an island that rests on something fixed (a wall, a static body) sleeps: one that
    // floats free, however slowly, keeps its momentum (stopped, a box gliding at 5 mm/s in
    // zero gravity halted before the box it was about to strike). Resting means pressing: a
    // contact that only sees the wall coming (no impulse this step) does not ground.
    const auto joins = [&](std::uint32_t i) { return bodies[i].motion != Motion::fixed; };
    grounded_.assign(n, 0);
    for (const PairContact& pc : contacts_) {
        if (!joins(pc.a) || !joins(pc.b)) {
            if (pc.touched) grounded_[pc.a] = grounded_[pc.b] = 1;
            continue;
        }
        if (const auto merged = unite(pc.a, pc.b)) {
            lightest_[merged->first] = std::min(lightest_[merged->first], lightest_[merged->second]);
        }
    }
    for (std::size_t i = 0; i < n; ++i) {
        grounded_[root(static_cast<std::uint32_t>(i))] |= grounded_[i];
    }
    bool fell = false;
    for (std::size_t i = 0; i < n; ++i) {
        Body& b = bodies[i];
        if (b.asleep || b.motion != Motion::dynamic) continue;
        const std::uint32_t r = root(static_cast<std::uint32_t>(i));
        if (lightest_[r] < def_.sleep_after || grounded_[r] == 0) continue;
        b.asleep = true;
        b.island = r;
        b.v = V2::Zero();
        b.omega = 0;
        ++asleep_count_;
        fell = true;
    }
    if (!fell) return;
    contacts_kept_ = false;
    const std::size_t before = parked_.size();
    std::erase_if(contacts_, [&](PairContact& pc) {
        if (stirs(bodies[pc.a]) || stirs(bodies[pc.b])) return false;
        parked_.push_back(std::move(pc));
        return true;
    });
    std::inplace_merge(parked_.begin(), parked_.begin() + static_cast<std::ptrdiff_t>(before),
                       parked_.end(), by_pair<PairContact, PairContact>);
    count_parked();
}

void BodySolver::forget(std::vector<Body>& bodies, std::size_t first, std::size_t last) {
    fat_pairs_.invalidate();
    contacts_kept_ = false;
    // The bodies that replace them have shapes of their own, and have not rested yet.
    fit(bodies.size());
    for (std::size_t i = first; i < last; ++i) {
        inner_[i] = -1;
        still_for_[i] = 0;
    }
    waking_.assign(bodies.size(), 0);
    for (std::size_t i = first; i < last; ++i) {
        if (bodies[i].asleep) waking_[bodies[i].island] = 1;
    }
    // Woken at rest: the next step's begin_step gives them gravity.
    wake_flagged(bodies, V2::Zero());
    const auto replaced = [&](const PairContact& pc) {
        return (pc.a >= first && pc.a < last) || (pc.b >= first && pc.b < last);
    };
    std::erase_if(contacts_, replaced);
    std::erase_if(parked_, replaced);
    // A sensor's overlaps with the old bodies go with them: a new body inside a sensor begins.
    std::erase_if(sensing_, [&](std::uint64_t key) {
        const auto a = static_cast<std::size_t>(key >> 32), b = static_cast<std::size_t>(key & 0xffffffffu);
        return (a >= first && a < last) || (b >= first && b < last);
    });
    unpark(bodies);
    count_parked();
}

std::size_t BodySolver::touching() const { return touches_.size() + parked_touching_; }

void BodySolver::contact_points(const std::vector<Body>& bodies,
                                std::vector<ContactPoint>& out) const {
    for (const std::vector<PairContact>* list : {&contacts_, &parked_}) {
        for (const PairContact& pc : *list) {
            if (!pc.touched) continue;
            const V2& n = pc.contact.normal;
            for (int k = 0; k < pc.contact.count; ++k) {
                const BlockPoint& p = pc.contact.points[static_cast<std::size_t>(k)];
                const V2 at = bodies[pc.a].x + p.ra;
                out.push_back({.a = pc.a,
                               .other_kind = ContactEvent::Other::body,
                               .other = pc.b,
                               .point = {at.x(), at.y()},
                               .normal = {n.x(), n.y()},
                               .force = p.normal_impulse});
            }
        }
    }
}

}  // namespace discreel::physics::detail
