#include "body_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "discreel/physics.hpp"

namespace discreel::physics::detail {
namespace {

void store(RigidBody& b, const BlockBody& s) {
    b.v = s.v;
    b.omega = s.omega;
}

V2 rotate(const V2& v, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

// The positional impulses (kg m, along n) at two points of one manifold that bring both
// separations, `gap` short of their allowed value (negative: too deep), to it or beyond, each
// zero where its point separates by itself: the velocity block's complementarity problem
// (block_solver.cpp) with the gaps in place of the velocities.
std::array<double, 2> block_push(const RigidBody& a, const RigidBody& b, const V2& n,
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

void BodySolver::find_pairs(const std::vector<RigidBody>& bodies, double dt, double fall) {
    const std::size_t n = bodies.size();
    boxes_.resize(n);
    margin_.resize(n);
    transforms_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const RigidBody& b = bodies[i];
        // How far the body's surface can move in the step: the pair's speculative distance
        // is the sum of the two, so contacts are found before a fast body passes through.
        margin_[i] = (b.v.norm() + std::abs(b.omega) * b.bound) * dt +
                     (b.inv_mass > 0 ? fall : 0.0) + 0.5 * def_.speculative;
        transforms_[i] = Transform::of(b.x, b.angle);
        const Transform& xf = transforms_[i];
        std::array<double, 4> box{HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
        for (int k = 0; k < b.shape.count; ++k) {
            const V2 p = xf.apply(b.shape.vertices[k]);
            box = {std::min(box[0], p.x()), std::min(box[1], p.y()), std::max(box[2], p.x()),
                   std::max(box[3], p.y())};
        }
        const double grow = b.shape.radius + margin_[i];
        boxes_[i] = {box[0] - grow, box[1] - grow, box[2] + grow, box[3] + grow};
    }
    // The fat list holds every pair these boxes can make while it is kept (fat_pairs.hpp);
    // the step's pairs are those whose boxes overlap now, in (a, b) order. Two bodies neither
    // of which a contact can move (walls, pegs, held bodies) make none.
    fat_margin_.resize(n);
    movable_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        fat_margin_[i] = 0.25 * bodies[i].bound + 4 * margin_[i];
        movable_[i] = bodies[i].inv_mass > 0;
    }
    fat_pairs_.update(boxes_, fat_margin_, movable_, fat_list_);
    pairs_.clear();
    for (const std::uint64_t key : fat_list_) {
        const auto i = static_cast<std::uint32_t>(key >> 32);
        const auto j = static_cast<std::uint32_t>(key & 0xffffffffu);
        if (boxes_overlap(boxes_[i], boxes_[j])) pairs_.push_back(key);
    }
}

void BodySolver::manifold_of(PairContact& pc, const PairContact* before,
                             const std::vector<RigidBody>& bodies) {
    const RigidBody& a = bodies[pc.a];
    const RigidBody& b = bodies[pc.b];
    const Transform& xa = transforms_[pc.a];
    const Transform& xb = transforms_[pc.b];
    const V2 offset = xa.inverse_rotate(xb.p - xa.p);
    const double turn = b.angle - a.angle;
    const bool still = before != nullptr && !fast_[pc.a] && !fast_[pc.b] &&
                       (offset - before->made.offset).norm() <=
                           def_.recycle_travel * std::min(a.inner, b.inner) &&
                       std::abs(turn - before->made.turn) <= def_.recycle_turn;
    if (still) {
        // The points stay fixed to the bodies; each one's separation is how far apart its two
        // surface points are along the normal now.
        pc.made = before->made;
        Manifold& m = pc.manifold;
        m.normal = xa.rotate(pc.made.normal);
        m.count = before->manifold.count;
        for (int k = 0; k < m.count; ++k) {
            const Made::Point& p = pc.made.points[static_cast<std::size_t>(k)];
            const V2 on_a = xa.apply(p.a), on_b = xb.apply(p.b);
            m.points[k] = {0.5 * (on_a + on_b), m.normal.dot(on_b - on_a), p.id};
        }
        return;
    }
    pc.manifold = collide(a.shape, xa, b.shape, xb, margin_[pc.a] + margin_[pc.b]);
    const Manifold& m = pc.manifold;
    pc.made.normal = xa.inverse_rotate(m.normal);
    pc.made.offset = offset;
    pc.made.turn = turn;
    for (int k = 0; k < m.count; ++k) {
        const ManifoldPoint& mp = m.points[k];
        const V2 half = 0.5 * mp.separation * m.normal;
        pc.made.points[static_cast<std::size_t>(k)] = {xa.inverse_apply(mp.point - half),
                                                       xb.inverse_apply(mp.point + half), mp.id};
    }
}

void BodySolver::apply_totals(const PairContact& pc, double sign) {
    const V2 tangent = -perp(pc.contact.normal);
    for (int k = 0; k < pc.contact.count; ++k) {
        const BlockPoint& p = pc.contact.points[k];
        apply_impulse(state_[pc.a], state_[pc.b], p,
                      sign * (p.normal_impulse * pc.contact.normal + p.tangent_impulse * tangent));
    }
}

std::uint32_t BodySolver::root(std::uint32_t i) {
    while (parent_[i] != i) {
        parent_[i] = parent_[parent_[i]];
        i = parent_[i];
    }
    return i;
}

void BodySolver::find_islands(const std::vector<RigidBody>& bodies) {
    const std::size_t n = bodies.size();
    parent_.resize(n);
    lightest_.resize(n);
    heaviest_.resize(n);
    points_.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        parent_[i] = static_cast<std::uint32_t>(i);
        // By inverse mass: what the solver uses (a body's `mass` may be left unset).
        lightest_[i] = heaviest_[i] = bodies[i].inv_mass;
    }
    const auto moves = [&](std::uint32_t i) { return bodies[i].inv_mass > 0; };
    // The lower index roots the merged island, so the grouping depends only on the contacts.
    for (const PairContact& pc : fresh_) {
        if (!moves(pc.a) || !moves(pc.b)) continue;
        const std::uint32_t ra = root(pc.a), rb = root(pc.b);
        if (ra == rb) continue;
        const std::uint32_t low = std::min(ra, rb), high = std::max(ra, rb);
        parent_[high] = low;
        lightest_[low] = std::max(lightest_[low], lightest_[high]);
        heaviest_[low] = std::min(heaviest_[low], heaviest_[high]);
    }
    const auto island_of = [&](const PairContact& pc) { return root(moves(pc.a) ? pc.a : pc.b); };
    for (const PairContact& pc : fresh_) points_[island_of(pc)] += pc.contact.count;
    direct_.assign(fresh_.size(), 0);
    blocked_.assign(fresh_.size(), 0);
    group_key_.resize(fresh_.size());
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        const PairContact& pc = fresh_[i];
        const std::uint32_t r = island_of(pc);
        if (lightest_[r] < def_.direct_mass_ratio * heaviest_[r]) continue;
        if (points_[r] <= def_.direct_points) {
            direct_[i] = 1;
            group_key_[i] = r;
            continue;
        }
        // Too large to solve whole: beyond block_mass_ratio the contact joins the block of its
        // lighter body; below it the island iterates like an even one.
        if (lightest_[r] < def_.block_mass_ratio * heaviest_[r]) continue;
        blocked_[i] = 1;
        const bool a_lighter =
            !moves(pc.b) || (moves(pc.a) && bodies[pc.a].inv_mass >= bodies[pc.b].inv_mass);
        group_key_[i] = a_lighter ? pc.a : pc.b;
    }
    group(direct_, islands_, island_start_);
    group(blocked_, blocks_, block_start_);
}

void BodySolver::group(const std::vector<unsigned char>& selected,
                       std::vector<IslandContact>& grouped, std::vector<std::size_t>& starts) {
    // Counting sort of the selected contacts by key (a body index), each group in fresh_'s
    // order; starts first counts per key, then keeps only the groups' bounds.
    const std::size_t n = parent_.size();
    starts.assign(n + 1, 0);
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        if (selected[i]) ++starts[group_key_[i] + 1];
    }
    for (std::size_t i = 0; i < n; ++i) starts[i + 1] += starts[i];
    grouped.resize(starts[n]);
    std::vector<std::size_t>& fill = island_fill_;
    fill.assign(starts.begin(), starts.end() - 1);
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        if (!selected[i]) continue;
        PairContact& pc = fresh_[i];
        grouped[fill[group_key_[i]]++] =
            IslandContact{pc.a, pc.b, &pc.contact, static_cast<std::uint32_t>(i)};
    }
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (starts[i + 1] > starts[i]) starts[kept++] = starts[i];
    }
    starts[kept] = grouped.size();
    starts.resize(kept + 1);
}

void BodySolver::step(std::vector<RigidBody>& bodies, const V2& gravity, double dt) {
    start_angle_.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        RigidBody& b = bodies[i];
        if (b.bound < 0) b.bound = bounding_radius(b.shape);
        if (b.inner < 0) b.inner = inner_radius(b.shape);
        if (b.inv_mass > 0) b.v += gravity * dt;
        start_angle_[i] = b.angle;
    }
    // Restitution acts on approaches faster than gravity gives in about two steps: slower
    // ones are a body settling, which would otherwise hop by e g dt every step.
    const double settle = 2 * gravity.norm() * dt;
    find_pairs(bodies, dt, 0.5 * gravity.norm() * dt * dt);
    // A body that will travel more than impact_travel of its inner radius is fast: its pairs
    // that start the step apart are left to the impacts (body_impacts.cpp), timed exactly,
    // rather than to a speculative contact made from where the step starts.
    fast_.assign(bodies.size(), 0);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const RigidBody& b = bodies[i];
        const double travel = (b.v.norm() + std::abs(b.omega) * b.bound) * dt;
        fast_[i] = b.inv_mass > 0 && travel > def_.impact_travel * b.inner;
    }

    fresh_.clear();
    auto previous = contacts_.begin();
    for (const std::uint64_t key : pairs_) {
        const auto i = static_cast<std::uint32_t>(key >> 32);
        const auto j = static_cast<std::uint32_t>(key & 0xffffffffu);
        const RigidBody& a = bodies[i];
        const RigidBody& b = bodies[j];
        PairContact pc;
        pc.a = i;
        pc.b = j;
        // The same pair last step (both lists in pair order): its manifold and its impulses.
        while (previous != contacts_.end() &&
               (previous->a < i || (previous->a == i && previous->b < j))) {
            ++previous;
        }
        const bool had = previous != contacts_.end() && previous->a == i && previous->b == j;
        manifold_of(pc, had ? &*previous : nullptr, bodies);
        if (pc.manifold.count == 0) continue;
        // A fast body's pair that starts apart, against a wall or a body of alike mass, is met
        // at its time of impact instead (body_impacts.cpp): exactly when it happens, bounced
        // by Poisson's rule, where a speculative contact would bounce it at the step's end by
        // Newton's rule at both points, which adds energy to a spinning body. Masses far apart
        // stay speculative: their islands are solved together (island.hpp), which impacts one
        // pair at a time are not.
        const double lighter = std::max(a.inv_mass, b.inv_mass);
        const double heavier = std::min(a.inv_mass, b.inv_mass);
        const bool wall = heavier == 0;
        if ((fast_[i] || fast_[j]) && (wall || lighter < def_.direct_mass_ratio * heavier)) {
            double apart = HUGE_VAL;
            for (int k = 0; k < pc.manifold.count; ++k) {
                apart = std::min(apart, pc.manifold.points[k].separation);
            }
            if (apart > def_.slop) continue;
        }
        BlockContact& c = pc.contact;
        c.normal = pc.manifold.normal;
        c.count = pc.manifold.count;
        c.friction = mix_friction(a.friction, b.friction);
        pc.restitution = mix_restitution(a.restitution, b.restitution);
        // Warm start: the impulses of the same features last step.
        pc.touched = had && previous->touched;   // until this step's impulses say otherwise
        const BlockBody va = velocity_of(a), vb = velocity_of(b);
        for (int k = 0; k < c.count; ++k) {
            const ManifoldPoint& mp = pc.manifold.points[k];
            BlockPoint& p = c.points[k];
            p.ra = mp.point - a.x;
            p.rb = mp.point - b.x;
            pc.anchors[k] = {p.ra, p.rb, mp.separation};
            // Apart: approach at most far enough to touch within the step; touching: stop
            // closing. The bounce comes after the positions move (below), so that a body
            // leaves from the surface at e times the speed it arrived with.
            p.target = mp.separation > 0 ? -mp.separation / dt : 0;
            pc.approach[static_cast<std::size_t>(k)] = normal_velocity(c, p, va, vb);
            if (!had) continue;
            for (int q = 0; q < previous->contact.count; ++q) {
                if (previous->manifold.points[q].id != mp.id) continue;
                p.normal_impulse = previous->contact.points[q].normal_impulse;
                p.tangent_impulse = previous->contact.points[q].tangent_impulse;
            }
        }
        fresh_.push_back(pc);
    }

    // The islands solved directly first (their bodies have no other contacts), then warm
    // start and the velocity iterations of the rest, body states carried between contacts.
    find_islands(bodies);
    // One more record than bodies: the scratch one the rows' empty lanes point at.
    state_.resize(bodies.size() + 1);
    for (std::size_t i = 0; i < bodies.size(); ++i) state_[i] = velocity_of(bodies[i]);
    state_.back() = BlockBody{};
    for_each_group(islands_, island_start_, [&](std::span<const IslandContact> island) {
        if (direct_solver_.velocities(island, state_)) return;
        // Not settled within its pivots (never seen): the island iterates like the others.
        for (const IslandContact& ic : island) direct_[ic.pair] = 0;
    });
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        PairContact& pc = fresh_[i];
        if (direct_[i]) continue;
        prepare_block(pc.contact, state_[pc.a], state_[pc.b]);
        apply_totals(pc, 1);
    }
    rows_.clear();
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        if (direct_[i] || blocked_[i]) continue;
        rows_.push_back(RowRef{fresh_[i].a, fresh_[i].b, &fresh_[i].contact});
    }
    block_rows_.build(rows_, state_);
    for (int it = 0; it < def_.iterations; ++it) {
        block_rows_.solve(state_);
        // A block's impulses are taken back out and solved again, together.
        for_each_group(blocks_, block_start_, [&](std::span<const IslandContact> block) {
            for (const IslandContact& ic : block) apply_totals(*pair_of(ic), -1);
            if (direct_solver_.velocities(block, state_)) return;
            for (const IslandContact& ic : block) apply_totals(*pair_of(ic), 1);
        });
    }
    block_rows_.store(rows_);
    for (std::size_t i = 0; i < bodies.size(); ++i) store(bodies[i], state_[i]);

    std::vector<V2>& moved = moved_;
    moved.resize(bodies.size());
    std::vector<double>& turned = turned_;
    turned.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        RigidBody& b = bodies[i];
        moved[i] = b.v * dt;
        turned[i] = b.omega * dt;
        b.x += moved[i];
        b.angle += turned[i];
    }

    // Restitution: points that arrived faster than settling and pushed this step leave at e
    // times their approach speed, both points of a manifold solved together (no spin from a
    // flat landing). Velocities only, frictionless, from the impulses already applied. The
    // bodies have moved: each point is taken midway between where its two anchors are now,
    // so that both bodies feel the impulse at one place and angular momentum is kept.
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        PairContact& pc = fresh_[i];
        BlockContact& c = pc.contact;
        bool bounce = false;
        for (int k = 0; k < c.count; ++k) {
            const double vn = pc.approach[static_cast<std::size_t>(k)];
            // A larger island of masses far apart does not bounce: its block iterations leave
            // light bodies rattling between heavy ones, and bouncing them by either rule pumps
            // energy in (heavy_light_bench's box; docs/tried.md).
            const bool hit = vn < -settle && c.points[k].normal_impulse > 0 && !blocked_[i];
            c.points[k].target = hit ? -pc.restitution * vn : 0;
            bounce = bounce || (hit && pc.restitution > 0);
        }
        if (!bounce && !direct_[i]) continue;
        for (int k = 0; k < c.count; ++k) {
            BlockPoint& p = c.points[k];
            const V2 ra = rotate(p.ra, turned[pc.a]), rb = rotate(p.rb, turned[pc.b]);
            const V2 point = 0.5 * ((bodies[pc.a].x + ra) + (bodies[pc.b].x + rb));
            p.ra = point - bodies[pc.a].x;
            p.rb = point - bodies[pc.b].x;
        }
        if (direct_[i]) continue;   // below, with its island
        prepare_block(c, state_[pc.a], state_[pc.b]);
        const double friction = c.friction;
        c.friction = 0;
        solve_block(c, state_[pc.a], state_[pc.b]);
        c.friction = friction;
    }
    // A direct island bounces by Poisson's rule: its points still closing are first stopped
    // together (the speculative solve let them close up to their gap), then each hit point gets
    // e times all the impulse that stopped it. Asking every point to leave at e times its
    // approach speed (Newton's rule, above) over-constrains a body struck at two places and
    // can add energy.
    const auto bounce_together = [&](std::span<const IslandContact> island) {
        const auto hit = [](const BlockPoint& p) { return p.target > 0; };   // and e > 0
        bool bounce = false;
        for (const IslandContact& ic : island) {
            for (int q = 0; q < ic.contact->count; ++q) bounce = bounce || hit(ic.contact->points[q]);
        }
        if (!bounce || !direct_solver_.stop(island, state_, push_)) return;
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
        if (!direct_solver_.stop(island, state_, push_)) return;
        point = 0;
        for (const IslandContact& ic : island) {
            const PairContact& pc = *pair_of(ic);
            for (int q = 0; q < ic.contact->count; ++q, ++point) {
                const BlockPoint& p = ic.contact->points[q];
                apply_impulse(state_[pc.a], state_[pc.b], p, push_[point] * ic.contact->normal);
            }
        }
    };
    for_each_group(islands_, island_start_, bounce_together);
    for (std::size_t i = 0; i < bodies.size(); ++i) store(bodies[i], state_[i]);

    // Whatever overlap is left beyond the slop is pushed out, point by point: positions only,
    // so no velocity (and no energy) is added. A point's separation follows from how far its
    // two anchors moved along the manifold's normal since the manifold was made, which is
    // accurate for the small motions of a step and costs no new manifold.
    spin_.resize(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) spin_[i] = {std::cos(turned[i]), std::sin(turned[i])};
    const auto rotate_by = [&](const V2& v, std::size_t i) {
        const auto [c, s] = spin_[i];
        return V2(c * v.x() - s * v.y(), s * v.x() + c * v.y());
    };
    // The separation of point k of pc now, and its anchors' offsets now.
    const auto separation_now = [&](const PairContact& pc, int k, V2& ra, V2& rb) {
        const Anchor& an = pc.anchors[static_cast<std::size_t>(k)];
        ra = rotate_by(an.ra, pc.a);
        rb = rotate_by(an.rb, pc.b);
        const V2 drift = (moved[pc.b] + rb - an.rb) - (moved[pc.a] + ra - an.ra);
        return an.separation + pc.contact.normal.dot(drift);
    };
    // Moves a and b apart by `amount` (kg m) of positional impulse along n at offsets ra, rb.
    const auto push_apart = [&](const PairContact& pc, const V2& ra, const V2& rb,
                                double amount) {
        RigidBody& a = bodies[pc.a];
        RigidBody& b = bodies[pc.b];
        const V2 impulse = amount * pc.contact.normal;
        const V2 da = a.inv_mass * impulse, db = b.inv_mass * impulse;
        const double ta = a.inv_inertia * cross(ra, impulse);
        const double tb = b.inv_inertia * cross(rb, impulse);
        a.x -= da;
        a.angle -= ta;
        b.x += db;
        b.angle += tb;
        moved[pc.a] -= da;
        turned[pc.a] -= ta;
        moved[pc.b] += db;
        turned[pc.b] += tb;
        spin_[pc.a] = {std::cos(turned[pc.a]), std::sin(turned[pc.a])};
        spin_[pc.b] = {std::cos(turned[pc.b]), std::sin(turned[pc.b])};
    };
    // A direct island: every point to within the slop at once, through the same matrix; the
    // blocks of larger islands the same way, one after the other, in sweeps.
    const auto push_out_together = [&](std::span<const IslandContact> island) {
        separation_.clear();
        bool overlaps = false;
        for (const IslandContact& ic : island) {
            const PairContact& pc = *pair_of(ic);
            for (int q = 0; q < pc.contact.count; ++q) {
                BlockPoint& p = ic.contact->points[q];
                // The slop, as below: pushing a body out raises it, and energy with it.
                separation_.push_back(separation_now(pc, q, p.ra, p.rb) + def_.slop);
                overlaps = overlaps || separation_.back() < 0;
            }
        }
        if (!overlaps || !direct_solver_.positions(island, state_, separation_, push_)) return;
        std::size_t point = 0;
        for (const IslandContact& ic : island) {
            const PairContact& pc = *pair_of(ic);
            for (int q = 0; q < pc.contact.count; ++q, ++point) {
                const BlockPoint& p = pc.contact.points[q];
                if (push_[point] > 0) push_apart(pc, p.ra, p.rb, push_[point]);
            }
        }
    };
    for_each_group(islands_, island_start_, push_out_together);
    for (int sweep = 0; sweep < def_.position_iterations; ++sweep) {
        for_each_group(blocks_, block_start_, push_out_together);
    }
    for (int sweep = 0; sweep < def_.position_iterations; ++sweep) {
        for (std::size_t i = 0; i < fresh_.size(); ++i) {
            if (direct_[i] || blocked_[i]) continue;
            const PairContact& pc = fresh_[i];
            const RigidBody& a = bodies[pc.a];
            const RigidBody& b = bodies[pc.b];
            const V2& n = pc.contact.normal;
            if (pc.contact.count == 2) {
                // Both points at once, as the velocities are solved: pushed one at a time, the
                // first push turns the body and the second turns it back only in part, which
                // sets a resting stack rocking.
                std::array<V2, 2> ra, rb;
                std::array<double, 2> overlap{};
                for (int k = 0; k < 2; ++k) {
                    overlap[static_cast<std::size_t>(k)] =
                        separation_now(pc, k, ra[static_cast<std::size_t>(k)],
                                       rb[static_cast<std::size_t>(k)]) + def_.slop;
                }
                if (overlap[0] >= 0 && overlap[1] >= 0) continue;
                const std::array<double, 2> push =
                    block_push(a, b, n, ra, rb,
                               {std::max(overlap[0], -def_.max_correction),
                                std::max(overlap[1], -def_.max_correction)});
                for (int k = 0; k < 2; ++k) {
                    const auto q = static_cast<std::size_t>(k);
                    if (push[q] > 0) push_apart(pc, ra[q], rb[q], push[q]);
                }
                continue;
            }
            for (int k = 0; k < pc.contact.count; ++k) {
                V2 ra, rb;
                const double overlap = separation_now(pc, k, ra, rb) + def_.slop;
                if (overlap >= 0) continue;
                const double push = std::min(-overlap, def_.max_correction);
                const double rna = cross(ra, n), rnb = cross(rb, n);
                const double k_n = a.inv_mass + b.inv_mass + a.inv_inertia * rna * rna +
                                   b.inv_inertia * rnb * rnb;
                if (k_n <= 0) continue;
                push_apart(pc, ra, rb, push / k_n);
            }
        }
    }
    // A pair that started the step apart and ends deeper in than the slop was not kept apart
    // by the iterations (bodies closing on each other from several sides at once, or features
    // meeting that were not the nearest where the step started): its bodies are swept for
    // their impacts too. Pairs that were already touching are a pile's, whose pressure the
    // iterations share out; only pairs with a body that moved a hundredth of its inner radius
    // are looked at again.
    for (const PairContact& pc : fresh_) {
        const RigidBody& a = bodies[pc.a];
        const RigidBody& b = bodies[pc.b];
        const auto moved_far = [&](std::uint32_t i) {
            return moved[i].norm() + std::abs(turned[i]) * bodies[i].bound > 0.01 * bodies[i].inner;
        };
        if (!moved_far(pc.a) && !moved_far(pc.b)) continue;
        double apart = HUGE_VAL;
        for (int k = 0; k < pc.manifold.count; ++k) apart = std::min(apart, pc.manifold.points[k].separation);
        if (apart <= 0) continue;
        const Manifold now = collide(a.shape, Transform::of(a.x, a.angle), b.shape,
                                     Transform::of(b.x, b.angle), 0);
        const double deep = def_.slop + 0.05 * std::min(a.inner, b.inner);
        for (int k = 0; k < now.count; ++k) {
            if (now.points[k].separation >= -deep) continue;
            fast_[pc.a] = a.inv_mass > 0;
            fast_[pc.b] = b.inv_mass > 0;
        }
    }
    time_impacts(bodies, dt, settle);
    touches_.clear();
    for (PairContact& pc : fresh_) {
        double impulse = 0;
        for (int k = 0; k < pc.contact.count; ++k) impulse += pc.contact.points[k].normal_impulse;
        const bool touching = impulse > 0;
        if (touching) {
            PairTouch t;
            t.a = pc.a;
            t.b = pc.b;
            t.impulse = impulse;
            t.began = !pc.touched;
            touches_.push_back(t);
        }
        pc.touched = touching;
    }
    // A pair that met at a time of impact touched too: with its contact's impulse if it has
    // one, as a new touch if not.
    if (!impact_touches_.empty()) {
        const auto by_pair = [](const PairTouch& x, const PairTouch& y) {
            return x.a != y.a ? x.a < y.a : x.b < y.b;
        };
        const std::size_t listed = touches_.size();
        for (const PairTouch& t : impact_touches_) {
            const auto end = touches_.begin() + static_cast<std::ptrdiff_t>(listed);
            const auto at = std::lower_bound(touches_.begin(), end, t, by_pair);
            if (at != end && at->a == t.a && at->b == t.b) {
                at->impulse += t.impulse;
            } else {
                touches_.push_back(t);
            }
        }
        std::sort(touches_.begin(), touches_.end(), by_pair);
    }
    std::swap(contacts_, fresh_);
}

BodySolver::Overlap BodySolver::max_overlap(const std::vector<RigidBody>& bodies) const {
    // Every pair the step's broad phase listed: a fast pair left to its impacts has no contact.
    Overlap deepest;
    for (const std::uint64_t key : pairs_) {
        const auto i = static_cast<std::uint32_t>(key >> 32);
        const auto j = static_cast<std::uint32_t>(key & 0xffffffffu);
        const RigidBody& a = bodies[i];
        const RigidBody& b = bodies[j];
        const Manifold m = collide(a.shape, Transform::of(a.x, a.angle), b.shape,
                                   Transform::of(b.x, b.angle), 0);
        for (int k = 0; k < m.count; ++k) {
            if (-m.points[k].separation <= deepest.depth) continue;
            deepest.depth = -m.points[k].separation;
            deepest.a = i;
            deepest.b = j;
        }
    }
    return deepest;
}

void BodySolver::forget(std::size_t first, std::size_t last) {
    fat_pairs_.invalidate();
    const auto replaced = [&](std::size_t i) { return i >= first && i < last; };
    std::erase_if(contacts_, [&](const PairContact& pc) { return replaced(pc.a) || replaced(pc.b); });
}

}  // namespace discreel::physics::detail
