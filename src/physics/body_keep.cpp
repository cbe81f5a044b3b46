// Contacts kept from one step to the next (body_solver.hpp, BodySolverDef::keep_contacts). A
// resting pile's pairs and manifolds are the same step after step: its bodies move by
// micrometres, each manifold is only moved with its bodies (the recycling of manifold_of), and
// the pair search, the matching of each pair with its last contact and the copying of every
// contact cost more than the solve they feed. While no body has moved or turned by half the
// bounds under which a manifold is recycled since the contacts were made, and none will at its
// speed now, the step takes the last step's contacts as they are and moves each point's
// anchors with its bodies, as the push-out does within a step: its separation follows from
// how far the two anchors moved along the normal. One body moving anywhere makes every
// contact again: the bound is the world's, not an island's.
#include <algorithm>
#include <cmath>

#include "body_solver.hpp"

namespace discreel::physics::detail {

bool BodySolver::keeps_contacts(const std::vector<Body>& bodies, double dt) const {
    // Sleeping islands park and unpark contacts, which the pair search looks after.
    if (!def_.keep_contacts || !contacts_kept_ || asleep_count_ != 0 || !parked_.empty() ||
        bodies.empty() || travelled_.size() != bodies.size()) {
        return false;
    }
    // Each body may move half what a pair may before its manifold is made again, for the
    // smallest body it could touch; and half a pair's speculative distance, which is what
    // the fat boxes of the pair search were grown by at least (no pair can have come within
    // reach unlisted).
    const double smallest = *std::min_element(inner_.begin(), inner_.end());
    const double travel_limit =
        0.5 * std::min(def_.recycle_travel * smallest, 0.5 * def_.speculative);
    const double turn_limit = 0.5 * def_.recycle_turn;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Body& b = bodies[i];
        const double turn = turned_since_[i] + std::abs(b.omega) * dt;
        const double travel = travelled_[i] + (b.v.norm() + std::abs(b.omega) * b.radius) * dt;
        if (turn > turn_limit || travel > travel_limit) return false;
    }
    return true;
}

void BodySolver::move_contacts(const std::vector<Body>& bodies, double dt) {
    // fresh_ holds what contacts_ held before the last step: its buffers are reused.
    std::swap(fresh_, contacts_);
    for (PairContact& pc : fresh_) {
        BlockContact& c = pc.contact;
        const BlockBody va = velocity_of(bodies[pc.a]), vb = velocity_of(bodies[pc.b]);
        for (int k = 0; k < c.count; ++k) {
            const auto q = static_cast<std::size_t>(k);
            BlockPoint& p = c.points[k];
            // moved_ and spin_ are the last step's motion, its push-out's included. The rows
            // keep the offsets they were built with (the bodies turned by under a milliradian
            // since), as Box2D's substeps do: their masses need not be computed again.
            V2 ra, rb;
            const double separation = separation_now(pc, k, ra, rb);
            pc.anchors[q] = {ra, rb, separation};
            p.target = separation > 0 ? -separation / dt : 0;
            pc.approach[q] = normal_velocity(c, p, va, vb);
        }
    }
}

void BodySolver::count_motion(const std::vector<Body>& bodies, bool kept) {
    const std::size_t n = bodies.size();
    if (!kept) {
        travelled_.assign(n, 0.0);
        turned_since_.assign(n, 0.0);
    }
    for (std::size_t i = 0; i < n; ++i) {
        travelled_[i] += moved_[i].norm() + std::abs(turned_[i]) * bodies[i].radius;
        turned_since_[i] += std::abs(turned_[i]);
    }
    // A body swept for its impacts moved in ways the contacts did not follow.
    contacts_kept_ = std::find(fast_.begin(), fast_.end(), 1) == fast_.end();
}

}  // namespace discreel::physics::detail
