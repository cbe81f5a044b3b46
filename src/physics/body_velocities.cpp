// The velocity stages of the manifold solver's step (body_solver.hpp): the direct islands, the
// warm start and the coloured rows' iterations with the blocks of larger islands between them;
// then, once the positions have moved, the bounces.
#include <algorithm>
#include <cmath>

#include "body_solver.hpp"
#include "discreel/physics.hpp"

namespace discreel::physics::detail {
namespace {

void store(Body& b, const BlockBody& s) {
    b.v = s.v;
    b.omega = s.omega;
}

}  // namespace

void BodySolver::solve_velocities(std::vector<Body>& bodies) {
    state_.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) state_[i] = velocity_of(bodies[i]);
    // Islands of masses far apart, and bounces, are checked against the kinetic energy their
    // bodies came with (below, and in bounce).
    arrived_ = state_;
    for_each_group(islands_, island_start_, [&](std::span<const IslandContact> island) {
        if (direct_solver_.velocities(island, state_)) return;
        // Not settled within its pivots (a few times in 2 s of a crowd of boxes 1e4 apart):
        // the island iterates like the others.
        for (const IslandContact& ic : island) direct_[ic.pair] = 0;
    });
    // The rows prepare themselves and apply their own warm start as they are built
    // (block_rows.hpp); a block's is prepared here and is in the velocities its solve starts
    // from. An even world has neither blocks nor warm starts to keep.
    if (far_islands_) warm_.resize(fresh_.size());
    for (std::size_t i = 0; far_islands_ && i < fresh_.size(); ++i) {
        PairContact& pc = fresh_[i];
        if (direct_[i]) continue;
        if (blocked_[i]) {
            prepare_block(pc.contact, state_[pc.a], state_[pc.b]);
            apply_totals(pc, 1);
        }
        for (int k = 0; k < pc.contact.count; ++k) {
            const BlockPoint& p = pc.contact.points[k];
            warm_[i][static_cast<std::size_t>(k)] = {p.normal_impulse, p.tangent_impulse};
        }
    }
    rows_.clear();
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        if (direct_[i] || blocked_[i]) continue;
        const PairContact& pc = fresh_[i];
        rows_.push_back(RowRef{pc.a, pc.b, &fresh_[i].contact, pc.as_solved});
    }
    // The joints' warm start goes into the velocities the rows are built from; pins are rows
    // of the coloured solve, after the contacts in each pass.
    pins_.clear();
    if (!joints_.empty()) {
        joints_.prepare(bodies, state_, dt_);
        joints_.pins(pins_);
    }
    block_rows_.build(rows_, pins_, state_);
    for (int it = 0; it < def_.iterations; ++it) {
        block_rows_.solve(def_.joint_passes);
        if (blocks_.empty() && !joints_.narrow()) continue;
        // A block's impulses are taken back out and solved again, together, in doubles; the
        // other joints' rows are solved in doubles too, after the contacts and pins of the
        // pass.
        block_rows_.flush(state_);
        for_each_group(blocks_, block_start_, [&](std::span<const IslandContact> block) {
            for (const IslandContact& ic : block) apply_totals(*pair_of(ic), -1);
            if (direct_solver_.velocities(block, state_)) return;
            for (const IslandContact& ic : block) apply_totals(*pair_of(ic), 1);
        });
        for (int pass = 0; joints_.narrow() && pass < def_.joint_passes; ++pass) {
            joints_.solve(state_);
        }
        block_rows_.reload(state_);
    }
    block_rows_.finish(rows_, pins_, state_);
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        fresh_[i].as_solved = direct_[i] == 0 && blocked_[i] == 0;
    }
    if (far_islands_) solve_gainers_again(bodies);
    if (!joints_.empty()) limit_joint_energy(bodies);
    for (std::size_t i = 0; i < bodies.size(); ++i) store(bodies[i], state_[i]);
}

void BodySolver::solve_gainers_again(const std::vector<Body>& bodies) {
    // The warm start applies last step's impulses whole; iterations take back what is not
    // needed now only by a fraction set by the masses' ratio per sweep, so between masses far
    // apart it can launch a light body (heavy_light_bench: a rise of 11 % of a crowd's energy
    // between two frames at 1e2, 1e6 times at 1e6). An island of masses direct_mass_ratio or
    // more apart that its iterations left with more kinetic energy than it came with (beyond
    // 1e-9 of it, rounding) is solved again from its arrival with half the warm start, and if
    // it still gains, with none (cold, the crowd's overlap grew by half). An island a moving
    // held body pushes is left as it is (the push is work done on it), and so is a direct one
    // (its solve is exact).
    const std::size_t n = bodies.size();
    const auto moves = [&](std::uint32_t i) { return bodies[i].inv_mass > 0; };
    const auto pushed = [&](std::uint32_t i) { return !moves(i) && state_[i].v != V2::Zero(); };
    // Marks in again_ the islands that gained (1), and those never solved again (2).
    const auto gained = [&] {
        arrived_energy_.assign(n, 0.0);
        solved_energy_.assign(n, 0.0);
        for (std::uint32_t i = 0; i < n; ++i) {
            if (!moves(i)) continue;
            arrived_energy_[root(i)] += kinetic_energy(arrived_[i]);
            solved_energy_[root(i)] += kinetic_energy(state_[i]);
        }
        again_.assign(n, 0);
        for (std::size_t i = 0; i < fresh_.size(); ++i) {
            const PairContact& pc = fresh_[i];
            if (pushed(pc.a)) again_[root(pc.b)] = 2;
            if (pushed(pc.b)) again_[root(pc.a)] = 2;
            if (direct_[i]) again_[island_of(pc, bodies)] = 2;
        }
        // Its rows are the contacts' only: an island a joint holds is left as solved.
        for (std::uint32_t i = 0; i < n; ++i) {
            if (joints_.holds(i)) again_[root(i)] = 2;
        }
        bool any = false;
        for (std::uint32_t r = 0; r < n; ++r) {
            if (parent_[r] != r || again_[r] != 0) continue;
            if (lightest_[r] < def_.direct_mass_ratio * heaviest_[r]) continue;
            again_[r] = solved_energy_[r] > (1 + 1e-9) * arrived_energy_[r];
            any = any || again_[r] == 1;
        }
        return any;
    };
    for (const double share : {0.5, 0.0}) {
        if (!gained()) return;
        for (std::uint32_t i = 0; i < n; ++i) {
            if (moves(i) && again_[root(i)] == 1) state_[i] = arrived_[i];
        }
        rows_.clear();
        for (std::size_t i = 0; i < fresh_.size(); ++i) {
            PairContact& pc = fresh_[i];
            if (again_[island_of(pc, bodies)] != 1) continue;
            for (int k = 0; k < pc.contact.count; ++k) {
                const auto [normal, tangent] = warm_[i][static_cast<std::size_t>(k)];
                pc.contact.points[k].normal_impulse = share * normal;
                pc.contact.points[k].tangent_impulse = share * tangent;
            }
            if (blocked_[i]) {
                apply_totals(pc, 1);
            } else {
                rows_.push_back(RowRef{pc.a, pc.b, &pc.contact});
            }
        }
        block_rows_.build(rows_, state_);
        for (int it = 0; it < def_.iterations; ++it) {
            block_rows_.solve();
            if (blocks_.empty()) continue;
            block_rows_.flush(state_);
            for_each_group(blocks_, block_start_, [&](std::span<const IslandContact> block) {
                if (again_[island_of(*pair_of(block.front()), bodies)] != 1) return;
                for (const IslandContact& ic : block) apply_totals(*pair_of(ic), -1);
                if (direct_solver_.velocities(block, state_)) return;
                for (const IslandContact& ic : block) apply_totals(*pair_of(ic), 1);
            });
            block_rows_.reload(state_);
        }
        block_rows_.finish(rows_, state_);
    }
}

void BodySolver::bounce(std::vector<Body>& bodies, double settle, double dt) {
    // Restitution: points that arrived faster than settling and pushed this step leave at e
    // times their approach speed, both points of a manifold solved together (no spin from a
    // flat landing), frictionless, from the impulses already applied. The bodies have moved:
    // each point is taken midway between where its two anchors are now, so that both bodies
    // feel the impulse at one place and angular momentum is kept; but a circle is struck
    // through its centre (then, if it slid along the other body in the step, the two lines of
    // the impulse are apart by the slide and angular momentum is kept only to that). A bounce
    // off a fixed body is timed within the step and moves the body too (time_bounce); the
    // bounces are held to the energy their bodies arrived with (limit_bounce_energy).
    bounced_.clear();
    bounce_impulses_.clear();
    timed_shifts_.clear();
    rows_state_ = state_;
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        PairContact& pc = fresh_[i];
        BlockContact& c = pc.contact;
        bool bounce = false;
        for (int k = 0; k < c.count; ++k) {
            const double vn = pc.approach[static_cast<std::size_t>(k)];
            // A larger island of masses far apart does not bounce: its block iterations leave
            // light bodies rattling between heavy ones, and bouncing them by either rule pumps
            // energy in (heavy_light_bench's box; docs/tried.md). Nor does a pair that touched
            // in the step before: a light body wedged in a pile would take Newton's bounce from
            // each neighbour in turn and rattle.
            const bool hit = vn < -settle && c.points[k].normal_impulse > 0 && !blocked_[i] &&
                             !pc.touched;
            c.points[k].target = hit ? -pc.restitution * vn : 0;
            bounce = bounce || (hit && pc.restitution > 0);
        }
        if (!bounce && !direct_[i]) continue;
        pc.as_solved = false;
        for (int k = 0; k < c.count; ++k) {
            BlockPoint& p = c.points[k];
            V2 ra, rb;
            offsets_now(pc, p.ra, p.rb, ra, rb);
            const V2 point = 0.5 * ((bodies[pc.a].x + ra) + (bodies[pc.b].x + rb));
            p.ra = point - bodies[pc.a].x;
            p.rb = point - bodies[pc.b].x;
            // A circle is struck through its centre, however the pair slid past each other
            // in the step: off it, the impulse spun frictionless circles up (an elastic gas
            // of them had put 73 % of its energy into spin after 10 s, and gained 12 %).
            if (shapes_[pc.a].count == 1) p.ra = c.normal * c.normal.dot(p.ra);
            if (shapes_[pc.b].count == 1) p.rb = c.normal * c.normal.dot(p.rb);
        }
        if (direct_[i]) continue;   // below, with its island
        bounced_.push_back(static_cast<std::uint32_t>(i));
        for (int k = 0; k < 2; ++k) bounce_impulses_.push_back(c.points[k].normal_impulse);
        const std::optional<double> gap = time_bounce(pc, bodies, dt);
        prepare_block(c, state_[pc.a], state_[pc.b]);
        const double friction = c.friction;
        c.friction = 0;
        solve_block(c, state_[pc.a], state_[pc.b]);
        c.friction = friction;
        if (!gap) continue;
        // The rows stopped the body where it met the wall; it has flown on since (moved there
        // below, unless the energy check scales its bounce down).
        const bool b_moves = bodies[pc.b].motion != Motion::fixed;
        V2 ra, rb;
        const double now = separation_now(pc, 0, ra, rb);
        timed_shifts_.push_back(
            {b_moves ? pc.b : pc.a, (b_moves ? 1.0 : -1.0) * (*gap - now) * c.normal});
    }
    limit_bounce_energy(bodies);
    for (const TimedShift& t : timed_shifts_) {
        if (scale_[cluster_[t.body]] != 1.0) continue;   // its bounce was scaled down
        bodies[t.body].x += t.shift;
        moved_[t.body] += t.shift;
    }
    // An island whose direct solve failed bounced with the others, above.
    for_each_group(islands_, island_start_, [&](std::span<const IslandContact> island) {
        if (direct_[island.front().pair]) bounce_together(island);
    });
    for (std::size_t i = 0; i < bodies.size(); ++i) store(bodies[i], state_[i]);
}

void BodySolver::limit_bounce_energy(const std::vector<Body>& bodies) {
    // Newton's rule at each point of a body struck at two places at once over-constrains it:
    // in an elastic gas the bounces made 12 % more energy in 10 s. Bounces that share moving
    // bodies are weighed together: where they leave those bodies more kinetic energy than
    // they arrived with (before the rows), they are scaled down, all by one factor (momentum
    // is kept), to just that energy. A bounce of one pair alone keeps its energy by itself.
    const std::size_t n = bodies.size();
    cluster_.resize(n);
    for (std::size_t i = 0; i < n; ++i) cluster_[i] = static_cast<std::uint32_t>(i);
    const auto find = [&](std::uint32_t i) { return root_in(cluster_, i); };
    const auto moving = [&](std::uint32_t i) { return bodies[i].inv_mass > 0; };
    for (const std::uint32_t i : bounced_) {
        const PairContact& pc = fresh_[i];
        if (!moving(pc.a) || !moving(pc.b)) continue;
        const std::uint32_t ra = find(pc.a), rb = find(pc.b);
        if (ra != rb) cluster_[std::max(ra, rb)] = std::min(ra, rb);
    }
    // Each body's entry its cluster's root from here on (bounce reads it for the shifts).
    for (std::size_t i = 0; i < n; ++i) cluster_[i] = find(static_cast<std::uint32_t>(i));
    // Per cluster: its bounced points (two at one manifold over-constrain a turning body as
    // two pairs do), and whether a held body (moving, of no inverse mass) does work on it,
    // which is not energy the bounce made.
    cluster_points_.assign(n, 0);
    cluster_held_.assign(n, 0);
    hits_of_.assign(n, 0);
    for (const std::uint32_t i : bounced_) {
        const PairContact& pc = fresh_[i];
        ++hits_of_[pc.a];
        ++hits_of_[pc.b];
        const std::uint32_t r = cluster_[moving(pc.a) ? pc.a : pc.b];
        cluster_points_[r] += static_cast<std::uint32_t>(pc.contact.count);
        for (const std::uint32_t j : {pc.a, pc.b}) {
            if (!moving(j) && bodies[j].motion != Motion::fixed) cluster_held_[r] = 1;
        }
    }
    // KE(s) = rows + s linear + s^2 square, for the bounce's changes scaled by s.
    energy_.assign(4 * n, 0.0);   // arrived, rows, linear, square per cluster root
    bool any = false;
    for (std::size_t i = 0; i < n; ++i) {
        if (!moving(static_cast<std::uint32_t>(i)) || hits_of_[i] == 0) continue;
        const std::size_t r = cluster_[i];
        if (cluster_points_[r] < 2 || cluster_held_[r] != 0) continue;
        any = true;
        const BlockBody& before = rows_state_[i];
        const BlockBody& after = state_[i];
        const V2 dv = after.v - before.v;
        const double dw = after.omega - before.omega;
        const double m = 1 / bodies[i].inv_mass;
        const double inertia = bodies[i].inv_inertia > 0 ? 1 / bodies[i].inv_inertia : 0;
        energy_[4 * r] += kinetic_energy(arrived_[i]);
        energy_[4 * r + 1] += kinetic_energy(before);
        energy_[4 * r + 2] += m * before.v.dot(dv) + inertia * before.omega * dw;
        energy_[4 * r + 3] += 0.5 * (m * dv.squaredNorm() + inertia * dw * dw);
    }
    scale_.assign(n, 1.0);
    if (!any) return;
    for (std::size_t r = 0; r < n; ++r) {
        const double rows = energy_[4 * r + 1];
        const double linear = energy_[4 * r + 2], square = energy_[4 * r + 3];
        // No more than the bodies arrived with, or than the rows left them if that is more
        // (a warm start's share): the bounce itself makes none.
        const double allowed = std::max(energy_[4 * r], rows);
        if (square <= 0 || rows + linear + square <= (1 + 1e-9) * allowed) continue;
        // The root of square s^2 + linear s + (rows - allowed) = 0 in [0, 1], in the form
        // that does not cancel when linear is large.
        const double d = linear * linear + 4 * square * (allowed - rows);
        const double root = linear + std::sqrt(d);
        scale_[r] = allowed > rows && root > 0 ? std::clamp(2 * (allowed - rows) / root, 0.0, 1.0)
                                               : std::clamp(-linear / square, 0.0, 1.0);
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (!moving(static_cast<std::uint32_t>(i)) || hits_of_[i] == 0) continue;
        const double s = scale_[cluster_[i]];
        if (s == 1.0) continue;
        state_[i].v = rows_state_[i].v + s * (state_[i].v - rows_state_[i].v);
        state_[i].omega = rows_state_[i].omega + s * (state_[i].omega - rows_state_[i].omega);
    }
    for (std::size_t k = 0; k < bounced_.size(); ++k) {
        PairContact& pc = fresh_[bounced_[k]];
        const double s = scale_[cluster_[moving(pc.a) ? pc.a : pc.b]];
        if (s == 1.0) continue;
        for (int q = 0; q < pc.contact.count; ++q) {
            const double before = bounce_impulses_[2 * k + static_cast<std::size_t>(q)];
            BlockPoint& p = pc.contact.points[q];
            p.normal_impulse = before + s * (p.normal_impulse - before);
        }
    }
}

std::optional<double> BodySolver::time_bounce(PairContact& pc, const std::vector<Body>& bodies,
                                              double dt) const {
    // Bounced at the step's end at e times the approach it had then, a ball leaves with the
    // speed gravity gave it over the whole step, not up to the moment it met the floor, and
    // from the floor, not from where the rest of the step took it: a drop of 1 cm rose 3 %
    // above e^2 h. Timed, its bounce is the disc solver's: exact to the rounding of the gap.
    const bool a_fixed = bodies[pc.a].motion == Motion::fixed;
    const bool b_fixed = bodies[pc.b].motion == Motion::fixed;
    if (a_fixed == b_fixed) return std::nullopt;
    BlockContact& c = pc.contact;
    const double e = pc.restitution;
    const double sign = b_fixed ? -1.0 : 1.0;          // the gap grows as the body moves along n
    const double a_n = sign * fall_.dot(c.normal) / dt;   // the gap's acceleration, m/s^2
    std::array<double, 2> met{}, speed{};                 // s into the step, m/s closing
    for (int k = 0; k < c.count; ++k) {
        const auto q = static_cast<std::size_t>(k);
        if (c.points[k].target <= 0) return std::nullopt;   // a point not bouncing
        // The gap at the step's start, s0 + u0 t + a t^2 / 2, closes first at t.
        const double s0 = pc.anchors[q].separation;
        const double u0 = pc.approach[q] - a_n * dt;
        const double d = u0 * u0 - 2 * a_n * s0;
        double t = 0;
        if (s0 > 0) {
            // Not closing within the step by its start motion (other rows brought it in):
            // nothing to time.
            if (d < 0 || u0 >= 0) return std::nullopt;
            t = 2 * s0 / (-u0 + std::sqrt(d));
            if (t > dt) return std::nullopt;
        }
        met[q] = t;
        speed[q] = u0 + a_n * t;
        if (speed[q] >= 0) return std::nullopt;
    }
    // Both points of a flat landing meet together; a tilted one turns the body, left to the
    // bounce at the step's end.
    if (c.count == 2 && std::abs(met[0] - met[1]) > 1e-6 * dt) return std::nullopt;
    const double rest = dt - met[0];
    const double gap = -e * speed[0] * rest + 0.5 * a_n * rest * rest;   // at the step's end
    // So slow off the wall that it would be back within the step: left to the rows.
    if (gap < 0) return std::nullopt;
    for (int k = 0; k < c.count; ++k) {
        c.points[k].target = -e * speed[static_cast<std::size_t>(k)] + a_n * rest;
    }
    return gap;
}

// The kinetic energy of the island's moving bodies (members_) at these velocities, J, in
// the frame of the first held body among them that moves (its push is work done on the
// island, not energy the bounce made; walls and pegs stand still).
double BodySolver::island_kinetic(const std::vector<BlockBody>& states) const {
    V2 frame = V2::Zero();
    for (const std::uint32_t m : members_) {
        if (states[m].inv_mass == 0 && states[m].v != V2::Zero()) {
            frame = states[m].v;
            break;
        }
    }
    double energy = 0;
    for (const std::uint32_t m : members_) energy += kinetic_energy(states[m], frame);
    return energy;
}

// A direct island bounces by Poisson's rule: its points still closing are first stopped
// together (the speculative solve let them close up to their gap), then each hit point gets
// e times all the impulse that stopped it. Asking every point to leave at e times its
// approach speed (Newton's rule, above) over-constrains a body struck at two places and
// can add energy.
void BodySolver::bounce_together(std::span<const IslandContact> island) {
    const auto hit = [](const BlockPoint& p) { return p.target > 0; };   // and e > 0
    bool bounce = false;
    for (const IslandContact& ic : island) {
        for (int q = 0; q < ic.contact->count; ++q) bounce = bounce || hit(ic.contact->points[q]);
    }
    if (!bounce || !direct_solver_.stop(island, state_, push_)) return;
    // Kept to undo the bounce: the bodies' velocities and points' impulses before it, and
    // the impulses that stop the island.
    members_.clear();
    for (const IslandContact& ic : island) {
        members_.push_back(pair_of(ic)->a);
        members_.push_back(pair_of(ic)->b);
    }
    std::sort(members_.begin(), members_.end());
    members_.erase(std::unique(members_.begin(), members_.end()), members_.end());
    kept_states_.clear();
    for (const std::uint32_t m : members_) kept_states_.push_back(state_[m]);
    kept_impulses_.clear();
    for (const IslandContact& ic : island) {
        for (int q = 0; q < ic.contact->count; ++q) {
            kept_impulses_.push_back(ic.contact->points[q].normal_impulse);
        }
    }
    stopping_ = push_;
    std::size_t point = 0;
    for (const IslandContact& ic : island) {
        const PairContact& pc = *pair_of(ic);
        for (int q = 0; q < ic.contact->count; ++q, ++point) {
            BlockPoint& p = ic.contact->points[q];
            double impulse = push_[point];
            if (hit(p)) impulse += pc.restitution * (p.normal_impulse + push_[point]);
            apply_impulse(state_[pc.a], state_[pc.b], p, impulse * ic.contact->normal);
            p.normal_impulse += impulse;
        }
    }
    // A bounce drives its bodies into their other contacts, which did not arrive (a light
    // body between a heavy one landing on it and the floor would leave through the floor
    // at e times the heavy one's momentum): they are stopped again, together, which only
    // takes energy out. Those impulses answer this bounce, not a lasting load, so they are
    // not kept for the next step's warm start (kept, they launched light bodies there).
    if (direct_solver_.stop(island, state_, push_)) {
        point = 0;
        for (const IslandContact& ic : island) {
            const PairContact& pc = *pair_of(ic);
            for (int q = 0; q < ic.contact->count; ++q, ++point) {
                const BlockPoint& p = ic.contact->points[q];
                apply_impulse(state_[pc.a], state_[pc.b], p,
                              push_[point] * ic.contact->normal);
            }
        }
    }
    // Poisson's rule point by point is not a law of a crowd: a light body squeezed between
    // heavy ones holds them apart with impulses far beyond its own momentum, and e times
    // those at the point that hit launches it. A bounce that leaves the island more kinetic
    // energy than it came with is undone: the island only stops (as the disc solver's
    // direct islands do; heavy_light_bench). An elastic bounce keeps the energy up to
    // rounding, which 1e-9 of it allows.
    if (island_kinetic(state_) <= (1 + 1e-9) * island_kinetic(arrived_)) return;
    for (std::size_t k = 0; k < members_.size(); ++k) state_[members_[k]] = kept_states_[k];
    point = 0;
    for (const IslandContact& ic : island) {
        const PairContact& pc = *pair_of(ic);
        for (int q = 0; q < ic.contact->count; ++q, ++point) {
            BlockPoint& p = ic.contact->points[q];
            p.normal_impulse = kept_impulses_[point] + stopping_[point];
            apply_impulse(state_[pc.a], state_[pc.b], p,
                          stopping_[point] * ic.contact->normal);
        }
    }
}

}  // namespace discreel::physics::detail
