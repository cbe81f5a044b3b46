// The position stages of the manifold solver's step (body_solver.hpp): the positions move with
// the solved velocities, overlap beyond the slop is pushed out (positions only), and pairs that
// sank in anyway are handed to the impacts.
#include <algorithm>
#include <array>
#include <cmath>

#include "body_solver.hpp"

namespace discreel::physics::detail {
namespace {

// The positional impulses (kg m, along n) at two points of one manifold that bring both
// separations, `gap` short of their allowed value (negative: too deep), to it or beyond, each
// zero where its point separates by itself: the velocity block's complementarity problem
// (block_solver.cpp) with the gaps in place of the velocities.
std::array<double, 2> block_push(const BlockBody& a, const BlockBody& b, const V2& n,
                                 const std::array<V2, 2>& ra, const std::array<V2, 2>& rb,
                                 const std::array<double, 2>& gap) {
    const double ra1 = cross(ra[0], n), rb1 = cross(rb[0], n);
    const double ra2 = cross(ra[1], n), rb2 = cross(rb[1], n);
    const double m = a.inv_mass + b.inv_mass;
    const double k11 = m + a.inv_inertia * ra1 * ra1 + b.inv_inertia * rb1 * rb1;
    const double k22 = m + a.inv_inertia * ra2 * ra2 + b.inv_inertia * rb2 * rb2;
    const double k12 = m + a.inv_inertia * ra1 * ra2 + b.inv_inertia * rb1 * rb2;
    const double det = k11 * k22 - k12 * k12;
    const double g1 = gap[0], g2 = gap[1];
    if (det > 1e-12 * k11 * k22) {   // both pushing
        const std::array<double, 2> x{(-k22 * g1 + k12 * g2) / det, (k12 * g1 - k11 * g2) / det};
        if (x[0] >= 0 && x[1] >= 0) return x;
    }
    if (k11 > 0 && -g1 / k11 >= 0 && k12 * (-g1 / k11) + g2 >= 0) return {-g1 / k11, 0};
    if (k22 > 0 && -g2 / k22 >= 0 && k12 * (-g2 / k22) + g1 >= 0) return {0, -g2 / k22};
    return {0, 0};
}

}  // namespace

void BodySolver::integrate_positions(std::vector<Body>& bodies, double dt) {
    std::vector<V2>& moved = moved_;
    moved.resize(bodies.size());
    std::vector<double>& turned = turned_;
    turned.resize(bodies.size());
    // A body that nothing pushed in the step (its velocity still the start's plus gravity)
    // moves by the mean of its velocities at the step's start and end, so that its flight is
    // the exact parabola (the disc solver's rule; by the end velocity it would run half a
    // step ahead, g t dt / 2: 1 cm after a second at 480 Hz), unless a contact within its
    // reach lies the way gravity's half step would move it back (against gravity) and the
    // other body does not move so too: its row let it go only as far as the end velocity
    // takes it, and moved by the mean it rose g dt^2 / 2 into what was above it, to be pushed
    // back out, energy and all. Two such bodies both move by the mean (a stack falling
    // together stays together); one that was pushed moves by its end velocity, which its
    // rows' targets are written for.
    const V2 half_fall = 0.5 * fall_;
    free_.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Body& b = bodies[i];
        free_[i] = b.inv_mass > 0 && !b.asleep && b.v == start_v_[i];
    }
    // Holding one back may hold back the one it carries: until nothing changes (a column of
    // n bodies takes at most n passes; each pass only ever clears).
    for (bool changed = true; changed;) {
        changed = false;
        for (const PairContact& pc : fresh_) {
            const double towards_b = -half_fall.dot(pc.contact.normal);   // A's rise, along n
            const std::uint32_t rising = towards_b > 0 ? pc.a : pc.b;
            const std::uint32_t other = towards_b > 0 ? pc.b : pc.a;
            if (towards_b == 0 || free_[rising] == 0 || free_[other] != 0) continue;
            free_[rising] = 0;
            changed = true;
        }
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        Body& b = bodies[i];
        moved[i] = (free_[i] != 0 ? V2(b.v - half_fall) : b.v) * dt;
        turned[i] = b.omega * dt;
        if (shifted_) {
            moved[i] += strike_shift_[i];
            turned[i] += strike_turn_[i];
        }
        b.x += moved[i];
        b.angle += turned[i];
    }
    spin_.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        spin_[i] = {std::cos(turned[i]), std::sin(turned[i])};
    }

}

void BodySolver::set_push_mass(std::uint32_t i, double lightest,
                               const std::vector<Body>& bodies) {
    const Body& body = bodies[i];
    BlockBody& m = push_mass_[i];
    m.inv_mass = body.inv_mass;
    m.inv_inertia = body.inv_inertia;
    // Raised by one factor, so that the body keeps its own ratio of mass to inertia.
    if (body.inv_mass > 0 && body.inv_mass * def_.push_mass_ratio < lightest) {
        const double raise = lightest / (def_.push_mass_ratio * body.inv_mass);
        m.inv_mass *= raise;
        m.inv_inertia *= raise;
    }
}

void BodySolver::set_push_masses(std::span<const IslandContact> group,
                                 const std::vector<Body>& bodies) {
    double lightest = 0;   // its inverse mass
    for (const IslandContact& ic : group) {
        lightest = std::max({lightest, bodies[ic.a].inv_mass, bodies[ic.b].inv_mass});
    }
    for (const IslandContact& ic : group) {
        set_push_mass(ic.a, lightest, bodies);
        set_push_mass(ic.b, lightest, bodies);
    }
}

void BodySolver::push_out(std::vector<Body>& bodies) {
    push_mass_.resize(bodies.size());
    // Every push counts (the islands' below too): see the sweeps.
    pushes_ = 0;
    pushed_at_.assign(bodies.size(), 0);
    seen_at_.assign(fresh_.size(), 0);
    // Joints first, so that the contacts see where the joints hold their bodies.
    if (!joints_.empty()) correct_joints(bodies);
    // Whatever overlap is left beyond the slop is pushed out, point by point: positions only,
    // so no velocity (and no energy) is added. An island whose direct solve failed iterates
    // like the others, and is pushed so.
    for_each_group(islands_, island_start_, [&](std::span<const IslandContact> island) {
        if (direct_[island.front().pair]) push_out_together(bodies, island);
    });
    for (int sweep = 0; sweep < def_.position_iterations; ++sweep) {
        for_each_group(blocks_, block_start_, [&](std::span<const IslandContact> block) {
            push_out_together(bodies, block);
        });
    }
    // A contact neither of whose bodies was pushed since it was last looked at would be
    // looked at in vain: its separations are what they were (a resting pile's later sweeps
    // cost next to nothing).
    const auto looked_at_since_pushed = [&](std::size_t i) {
        const PairContact& pc = fresh_[i];
        return pushed_at_[pc.a] <= seen_at_[i] && pushed_at_[pc.b] <= seen_at_[i];
    };
    std::uint32_t pushes_before_sweep = 0;
    for (int sweep = 0; sweep < def_.position_iterations; ++sweep) {
        // A sweep that pushed nothing leaves every contact as it was looked at: the next would
        // skip them all.
        if (sweep > 0 && pushes_ == pushes_before_sweep) break;
        pushes_before_sweep = pushes_;
        for (std::size_t i = 0; i < fresh_.size(); ++i) {
            if (direct_[i] || blocked_[i]) continue;
            if (sweep > 0 && looked_at_since_pushed(i)) continue;
            seen_at_[i] = pushes_;
            push_out_contact(bodies, fresh_[i]);
        }
    }
    // Walls win, as in the disc solver: what the sweeps left in a wall or fixed body (a light
    // body between a heavy one and the floor, pushed back in by it) is pushed out of it last,
    // even into its neighbour, which the next step's rows and push-out see. A contact the
    // sweeps looked at after the last push of either body is as they left it.
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        const PairContact& pc = fresh_[i];
        if (bodies[pc.a].motion != Motion::fixed && bodies[pc.b].motion != Motion::fixed) continue;
        if (!direct_[i] && !blocked_[i] && looked_at_since_pushed(i)) continue;
        push_out_contact(bodies, pc);
    }
}

double BodySolver::separation_now(const PairContact& pc, int k, V2& ra, V2& rb) const {
    // A point's separation follows from how far its two anchors moved along the manifold's
    // normal since the manifold was made, which is accurate for the small motions of a step
    // and costs no new manifold.
    const Anchor& an = pc.anchors[static_cast<std::size_t>(k)];
    offsets_now(pc, an.ra, an.rb, ra, rb);
    const V2 drift = (moved_[pc.b] + rb - an.rb) - (moved_[pc.a] + ra - an.ra);
    return an.separation + pc.contact.normal.dot(drift);
}

void BodySolver::offsets_now(const PairContact& pc, const V2& ra0, const V2& rb0, V2& ra,
                             V2& rb) const {
    // A rounded shape's point is a point of its core, which turns with the body, and its
    // radius along the normal, which does not: turned whole, a spinning circle's anchor left
    // the contact (0.2 rad in a step rises 8 mm at r = 0.4) and the circle, measured apart,
    // was left 8 mm deep in the floor. Its offset so is along the normal: a push does not spin
    // it.
    const V2& n = pc.contact.normal;
    const V2 round_a = shapes_[pc.a].radius * n;
    const V2 round_b = -shapes_[pc.b].radius * n;
    ra = turned_by(ra0 - round_a, spin_[pc.a]) + round_a;
    rb = turned_by(rb0 - round_b, spin_[pc.b]) + round_b;
}

void BodySolver::turn_body(std::uint32_t i, double by) {
    // The body's record of its turn in the step, and its cosine and sine with it.
    turned_[i] += by;
    spin_[i] = turned_on(spin_[i], by);
}

void BodySolver::push_apart(std::vector<Body>& bodies, const PairContact& pc, const V2& ra,
                            const V2& rb, double amount) {
    Body& a = bodies[pc.a];
    Body& b = bodies[pc.b];
    const BlockBody& ma = push_mass_[pc.a];
    const BlockBody& mb = push_mass_[pc.b];
    const V2 impulse = amount * pc.contact.normal;
    const V2 da = ma.inv_mass * impulse, db = mb.inv_mass * impulse;
    const double ta = ma.inv_inertia * cross(ra, impulse);
    const double tb = mb.inv_inertia * cross(rb, impulse);
    a.x -= da;
    a.angle -= ta;
    b.x += db;
    b.angle += tb;
    moved_[pc.a] -= da;
    moved_[pc.b] += db;
    turn_body(pc.a, -ta);
    turn_body(pc.b, tb);
    ++pushes_;
    pushed_at_[pc.a] = pushes_;
    pushed_at_[pc.b] = pushes_;
}

void BodySolver::push_out_together(std::vector<Body>& bodies,
                                   std::span<const IslandContact> island) {
    // A direct island: every point to within the slop at once, through the same matrix; the
    // blocks of larger islands the same way, one after the other, in sweeps.
    separation_.clear();
    bool overlaps = false;
    for (const IslandContact& ic : island) {
        PairContact& pc = *pair_of(ic);
        pc.as_solved = false;   // its offsets are moved below
        for (int q = 0; q < pc.contact.count; ++q) {
            BlockPoint& p = ic.contact->points[q];
            // The slop, as below: pushing a body out raises it, and energy with it.
            separation_.push_back(separation_now(pc, q, p.ra, p.rb) + def_.slop);
            overlaps = overlaps || separation_.back() < 0;
        }
    }
    if (!overlaps) return;
    set_push_masses(island, bodies);
    if (!direct_solver_.positions(island, push_mass_, separation_, push_)) return;
    // An island's body moves at most its inner radius a sweep: a light body crushed between
    // a wall and a heavy body whose faces meet at a slant can only get out along the slant,
    // and its LCP would push it metres along it at once (and the next step launch it). A
    // bound as small as a single point's 2 cm would leave it to be pushed through the wall.
    shifts_.clear();
    const auto shift = [&](std::uint32_t body, const V2& by, double turn_by) {
        for (Shift& s : shifts_) {
            if (s.body != body) continue;
            s.by += by;
            s.turn += turn_by;
            return;
        }
        shifts_.push_back({body, by, turn_by});
    };
    std::size_t at = 0;
    for (const IslandContact& ic : island) {
        const PairContact& pc = *pair_of(ic);
        for (int q = 0; q < pc.contact.count; ++q, ++at) {
            const BlockPoint& p = pc.contact.points[q];
            const V2 impulse = push_[at] * pc.contact.normal;
            const BlockBody& a = push_mass_[pc.a];
            const BlockBody& b = push_mass_[pc.b];
            shift(pc.a, -a.inv_mass * impulse, -a.inv_inertia * cross(p.ra, impulse));
            shift(pc.b, b.inv_mass * impulse, b.inv_inertia * cross(p.rb, impulse));
        }
    }
    double over = 1;   // the most any body's push exceeds its inner radius by, as a factor
    for (const Shift& s : shifts_) {
        const Body& body = bodies[s.body];
        over = std::max(over, (s.by.norm() + std::abs(s.turn) * body.radius) / inner_[s.body]);
    }
    if (over > 1) {
        for (double& x : push_) x /= over;
    }
    std::size_t point = 0;
    for (const IslandContact& ic : island) {
        const PairContact& pc = *pair_of(ic);
        for (int q = 0; q < pc.contact.count; ++q, ++point) {
            const BlockPoint& p = pc.contact.points[q];
            if (push_[point] > 0) push_apart(bodies, pc, p.ra, p.rb, push_[point]);
        }
    }
}

void BodySolver::push_out_contact(std::vector<Body>& bodies, const PairContact& pc) {
    const BlockBody& a = push_mass_[pc.a];
    const BlockBody& b = push_mass_[pc.b];
    const V2& n = pc.contact.normal;
    if (pc.contact.count == 2) {
        // Both points at once, as the velocities are solved: pushed one at a time, the first
        // push turns the body and the second turns it back only in part, which sets a resting
        // stack rocking.
        std::array<V2, 2> ra, rb;
        std::array<double, 2> separation{};
        for (std::size_t k = 0; k < 2; ++k) {
            separation[k] = separation_now(pc, static_cast<int>(k), ra[k], rb[k]);
        }
        if (separation[0] >= -def_.slop && separation[1] >= -def_.slop) return;
        set_push_mass(pc.a, 0, bodies);
        set_push_mass(pc.b, 0, bodies);
        const auto short_of = [&](double s) {
            return std::max(s + def_.push_to, -def_.max_correction);
        };
        const std::array<double, 2> push =
            block_push(a, b, n, ra, rb, {short_of(separation[0]), short_of(separation[1])});
        for (std::size_t k = 0; k < 2; ++k) {
            if (push[k] > 0) push_apart(bodies, pc, ra[k], rb[k], push[k]);
        }
        return;
    }
    for (int k = 0; k < pc.contact.count; ++k) {
        V2 ra, rb;
        const double separation = separation_now(pc, k, ra, rb);
        if (separation >= -def_.slop) continue;
        set_push_mass(pc.a, 0, bodies);
        set_push_mass(pc.b, 0, bodies);
        const double push = std::min(-(separation + def_.push_to), def_.max_correction);
        const double rna = cross(ra, n), rnb = cross(rb, n);
        const double k_n =
            a.inv_mass + b.inv_mass + a.inv_inertia * rna * rna + b.inv_inertia * rnb * rnb;
        if (k_n <= 0) continue;
        push_apart(bodies, pc, ra, rb, push / k_n);
    }
}

void BodySolver::mark_sunk(const std::vector<Body>& bodies) {
    const std::vector<V2>& moved = moved_;
    const std::vector<double>& turned = turned_;
    // A pair that started the step apart and ends deeper in than the slop was not kept apart
    // by the iterations (bodies closing on each other from several sides at once, or features
    // meeting that were not the nearest where the step started): its bodies are swept for
    // their impacts too. Pairs that were already touching are a pile's, whose pressure the
    // iterations share out; only pairs with a body that moved a hundredth of its inner radius
    // are looked at again.
    for (const PairContact& pc : fresh_) {
        const Body& a = bodies[pc.a];
        const Body& b = bodies[pc.b];
        const auto moved_far = [&](std::uint32_t i) {
            return moved[i].norm() + std::abs(turned[i]) * bodies[i].radius > 0.01 * inner_[i];
        };
        if (!moved_far(pc.a) && !moved_far(pc.b)) continue;
        double apart = HUGE_VAL;
        for (int k = 0; k < pc.contact.count; ++k) {
            apart = std::min(apart, pc.anchors[static_cast<std::size_t>(k)].separation);
        }
        if (apart <= 0) continue;
        const double deep = def_.slop + 0.05 * std::min(inner_[pc.a], inner_[pc.b]);
        // No point of either body moved farther than its centre's travel and its turn at its
        // bounding radius: a pair that far apart cannot have sunk in so deep.
        const auto travel = [&](std::uint32_t i) {
            return moved[i].norm() + std::abs(turned[i]) * bodies[i].radius;
        };
        if (apart - (travel(pc.a) + travel(pc.b)) > -deep) continue;
        const Manifold now = collide(shapes_[pc.a], Transform::of(a.x, a.angle), shapes_[pc.b],
                                     Transform::of(b.x, b.angle), 0);
        for (int k = 0; k < now.count; ++k) {
            if (now.points[k].separation >= -deep) continue;
            fast_[pc.a] = a.inv_mass > 0;
            fast_[pc.b] = b.inv_mass > 0;
        }
    }
}

}  // namespace discreel::physics::detail
