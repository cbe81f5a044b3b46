// Resting contact. Contact impulses here stand for forces spread over the substep (gravity,
// weight of a pile, friction while sliding), so, like gravity, an impulse dv moves a body by
// dv h / 2 within the substep: positions advance by the mean of the substep's start and end
// velocities. A disc resting on the floor then ends every substep exactly where it began with
// zero velocity, and a free disc follows the exact parabola.
//
// The normal row therefore constrains the displacement velocity w = (v_begin + v) / 2 + shift / h
// so that the gap at the end of the substep is not negative. It is linearised around where the
// pair would end up without contact forces, not where it starts: a constraint acts only if the
// pair would actually overlap by then, so discs grazing past each other feel nothing (a
// start-of-substep normal would push them apart and add energy). Existing overlap is not
// resolved here (that would become velocity) but left to PositionProjector. The friction row
// constrains the end velocity of the contact points (stick), within +- friction * normal impulse.
// Only the end velocity v changes while iterating (w moves by half of any change), so the row
// is written as a bound on it. The iterations only read and write velocities, so they run on a
// compact copy: one row per contact with everything constant over the substep folded in
// (normal, masses, bound), and one small velocity record per body. That keeps the hot loop
// inside a few cache lines per contact, even for 10 000 discs.
//
// Rows are solved grouped by colour, no two rows of a colour sharing a disc (greedy colouring
// of the broad phase's whole pair list, redone when it is rebuilt, as Box2D's constraint graph
// does): in active order consecutive rows share their first disc, so each row had to wait for
// the previous one's velocity update; within a colour they are independent, so they are solved
// four at a time in the lanes of an AVX register (two SSE registers on a CPU without AVX2), with
// the same arithmetic per lane as one at a time. An immovable body (wall, peg, held disc) is
// never changed by a row, so each of its rows reads it from a private copy instead of chaining
// every floor row through one record.
#include <algorithm>
#include <bit>
#include <cmath>

#include "substep.hpp"

namespace discreel::physics::detail {

// A 4x4 transpose: lane l of column k is lane k of row l.
inline void ContactSolver::transpose(const Lanes& r0, const Lanes& r1, const Lanes& r2,
                                     const Lanes& r3, Lanes& c0, Lanes& c1, Lanes& c2,
                                     Lanes& c3) {
    const Lanes t0 = __builtin_shufflevector(r0, r1, 0, 4, 2, 6);
    const Lanes t1 = __builtin_shufflevector(r0, r1, 1, 5, 3, 7);
    const Lanes t2 = __builtin_shufflevector(r2, r3, 0, 4, 2, 6);
    const Lanes t3 = __builtin_shufflevector(r2, r3, 1, 5, 3, 7);
    c0 = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
    c1 = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
    c2 = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
    c3 = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

// Gathers the velocity records of one end of a block's rows into lanes, and scatters them back:
// a 4x4 transpose of whole records, each read and written with one access of its own size
// (fewer instructions than gathering the lanes one double at a time).
inline void ContactSolver::load(const std::uint32_t (&records)[width], Lanes& x, Lanes& y,
                                Lanes& w) const {
    Lanes unused;  // inlined: the compiler drops the shuffles that only feed it
    transpose(velocities_[records[0]].packed, velocities_[records[1]].packed,
              velocities_[records[2]].packed, velocities_[records[3]].packed, x, y, w, unused);
}

inline void ContactSolver::store(const std::uint32_t (&records)[width], const Lanes& x,
                                 const Lanes& y, const Lanes& w) {
    // The lanes of a block share no record but the scratch one: a colour shares no disc and
    // immovable ends have private copies; empty lanes all point at the scratch record, and all
    // store back the zeros it holds. The unused lane of a record gets whatever is at hand.
    const Lanes xy02 = __builtin_shufflevector(x, y, 0, 4, 2, 6);
    const Lanes xy13 = __builtin_shufflevector(x, y, 1, 5, 3, 7);
    const Lanes w_swapped = __builtin_shufflevector(w, w, 1, 0, 3, 2);
    velocities_[records[0]].packed = __builtin_shufflevector(xy02, w, 0, 1, 4, 5);
    velocities_[records[1]].packed = __builtin_shufflevector(xy13, w_swapped, 0, 1, 4, 5);
    velocities_[records[2]].packed = __builtin_shufflevector(xy02, w, 2, 3, 6, 7);
    velocities_[records[3]].packed = __builtin_shufflevector(xy13, w_swapped, 2, 3, 6, 7);
}

// Greedy colouring of the whole contact list, in pair order, redone only when the broad phase
// rebuilds it: no two contacts of a colour share a disc (walls take no colour; pegs and held
// discs do, so the colours stay valid whatever moves), which is then true of any subset, such
// as the contacts active in a substep.
void ContactSolver::colour_contacts(const Substep& s) {
    coloured_version_ = s.contacts_version;
    colours_used_.assign(s.disc_count, 0);
    colour_of_.resize(s.contacts.size());
    for (std::size_t i = 0; i < s.contacts.size(); ++i) {
        const Contact& c = s.contacts[i];
        const bool b_disc = c.b < s.disc_count;
        const std::uint64_t used = colours_used_[c.a] | (b_disc ? colours_used_[c.b] : 0);
        const unsigned colour = static_cast<unsigned>(std::countr_one(used));
        colour_of_[i] = static_cast<std::uint8_t>(colour);
        if (colour == overflow) continue;
        const std::uint64_t bit = std::uint64_t{1} << colour;
        colours_used_[c.a] |= bit;
        if (b_disc) colours_used_[c.b] |= bit;
    }
}

void ContactSolver::compute_masses(const Substep& s) {
    massed_contacts_ = s.contacts_version;
    massed_bodies_ = s.bodies_version;
    masses_.resize(s.contacts.size());
    for (std::size_t i = 0; i < s.contacts.size(); ++i) {
        const Body& a = s.bodies[s.contacts[i].a];
        const Body& b = s.bodies[s.contacts[i].b];
        // Two immovable bodies give infinities here; they get no row. The angular terms are
        // r times the rows' spin factor r / I, not tangent_mass_inverse's (r r) / I: the two
        // can differ in the last bit, and the determinism hash pins this rounding.
        masses_[i] = Masses{1.0 / normal_mass_inverse(a, b),
                            1.0 / (a.inv_mass + b.inv_mass + a.radius * (a.radius * a.inv_inertia) +
                                   b.radius * (b.radius * b.inv_inertia))};
    }
}

void ContactSolver::begin(const Substep& s) {
    // Colours first, so that each row is built straight into its place.
    if (s.contacts_version != coloured_version_) colour_contacts(s);
    if (s.contacts_version != massed_contacts_ || s.bodies_version != massed_bodies_) {
        compute_masses(s);
    }
    colour_start_.assign(overflow + 2, 0);
    pending_.clear();
    copied_.clear();
}

void ContactSolver::solve(Substep& s, int iterations) {
    const double inv_h = 1.0 / s.h;
    // The bodies' records, the copies' and a scratch one for the empty lanes.
    velocities_.resize(s.bodies.size() + copied_.size() + 1);
    const auto scratch = static_cast<std::uint32_t>(velocities_.size() - 1);
    velocities_[scratch] = Velocity{};
    predicted_.resize(s.bodies.size());
    // Hoisted by hand: the stores below could alias the vectors' own pointers for all the
    // compiler knows, so it would reload them for every body.
    const double half_h = 0.5 * s.h;
    const V2 fall = s.gravity * s.h;
    Body* const bodies = s.bodies.data();
    Velocity* const velocities = velocities_.data();
    Predicted* const predicted = predicted_.data();
    const std::size_t body_count = s.bodies.size();
    for (std::size_t i = 0; i < body_count; ++i) {
        Body& b = bodies[i];
        b.v_begin = b.v;
        b.omega_begin = b.omega;
        if (b.falls()) b.v += fall;
        velocities[i] = Velocity{{b.v.x(), b.v.y(), b.omega, 0.0}};
        // Where it ends up without contact forces: the integration at the bottom, with v.
        const V2 end = b.x + (b.v_begin + b.v) * half_h + b.shift;
        predicted[i] = Predicted{{end.x(), end.y(), b.v_begin.x(), b.v_begin.y()},
                                 {b.radius, b.inv_mass, b.radius * b.inv_inertia, 0.0}};
    }
    for (std::size_t k = 0; k < copied_.size(); ++k) {
        velocities_[s.bodies.size() + k] = velocities_[copied_[k]];
    }

    // Lanes: each colour starts on a block, and a row of the overflow group (whose rows may
    // share a disc) gets a block to itself.
    const auto whole_blocks = [](std::uint32_t n) { return (n + width - 1) / width * width; };
    colour_start_[overflow + 1] *= width;
    for (unsigned c = 0; c <= overflow; ++c) {
        colour_start_[c + 1] = colour_start_[c] + whole_blocks(colour_start_[c + 1]);
    }
    const std::uint32_t lanes = colour_start_[overflow + 1];
    rows_.resize(lanes / width);
    lane_of_.resize(pending_.size());
    pending_of_lane_.resize(lanes);
    for (std::uint32_t k = 0; k < pending_.size(); ++k) {
        const unsigned colour = pending_[k].colour;
        const std::uint32_t slot = colour_start_[colour];
        colour_start_[colour] += colour == overflow ? width : 1;
        lane_of_[k] = slot;
        pending_of_lane_[slot] = k;
    }
    // The lanes left over: the last block of a colour whose count is not a multiple of the
    // width, all but the first of each block of the overflow group. They are built from any
    // row (the first) and then emptied, so that every block is built whole.
    empty_lanes_.clear();
    for (unsigned c = 0; c < overflow; ++c) {
        for (std::uint32_t slot = colour_start_[c]; slot % width != 0; ++slot) {
            empty_lanes_.push_back(slot);
        }
    }
    for (std::uint32_t slot = whole_blocks(colour_start_[overflow - 1]); slot < lanes;
         slot += width) {
        for (unsigned l = 1; l < width; ++l) empty_lanes_.push_back(slot + l);
    }
    for (const std::uint32_t slot : empty_lanes_) pending_of_lane_[slot] = 0;

    build_rows(s, inv_h);

    for (const std::uint32_t slot : empty_lanes_) {
        RowBlock& r = rows_[slot / width];
        const unsigned l = slot % width;
        r.a[l] = r.b[l] = scratch;
        for (Lanes* field : {&r.normal_x, &r.normal_y, &r.bias, &r.normal_mass, &r.tangent_mass,
                             &r.friction, &r.inv_mass_a, &r.inv_mass_b, &r.radius_a, &r.radius_b,
                             &r.spin_a, &r.spin_b, &r.normal_impulse, &r.tangent_impulse}) {
            (*field)[l] = 0.0;
        }
    }

    solve_rows(iterations);

    // In contact order: the contacts are written in one forward sweep (in lane order they
    // were a scattered write each), and each row's two impulses lie side by side in its block.
    for (std::size_t k = 0; k < pending_.size(); ++k) {
        const std::uint32_t slot = lane_of_[k];
        const RowBlock& r = rows_[slot / width];
        Contact& c = s.contacts[pending_[k].contact];
        c.normal_impulse = r.normal_impulse[slot % width];
        c.tangent_impulse = r.tangent_impulse[slot % width];
        c.step_impulse += r.normal_impulse[slot % width];
    }
    const std::size_t disc_count = s.disc_count;
    for (std::size_t i = 0; i < disc_count; ++i) {
        Body& b = bodies[i];
        if (!b.moves()) continue;
        b.v = velocities[i].v();
        b.omega = velocities[i].omega();
        b.x += (b.v_begin + b.v) * half_h + b.shift;
        b.angle += (b.omega_begin + b.omega) * half_h + b.turn;
    }
}

// A block at a time, in lane order: its four rows' geometry and bias side by side in lanes (the
// same IEEE operations per lane as disc_disc and one row at a time), and each of its fields
// written once, whole. Rows against a wall take their normal and gap from disc_feature, a lane
// at a time.
[[gnu::target_clones("avx2", "default")]] void ContactSolver::build_rows(const Substep& s,
                                                                        double inv_h) {
    const Lanes zero = {};
    const Lanes one = zero + 1.0;
    for (std::size_t block = 0; block < rows_.size(); ++block) {
        RowBlock& r = rows_[block];
        const Contact* contact[width];
        const Predicted* a[width];
        const Predicted* b[width];
        Lanes allowed_overlap, restitution;
        for (unsigned l = 0; l < width; ++l) {
            const Pending& p = pending_[pending_of_lane_[block * width + l]];
            const Contact& c = s.contacts[p.contact];
            contact[l] = &c;
            a[l] = &predicted_[c.a];
            b[l] = &predicted_[c.b];
            r.a[l] = p.a;
            r.b[l] = p.b;
            r.normal_mass[l] = masses_[p.contact].normal;
            r.tangent_mass[l] = masses_[p.contact].tangent;
            r.friction[l] = c.friction;
            r.normal_impulse[l] = c.normal_impulse;
            r.tangent_impulse[l] = c.tangent_impulse;
            allowed_overlap[l] = std::min(c.gap, 0.0);
            restitution[l] = c.restitution;
        }
        Lanes ax, ay, a_begin_x, a_begin_y, bx, by, b_begin_x, b_begin_y, unused;
        transpose(a[0]->motion, a[1]->motion, a[2]->motion, a[3]->motion, ax, ay, a_begin_x,
                  a_begin_y);
        transpose(b[0]->motion, b[1]->motion, b[2]->motion, b[3]->motion, bx, by, b_begin_x,
                  b_begin_y);
        transpose(a[0]->mass, a[1]->mass, a[2]->mass, a[3]->mass, r.radius_a, r.inv_mass_a,
                  r.spin_a, unused);
        transpose(b[0]->mass, b[1]->mass, b[2]->mass, b[3]->mass, r.radius_b, r.inv_mass_b,
                  r.spin_b, unused);
        Lanes avx, avy, bvx, bvy;
        load(r.a, avx, avy, unused);
        load(r.b, bvx, bvy, unused);

        const Lanes dx = ax - bx;
        const Lanes dy = ay - by;
        const Lanes squared = dx * dx + dy * dy;
        Lanes dist;
        for (unsigned l = 0; l < width; ++l) dist[l] = std::sqrt(squared[l]);
        // Coincident centres have no direction; disc_disc's fixed one.
        const auto apart = dist > zero;
        Lanes normal_x = apart ? dx / dist : zero;
        Lanes normal_y = apart ? dy / dist : one;
        Lanes gap = dist - r.radius_a - r.radius_b;
        for (unsigned l = 0; l < width; ++l) {
            if (const Feature* f = s.feature_of(*contact[l])) {
                const Proximity end =
                    disc_feature(V2(a[l]->motion[0], a[l]->motion[1]), a[l]->mass[0], *f);
                normal_x[l] = end.normal.x();
                normal_y[l] = end.normal.y();
                gap[l] = end.gap;
            }
        }
        // The normal row bounds the end velocity n.(v_a - v_b) from below so that the gap at
        // the end is no smaller than allowed: with positions advancing by the mean velocity,
        // a change dv in it moves the gap by dv h / 2, hence the factor 2.
        const Lanes close = (normal_x * (avx - bvx) + normal_y * (avy - bvy)) -
                            2.0 * (gap - allowed_overlap) * inv_h;
        // Never ask for more than a restitution bounce: the pair must not leave faster than
        // e times its approach speed (after gravity, forces only ever stop a pair). Overlap that
        // this cannot prevent is removed by PositionProjector, without creating velocity.
        const Lanes approach =
            normal_x * (a_begin_x - b_begin_x) + normal_y * (a_begin_y - b_begin_y);
        const Lanes bounce = -restitution * approach;
        const Lanes leave = zero < bounce ? bounce : zero;  // std::max(0.0, bounce)
        r.bias = leave < close ? leave : close;             // std::min(close, leave)
        r.normal_x = normal_x;
        r.normal_y = normal_y;
    }
}

// Warm start, then sequential impulses, a block of rows at a time. A normal impulse passes
// through the centres, so only tangential impulses turn the discs. Each lane does the same IEEE
// operations in the same order in both builds (and no FMA: -ffp-contract=off), so the AVX2 build
// gives the same bits as the baseline one; it only does four rows per instruction instead of two.
[[gnu::target_clones("avx2", "default")]] void ContactSolver::solve_rows(int iterations) {
    for (const RowBlock& r : rows_) {
        Lanes avx, avy, aw, bvx, bvy, bw;
        load(r.a, avx, avy, aw);
        load(r.b, bvx, bvy, bw);
        const Lanes px = r.normal_x * r.normal_impulse - r.normal_y * r.tangent_impulse;
        const Lanes py = r.normal_y * r.normal_impulse + r.normal_x * r.tangent_impulse;
        avx += px * r.inv_mass_a;
        avy += py * r.inv_mass_a;
        bvx -= px * r.inv_mass_b;
        bvy -= py * r.inv_mass_b;
        aw -= r.spin_a * r.tangent_impulse;
        bw -= r.spin_b * r.tangent_impulse;
        store(r.a, avx, avy, aw);
        store(r.b, bvx, bvy, bw);
    }
    // Both rows of a contact are solved from the same velocities: a normal impulse passes
    // through the centres along n, so it leaves the tangential relative velocity unchanged and
    // the friction row need not wait for it. One update per body per contact, and a dependency
    // chain half as long as solving the rows one after the other.
    const Lanes zero = {};
    for (int it = 0; it < iterations; ++it) {
        for (RowBlock& r : rows_) {
            Lanes avx, avy, aw, bvx, bvy, bw;
            load(r.a, avx, avy, aw);
            load(r.b, bvx, bvy, bw);
            const Lanes dvx = avx - bvx;
            const Lanes dvy = avy - bvy;
            // n = (nx, ny), t = perp(n) = (-ny, nx).
            const Lanes vn = r.normal_x * dvx + r.normal_y * dvy;
            const Lanes vt = (-r.normal_y * dvx + r.normal_x * dvy) - r.radius_a * aw -
                             r.radius_b * bw;
            const Lanes jn_free = r.normal_impulse + (r.bias - vn) * r.normal_mass;
            const Lanes jn = jn_free < zero ? zero : jn_free;
            const Lanes limit = r.friction * jn;
            const Lanes jt_free = r.tangent_impulse - vt * r.tangent_mass;
            const Lanes jt = jt_free < -limit ? -limit : (limit < jt_free ? limit : jt_free);
            const Lanes dn = jn - r.normal_impulse;
            const Lanes dt = jt - r.tangent_impulse;
            const Lanes px = r.normal_x * dn - r.normal_y * dt;
            const Lanes py = r.normal_y * dn + r.normal_x * dt;
            avx += px * r.inv_mass_a;
            avy += py * r.inv_mass_a;
            bvx -= px * r.inv_mass_b;
            bvy -= py * r.inv_mass_b;
            aw -= r.spin_a * dt;
            bw -= r.spin_b * dt;
            store(r.a, avx, avy, aw);
            store(r.b, bvx, bvy, bw);
            r.normal_impulse = jn;
            r.tangent_impulse = jt;
        }
    }
}

}  // namespace discreel::physics::detail
