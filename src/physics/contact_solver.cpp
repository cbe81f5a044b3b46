// Resting contact. Contact impulses here stand for forces spread over the substep (gravity,
// weight of a pile, friction while sliding), so, like gravity, an impulse dv moves a body by
// dv h / 2 within the substep: positions advance by the mean of the substep's start and end
// velocities. A disc resting on the floor then ends every substep where it began (to the
// rounding of the rows' floats, below), and a free disc follows the exact parabola.
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
// (normal, masses, bound), and one small record per body. That keeps the hot loop inside a
// few cache lines per contact, however many discs there are.
//
// The copy is in single precision, which halves the bytes the iterations read and doubles the
// lanes per instruction, but only for what the iterations change: each body's record holds the
// change of its velocity (zero at the start), and each row has its bodies' start velocities
// folded into its bounds, in doubles, when it is built. So the floats carry a pile's contact
// impulses, not its falling speed, whose rounding would show; positions and velocities stay
// doubles, and a body no row pushes keeps its velocity bit for bit (docs/physics-speed.md).
//
// Rows are solved grouped by colour, no two rows of a colour sharing a disc (greedy colouring
// of the broad phase's whole pair list, redone when it is rebuilt). In active order,
// consecutive rows share their first disc, so each row would wait for the previous one's
// velocity update; within a colour they are independent, so they are solved eight at a time in
// the lanes of a vector (simd.hpp: one AVX register, or two SSE or NEON ones), with the same
// arithmetic per lane as one at a time. An immovable body (wall, peg, held disc) is never
// changed by a row, so each of its rows reads it from a private copy: rows on one floor would
// otherwise all chain through its record.
#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "contact_solver.hpp"

namespace discreel::physics::detail {

// A 4x4 transpose: lane l of column k is lane k of row l.
inline void ContactSolver::transpose(const Lanes& r0, const Lanes& r1, const Lanes& r2,
                                     const Lanes& r3, Lanes& c0, Lanes& c1, Lanes& c2,
                                     Lanes& c3) {
    const Lanes t0 = simd::unpack_low(r0, r1);
    const Lanes t1 = simd::unpack_high(r0, r1);
    const Lanes t2 = simd::unpack_low(r2, r3);
    const Lanes t3 = simd::unpack_high(r2, r3);
    c0 = simd::low_halves(t0, t2);
    c1 = simd::low_halves(t1, t3);
    c2 = simd::high_halves(t0, t2);
    c3 = simd::high_halves(t1, t3);
}

// Gathers the velocity records of one end of a block's rows into lanes, and scatters them back
// (simd.hpp: one access of a record's own size each).
inline void ContactSolver::load(const std::uint32_t (&records)[width], Floats& x, Floats& y,
                                Floats& u, Floats& inv_mass) const {
    simd::gather8(velocities_.data(), records, x, y, u, inv_mass);
}

inline void ContactSolver::store(const std::uint32_t (&records)[width], const Floats& x,
                                 const Floats& y, const Floats& u, const Floats& inv_mass) {
    // The lanes of a block share no record but the scratch one: a colour shares no disc and
    // immovable ends have private copies; empty lanes all point at the scratch record, and all
    // store back the zeros it holds.
    simd::scatter8(velocities_.data(), records, x, y, u, inv_mass);
}

// Pegs and held discs take colours too, so the colours stay valid whatever moves.
void colour_greedily(std::span<const Contact> contacts, std::size_t disc_count,
                     std::vector<std::uint64_t>& used, std::vector<std::uint8_t>& colour_of) {
    used.assign(disc_count, 0);
    colour_of.resize(contacts.size());
    for (std::size_t i = 0; i < contacts.size(); ++i) {
        const Contact& c = contacts[i];
        const bool b_disc = c.b < disc_count;
        const std::uint64_t taken = used[c.a] | (b_disc ? used[c.b] : 0);
        const unsigned colour = static_cast<unsigned>(std::countr_one(taken));
        colour_of[i] = static_cast<std::uint8_t>(colour);
        if (colour == overflow_colour) continue;
        const std::uint64_t bit = std::uint64_t{1} << colour;
        used[c.a] |= bit;
        if (b_disc) used[c.b] |= bit;
    }
}

// The whole contact list, in pair order, redone only when the broad phase rebuilds it: what
// holds of the list holds of any subset, such as the contacts active in a substep.
void ContactSolver::colour_contacts(const Substep& s) {
    coloured_version_ = s.contacts_version;
    colour_greedily(s.contacts, s.disc_count, colours_used_, colour_of_);
}

void ContactSolver::compute_masses(const Substep& s) {
    // The unit follows the bodies, not the contact list: it need not be found at every rebuild.
    if (s.bodies_version != massed_bodies_) {
        double heaviest = 0.0, heaviest_moving = 0.0;
        double lightest_moving = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < s.disc_count; ++i) {
            const Body& b = s.bodies[i];
            heaviest = std::max(heaviest, b.mass);
            if (b.inv_mass == 0.0) continue;
            heaviest_moving = std::max(heaviest_moving, b.mass);
            lightest_moving = std::min(lightest_moving, b.mass);
        }
        mass_unit_ = heaviest > 0.0 ? std::ldexp(1.0, std::ilogb(heaviest)) : 1.0;
        islands_.set_masses(lightest_moving, heaviest_moving);
    }
    massed_contacts_ = s.contacts_version;
    massed_bodies_ = s.bodies_version;
    masses_.resize(s.contacts.size());
    for (std::size_t i = 0; i < s.contacts.size(); ++i) {
        const Body& a = s.bodies[s.contacts[i].a];
        const Body& b = s.bodies[s.contacts[i].b];
        // Two immovable bodies give infinities here; they get no row. A disc's r^2 / I is
        // 2 / m (I = m r^2 / 2), which is how the iterations turn a tangential impulse into spin.
        const double inverse = normal_mass_inverse(a, b);
        masses_[i] = Masses{static_cast<float>(1.0 / (inverse * mass_unit_)),
                            static_cast<float>(1.0 / (3.0 * inverse * mass_unit_))};
    }
}

void ContactSolver::plan_islands(Substep& s) {
    row_contacts_.clear();
    if (islands_.far_apart()) {
        for (const Pending& p : pending_) row_contacts_.push_back(p.contact);
    }
    islands_.plan(s, row_contacts_);
}

void ContactSolver::begin(const Substep& s) {
    // Colours first, so that each row is built straight into its place.
    if (s.contacts_version != coloured_version_) colour_contacts(s);
    if (s.contacts_version != massed_contacts_ || s.bodies_version != massed_bodies_) {
        compute_masses(s);
    }
    colour_start_.assign(overflow + 2, 0);
    pending_.clear();
    copies_ = 0;
}

void ContactSolver::solve(Substep& s, int iterations) {
    const double inv_h = 1.0 / s.h;
    // The bodies' records, the copies' and a scratch one for the empty lanes.
    velocities_.resize(s.bodies.size() + copies_ + 1);
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
        velocities[i] = Velocity{{0.0F, 0.0F, 0.0F, static_cast<float>(b.inv_mass * mass_unit_)}};
        // Where it ends up without contact forces: the integration at the bottom, with v.
        const V2 end = b.x + (b.v_begin + b.v) * half_h + b.shift;
        predicted[i] = Predicted{{end.x(), end.y(), b.v_begin.x(), b.v_begin.y()},
                                 {b.v.x(), b.v.y(), b.omega, b.radius}};
    }
    // Immovable ends change by nothing: their copies are all zeros, like the scratch record.
    for (std::uint32_t k = 0; k < copies_; ++k) velocities_[s.bodies.size() + k] = Velocity{};

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

    if (islands_.far_apart()) geometry_.resize(lanes);
    build_rows(s, inv_h);

    for (const std::uint32_t slot : empty_lanes_) {
        RowBlock& r = rows_[slot / width];
        const unsigned l = slot % width;
        r.a[l] = r.b[l] = scratch;
        for (Floats* field : {&r.normal_x, &r.normal_y, &r.bias, &r.slip, &r.normal_mass,
                              &r.tangent_mass, &r.friction, &r.normal_impulse,
                              &r.tangent_impulse}) {
            (*field)[l] = 0.0F;
        }
    }

    solve_rows(iterations);
    island_rows_.clear();
    for (const std::uint32_t k : islands_.planned()) {
        const std::uint32_t slot = lane_of_[k];
        IslandRow& row = island_rows_.emplace_back(geometry_[slot]);
        row.normal_impulse =
            static_cast<double>(rows_[slot / width].normal_impulse[slot % width]) * mass_unit_;
    }
    islands_.solve(s, island_rows_);

    // In contact order, so that the contacts are written in one forward sweep rather than
    // scattered; each row's two impulses lie side by side in its block.
    const double unit = mass_unit_;
    for (std::size_t k = 0; k < pending_.size(); ++k) {
        const std::uint32_t slot = lane_of_[k];
        const RowBlock& r = rows_[slot / width];
        Contact& c = s.contacts[pending_[k].contact];
        c.normal_impulse = static_cast<double>(r.normal_impulse[slot % width]) * unit;
        c.tangent_impulse = static_cast<double>(r.tangent_impulse[slot % width]) * unit;
        c.step_impulse += c.normal_impulse;
    }
    // A body no row changed gets back exactly the velocity it had (corrections of zero).
    const std::size_t disc_count = s.disc_count;
    const bool direct = !islands_.planned().empty();
    for (std::size_t i = 0; i < disc_count; ++i) {
        Body& b = bodies[i];
        if (!b.moves()) continue;
        if (const DiscIslands::Solved* solved = direct ? islands_.solved(i) : nullptr) {
            b.v = solved->v;
            b.omega = solved->omega;
        } else {
            const Quad dv = velocities[i].packed;
            b.v += V2(static_cast<double>(dv[0]), static_cast<double>(dv[1]));
            // (Only a tangential impulse changes r omega; a disc no row touched may have r = 0.)
            b.omega += dv[2] == 0.0F ? 0.0 : static_cast<double>(dv[2]) / b.radius;
        }
        b.x += (b.v_begin + b.v) * half_h + b.shift;
        b.angle += (b.omega_begin + b.omega) * half_h + b.turn;
    }
    if (direct) islands_.count_impulses(s.contacts);
}

// A block at a time, in lane order, half a block (four rows) at a time in double lanes: the
// rows' geometry and bias side by side (the same IEEE operations per lane as disc_disc and one
// row at a time), then every field of the block rounded to floats and written once, whole. Rows
// against a wall take their normal and gap from disc_feature, a lane at a time. The bodies'
// start velocities are folded into the constants here, in doubles, so that the floats of the
// iterations carry only the corrections (a pile's contact impulses, not its falling speed).
DISCREEL_CLONES void ContactSolver::build_rows(const Substep& s, double inv_h) {
    const Lanes zero = {};
    const Lanes one = zero + 1.0;
    const double per_unit = 1.0 / mass_unit_;  // exact: a power of two
    const auto join = [](Floats& field, const Lanes& first, const Lanes& second) {
        field = simd::join(simd::to_floats(first), simd::to_floats(second));
    };
    for (std::size_t block = 0; block < rows_.size(); ++block) {
        RowBlock& r = rows_[block];
        Lanes normal_x[2], normal_y[2], bias[2], slip[2];
        for (unsigned part = 0; part < 2; ++part) {
            const Contact* contact[half];
            const Predicted* a[half];
            const Predicted* b[half];
            Lanes allowed_overlap, restitution;
            for (unsigned l = 0; l < half; ++l) {
                const unsigned lane = part * half + l;
                const Pending& p = pending_[pending_of_lane_[block * width + lane]];
                const Contact& c = s.contacts[p.contact];
                contact[l] = &c;
                a[l] = &predicted_[c.a];
                b[l] = &predicted_[c.b];
                r.a[lane] = p.a;
                r.b[lane] = p.b;
                r.normal_mass[lane] = masses_[p.contact].normal;
                r.tangent_mass[lane] = masses_[p.contact].tangent;
                r.friction[lane] = static_cast<float>(c.friction);
                r.normal_impulse[lane] = static_cast<float>(c.normal_impulse * per_unit);
                r.tangent_impulse[lane] = static_cast<float>(c.tangent_impulse * per_unit);
                allowed_overlap[l] = std::min(c.gap, 0.0);
                restitution[l] = c.restitution;
            }
            Lanes ax, ay, a_begin_x, a_begin_y, bx, by, b_begin_x, b_begin_y;
            Lanes avx, avy, a_omega, a_radius, bvx, bvy, b_omega, b_radius;
            transpose(a[0]->motion, a[1]->motion, a[2]->motion, a[3]->motion, ax, ay, a_begin_x,
                      a_begin_y);
            transpose(b[0]->motion, b[1]->motion, b[2]->motion, b[3]->motion, bx, by, b_begin_x,
                      b_begin_y);
            transpose(a[0]->now, a[1]->now, a[2]->now, a[3]->now, avx, avy, a_omega, a_radius);
            transpose(b[0]->now, b[1]->now, b[2]->now, b[3]->now, bvx, bvy, b_omega, b_radius);

            const Lanes dx = ax - bx;
            const Lanes dy = ay - by;
            const Lanes squared = dx * dx + dy * dy;
            Lanes dist;
            for (unsigned l = 0; l < half; ++l) dist[l] = std::sqrt(squared[l]);
            // Coincident centres have no direction; disc_disc's fixed one.
            const auto apart = dist > zero;
            Lanes nx = apart ? dx / dist : zero;
            Lanes ny = apart ? dy / dist : one;
            Lanes gap = dist - a_radius - b_radius;
            for (unsigned l = 0; l < half; ++l) {
                if (const Feature* f = s.feature_of(*contact[l])) {
                    const Proximity end = disc_feature(V2(a[l]->motion[0], a[l]->motion[1]),
                                                       a[l]->now[3], *f);
                    nx[l] = end.normal.x();
                    ny[l] = end.normal.y();
                    gap[l] = end.gap;
                }
            }
            // The normal row bounds the end velocity n.(v_a - v_b) from below so that the gap
            // at the end is no smaller than allowed: with positions advancing by the mean
            // velocity, a change dv in it moves the gap by dv h / 2, hence the factor 2.
            const Lanes dvx = avx - bvx;
            const Lanes dvy = avy - bvy;
            const Lanes normal_speed = nx * dvx + ny * dvy;
            const Lanes close = normal_speed - 2.0 * (gap - allowed_overlap) * inv_h;
            // Never ask for more than a restitution bounce: the pair must not leave faster
            // than e times its approach speed (after gravity, forces only ever stop a pair).
            // Overlap that this cannot prevent is removed by PositionProjector, without
            // creating velocity.
            const Lanes approach = nx * (a_begin_x - b_begin_x) + ny * (a_begin_y - b_begin_y);
            const Lanes bounce = -restitution * approach;
            const Lanes leave = zero < bounce ? bounce : zero;  // std::max(0.0, bounce)
            // As bounds on the corrections: less the start velocities' share.
            const Lanes target = leave < close ? leave : close;  // std::min
            bias[part] = target - normal_speed;
            if (islands_.far_apart()) {
                const std::size_t first_lane = block * width + std::size_t{part} * half;
                for (unsigned l = 0; l < half; ++l) {
                    geometry_[first_lane + l] = {V2(nx[l], ny[l]), target[l], 0.0};
                }
            }
            slip[part] = (-ny * dvx + nx * dvy) - a_radius * a_omega - b_radius * b_omega;
            normal_x[part] = nx;
            normal_y[part] = ny;
        }
        join(r.normal_x, normal_x[0], normal_x[1]);
        join(r.normal_y, normal_y[0], normal_y[1]);
        join(r.bias, bias[0], bias[1]);
        join(r.slip, slip[0], slip[1]);
    }
}

// Warm start, then sequential impulses, a block of rows at a time, on the velocity corrections
// (see Velocity). A normal impulse passes through the centres, so only tangential impulses turn
// the discs; for a disc (I = m r^2 / 2) an impulse j at the rim changes r omega by 2 j / m. Each
// lane does the same IEEE operations in the same order in both builds (and no FMA:
// -ffp-contract=off), so the AVX2 build gives the same bits as the baseline one; it only does
// eight rows per instruction instead of four.
DISCREEL_CLONES void ContactSolver::solve_rows(int iterations) {
    for (const RowBlock& r : rows_) {
        Floats ax, ay, au, a_inv, bx, by, bu, b_inv;
        load(r.a, ax, ay, au, a_inv);
        load(r.b, bx, by, bu, b_inv);
        const Floats px = r.normal_x * r.normal_impulse - r.normal_y * r.tangent_impulse;
        const Floats py = r.normal_y * r.normal_impulse + r.normal_x * r.tangent_impulse;
        ax += px * a_inv;
        ay += py * a_inv;
        bx -= px * b_inv;
        by -= py * b_inv;
        au -= (a_inv + a_inv) * r.tangent_impulse;
        bu -= (b_inv + b_inv) * r.tangent_impulse;
        store(r.a, ax, ay, au, a_inv);
        store(r.b, bx, by, bu, b_inv);
    }
    // Both rows of a contact are solved from the same velocities: a normal impulse passes
    // through the centres along n, so it leaves the tangential relative velocity unchanged and
    // the friction row need not wait for it. One update per body per contact, and a dependency
    // chain half as long as solving the rows one after the other.
    const Floats zero = {};
    for (int it = 0; it < iterations; ++it) {
        for (RowBlock& r : rows_) {
            Floats ax, ay, au, a_inv, bx, by, bu, b_inv;
            load(r.a, ax, ay, au, a_inv);
            load(r.b, bx, by, bu, b_inv);
            const Floats dvx = ax - bx;
            const Floats dvy = ay - by;
            // n = (nx, ny), t = perp(n) = (-ny, nx).
            const Floats vn = r.normal_x * dvx + r.normal_y * dvy;
            const Floats vt = ((-r.normal_y * dvx + r.normal_x * dvy) - au - bu) + r.slip;
            const Floats jn_free = r.normal_impulse + (r.bias - vn) * r.normal_mass;
            const Floats jn = jn_free < zero ? zero : jn_free;
            const Floats limit = r.friction * jn;
            const Floats jt_free = r.tangent_impulse - vt * r.tangent_mass;
            const Floats jt = jt_free < -limit ? -limit : (limit < jt_free ? limit : jt_free);
            const Floats dn = jn - r.normal_impulse;
            const Floats dt = jt - r.tangent_impulse;
            const Floats px = r.normal_x * dn - r.normal_y * dt;
            const Floats py = r.normal_y * dn + r.normal_x * dt;
            ax += px * a_inv;
            ay += py * a_inv;
            bx -= px * b_inv;
            by -= py * b_inv;
            au -= (a_inv + a_inv) * dt;
            bu -= (b_inv + b_inv) * dt;
            store(r.a, ax, ay, au, a_inv);
            store(r.b, bx, by, bu, b_inv);
            r.normal_impulse = jn;
            r.tangent_impulse = jt;
        }
    }
}

}  // namespace discreel::physics::detail
