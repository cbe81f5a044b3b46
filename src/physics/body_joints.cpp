// The joints' stages of the manifold solver's step (body_solver.hpp); their rows are solved
// with the contacts' (body_velocities.cpp, joint.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "body_solver.hpp"

namespace discreel::physics::detail {

void BodySolver::correct_joints(std::vector<Body>& bodies) {
    // Positions only, as the contacts' push-out: the pins' rows (pin_position_passes of them),
    // then passes that move every other joint back to its geometry with its bodies' true
    // masses until the worst is within tolerance. The moves are the step's motion too (the
    // contacts' separations follow them), and count as pushes.
    joint_moves_.resize(bodies.size());
    const auto record_moves = [&] {
        for (const std::uint32_t i : joints_.held_bodies()) {
            Joints::Moved& m = joint_moves_[i];
            if (m.by == V2::Zero() && m.turn == 0) continue;
            moved_[i] += m.by;
            turn_body(i, m.turn);
            ++pushes_;
            pushed_at_[i] = pushes_;
            m = {};
        }
    };
    correct_pins(bodies);
    record_moves();
    for (int pass = 0; joints_.narrow() && pass < def_.joint_position_passes; ++pass) {
        const double worst = joints_.correct(bodies, joint_moves_);
        record_moves();
        if (worst <= Joints::tolerance) break;
    }
    joint_poses_.clear();
    for (const std::uint32_t i : joints_.held_bodies()) {
        joint_poses_.emplace_back(bodies[i].x, bodies[i].angle);
    }
}

bool BodySolver::joints_moved(const std::vector<Body>& bodies) const {
    const std::span<const std::uint32_t> held = joints_.held_bodies();
    if (joint_poses_.size() != held.size()) return true;
    for (std::size_t k = 0; k < held.size(); ++k) {
        const Body& b = bodies[held[k]];
        if (b.x != joint_poses_[k].first || b.angle != joint_poses_[k].second) return true;
    }
    return false;
}

void BodySolver::correct_pins(std::vector<Body>& bodies) {
    // The pins' gaps, closed by the coloured rows on displacements (m) and turns (rad) for
    // velocities, with the offsets of the poses now: linear in the turns, which are small
    // (closing a 1 mm gap turns a 0.5 m arm by 2 mrad; the anchor is then off by r turn^2 / 2,
    // 1e-6 m, the joints' tolerance, and the next step's pass takes it up).
    if (joints_.pin_gaps(bodies, pin_gaps_) <= Joints::tolerance || pin_gaps_.empty()) return;
    pin_moves_.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        pin_moves_[i] = {V2::Zero(), 0, bodies[i].inv_mass, bodies[i].inv_inertia};
    }
    pin_positions_.build({}, pin_gaps_, pin_moves_);
    pin_positions_.solve(def_.pin_position_passes);
    pin_positions_.finish({}, pin_gaps_, pin_moves_);
    for (const std::uint32_t i : joints_.held_bodies()) {
        const BlockBody& m = pin_moves_[i];
        if (m.v == V2::Zero() && m.omega == 0) continue;
        bodies[i].x += m.v;
        bodies[i].angle += m.omega;
        joint_moves_[i].by += m.v;
        joint_moves_[i].turn += m.omega;
    }
}

void BodySolver::limit_joint_energy(const std::vector<Body>& bodies) {
    // Rigid joints do no work: solved exactly, a group of bodies that joints and contacts
    // join leaves the rows with at most the kinetic energy it arrived with. Solved by passes
    // that have not settled (the tail of a whipping chain), the warm start can leave it more
    // (a 40-link chain gained 13 J between two frames). Such a group's velocities are scaled
    // back to its arrival's energy: about the group's centre of mass when nothing fixed holds
    // it (its momentum kept), whole when a fixed body or the world does; the joints' rows stay
    // satisfied (they are linear in the velocities). A group that a motor, a spring or a held
    // body works on is left as solved.
    const auto n = static_cast<std::uint32_t>(bodies.size());
    const auto moves = [&](std::uint32_t i) { return i < n && bodies[i].inv_mass > 0; };
    const auto held = [&](std::uint32_t i) { return i < n && bodies[i].motion == Motion::held; };
    std::vector<std::uint32_t>& group = cluster_;
    group.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) group[i] = i;
    const auto find = [&](std::uint32_t i) { return root_in(group, i); };
    const auto join = [&](std::uint32_t a, std::uint32_t b) {
        const std::uint32_t ra = find(a), rb = find(b);
        group[std::max(ra, rb)] = std::min(ra, rb);
    };
    // Per body, then per root: a joint holds it, something fixed does, something works on it.
    constexpr unsigned char jointed = 1, fixed = 2, worked = 4;
    std::vector<unsigned char>& flags = cluster_held_;
    flags.assign(n, 0);
    // An end of a joint or contact whose other end does not move.
    const auto held_by = [&](std::uint32_t body, std::uint32_t other) {
        flags[body] |= held(other) ? worked : fixed;
    };
    joints_.for_each_joint([&](std::uint32_t a, std::uint32_t b, bool works) {
        if (moves(a) && moves(b)) join(a, b);
        for (const auto& [body, other] : {std::pair{a, b}, std::pair{b, a}}) {
            if (!moves(body)) continue;
            flags[body] |= jointed | (works ? worked : 0);
            if (!moves(other)) held_by(body, other);
        }
    });
    for (const PairContact& pc : fresh_) {
        if (moves(pc.a) && moves(pc.b)) {
            join(pc.a, pc.b);
        } else if (moves(pc.a) || moves(pc.b)) {
            held_by(moves(pc.a) ? pc.a : pc.b, moves(pc.a) ? pc.b : pc.a);
        }
    }
    // Per root: kinetic energy arrived and solved (in the group's frame), mass, momentum.
    constexpr std::size_t fields = 5;
    std::vector<double>& sums = energy_;
    sums.assign(fields * n, 0.0);
    for (std::uint32_t i = 0; i < n; ++i) {
        if (!moves(i)) continue;
        const std::uint32_t r = find(i);
        flags[r] |= flags[i];
        const double mass = 1 / bodies[i].inv_mass;
        sums[fields * r + 2] += mass;
        sums[fields * r + 3] += mass * state_[i].v.x();
        sums[fields * r + 4] += mass * state_[i].v.y();
    }
    const auto limited = [&](std::uint32_t r) {
        return (flags[r] & (jointed | worked)) == jointed;
    };
    const auto frame_of = [&](std::uint32_t r) -> V2 {
        if ((flags[r] & fixed) != 0) return V2::Zero();
        return V2(sums[fields * r + 3], sums[fields * r + 4]) / sums[fields * r + 2];
    };
    for (std::uint32_t i = 0; i < n; ++i) {
        if (!moves(i) || !limited(find(i))) continue;
        const std::uint32_t r = find(i);
        sums[fields * r] += kinetic_energy(arrived_[i], frame_of(r));
        sums[fields * r + 1] += kinetic_energy(state_[i], frame_of(r));
    }
    for (std::uint32_t i = 0; i < n; ++i) {
        if (!moves(i) || !limited(find(i))) continue;
        const std::uint32_t r = find(i);
        const double arrived = sums[fields * r], solved = sums[fields * r + 1];
        if (!(solved > arrived * (1 + 1e-12))) continue;
        const V2 frame = frame_of(r);
        const double scale = std::sqrt(arrived / solved);
        state_[i].v = frame + scale * (state_[i].v - frame);
        state_[i].omega *= scale;
    }
}

}  // namespace discreel::physics::detail
