#include "block_rows.hpp"

#include <algorithm>
#include <bit>

#include "discreel/clones.hpp"

namespace discreel::physics::detail {
namespace {

using Lanes = simd::Double4;
using Mask = decltype(Lanes{} < Lanes{});

// One end of four rows: its velocities (gathered) and inverse masses (the block's), lane by
// lane.
struct Ends {
    Lanes vx, vy, w, inv_mass, inv_inertia;
};

[[gnu::always_inline]] inline Ends gather(std::span<const BlockBody> bodies,
                                          const std::uint32_t (&at)[4], const Lanes& inv_mass,
                                          const Lanes& inv_inertia) {
    Ends e;
    for (unsigned l = 0; l < 4; ++l) {
        const BlockBody& s = bodies[at[l]];
        e.vx[l] = s.v.x();
        e.vy[l] = s.v.y();
        e.w[l] = s.omega;
    }
    e.inv_mass = inv_mass;
    e.inv_inertia = inv_inertia;
    return e;
}

// Lane by lane, in lane order: lanes that share an immovable body all write back what they
// read, which no row changed.
[[gnu::always_inline]] inline void scatter(std::span<BlockBody> bodies,
                                           const std::uint32_t (&at)[4], const Ends& e) {
    for (unsigned l = 0; l < 4; ++l) {
        BlockBody& s = bodies[at[l]];
        s.v = V2(e.vx[l], e.vy[l]);
        s.omega = e.w[l];
    }
}

// The impulse (px, py) on B, and its opposite on A, at offsets ra and rb.
[[gnu::always_inline]] inline void push(Ends& a, Ends& b, const Lanes& ra_x, const Lanes& ra_y,
                                        const Lanes& rb_x, const Lanes& rb_y, const Lanes& px,
                                        const Lanes& py) {
    a.vx = a.vx - a.inv_mass * px;
    a.vy = a.vy - a.inv_mass * py;
    a.w = a.w - a.inv_inertia * (ra_x * py - ra_y * px);
    b.vx = b.vx + b.inv_mass * px;
    b.vy = b.vy + b.inv_mass * py;
    b.w = b.w + b.inv_inertia * (rb_x * py - rb_y * px);
}

// B's point's velocity relative to A's, along (dx, dy), into `out`. (The helpers here return
// vectors through references: a 256-bit vector returned by value is an ABI that clang refuses
// to call without AVX, even inlined.)
[[gnu::always_inline]] inline void along(const Ends& a, const Ends& b, const Lanes& ra_x,
                                         const Lanes& ra_y, const Lanes& rb_x, const Lanes& rb_y,
                                         const Lanes& dx, const Lanes& dy, Lanes& out) {
    const Lanes rel_x = (b.vx - b.w * rb_y) - (a.vx - a.w * ra_y);
    const Lanes rel_y = (b.vy + b.w * rb_x) - (a.vy + a.w * ra_x);
    out = rel_x * dx + rel_y * dy;
}

// One point's friction: the tangent impulse that stops its sliding, within +- friction times
// its normal impulse (std::clamp's order of tests).
[[gnu::always_inline]] inline void friction_at(Ends& a, Ends& b, const Lanes& ra_x,
                                               const Lanes& ra_y, const Lanes& rb_x,
                                               const Lanes& rb_y, const Lanes& tx,
                                               const Lanes& ty, const Lanes& mass,
                                               const Lanes& friction, const Lanes& normal,
                                               Lanes& tangent) {
    Lanes vt;
    along(a, b, ra_x, ra_y, rb_x, rb_y, tx, ty, vt);
    const Lanes limit = friction * normal;
    const Lanes wanted = tangent - vt * mass;
    const Lanes low = -limit;
    const Lanes capped = limit < wanted ? limit : wanted;
    const Lanes total = wanted < low ? low : capped;
    const Mask active = mass > Lanes{};
    const Lanes change = active ? total - tangent : Lanes{};
    tangent = active ? total : tangent;
    push(a, b, ra_x, ra_y, rb_x, rb_y, change * tx, change * ty);
}

}  // namespace

bool BlockRows::same_layout(std::span<const RowRef> rows,
                            std::span<const BlockBody> bodies) const {
    if (rows.size() != layout_.size() || bodies.size() != bodies_at_layout_) return false;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (layout_[i] != key_of(rows[i], bodies)) return false;
    }
    return true;
}

std::uint64_t BlockRows::key_of(const RowRef& r, std::span<const BlockBody> bodies) {
    const auto moves = [&](std::uint32_t i) {
        return bodies[i].inv_mass > 0 || bodies[i].inv_inertia > 0 ? 1u : 0u;
    };
    return std::uint64_t{r.a} << 33 | std::uint64_t{r.b} << 2 | moves(r.a) << 1 | moves(r.b);
}

void BlockRows::lay_out(std::span<const RowRef> rows, std::span<const BlockBody> bodies) {
    const std::size_t n = bodies.size() - 1;   // the last is the scratch record
    const auto scratch = static_cast<std::uint32_t>(n);
    layout_.resize(rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) layout_[i] = key_of(rows[i], bodies);
    bodies_at_layout_ = bodies.size();
    // Greedy colouring in row order: each row takes the lowest colour none of its moving
    // bodies has yet.
    used_.assign(n, 0);
    colour_of_.resize(rows.size());
    colour_start_.assign(overflow + 2, 0);
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const RowRef& r = rows[i];
        const bool a_moves = (layout_[i] & 2) != 0, b_moves = (layout_[i] & 1) != 0;
        const std::uint64_t taken = (a_moves ? used_[r.a] : 0) | (b_moves ? used_[r.b] : 0);
        const auto colour = static_cast<unsigned>(std::countr_one(taken));
        colour_of_[i] = static_cast<std::uint8_t>(colour);
        ++colour_start_[colour + 1];
        if (colour == overflow) continue;
        const std::uint64_t bit = std::uint64_t{1} << colour;
        if (a_moves) used_[r.a] |= bit;
        if (b_moves) used_[r.b] |= bit;
    }
    // Each colour starts on a block; an overflow row has a block to itself.
    colour_start_[overflow + 1] *= width;
    for (unsigned c = 0; c <= overflow; ++c) {
        const std::uint32_t count = colour_start_[c + 1];
        colour_start_[c + 1] = colour_start_[c] + (count + width - 1) / width * width;
    }
    const std::uint32_t lanes = colour_start_[overflow + 1];
    blocks_.assign(lanes / width, Block{});
    for (Block& block : blocks_) {
        std::fill(std::begin(block.a), std::end(block.a), scratch);
        std::fill(std::begin(block.b), std::end(block.b), scratch);
    }
    lane_of_.resize(rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const unsigned colour = colour_of_[i];
        const std::uint32_t slot = colour_start_[colour];
        colour_start_[colour] += colour == overflow ? width : 1;
        lane_of_[i] = slot;
        Block& block = blocks_[slot / width];
        block.a[slot % width] = rows[i].a;
        block.b[slot % width] = rows[i].b;
    }
}

void BlockRows::build(std::span<const RowRef> rows, std::span<const BlockBody> bodies) {
    // The colours and lanes hold while the rows are those of the last layout, the same pairs
    // in the same order with the same bodies movable: a resting pile lays out rarely.
    if (!same_layout(rows, bodies)) lay_out(rows, bodies);
    for (std::size_t i = 0; i < rows.size(); ++i) {
        Block& block = blocks_[lane_of_[i] / width];
        const unsigned l = lane_of_[i] % width;
        const RowRef& r = rows[i];
        const BlockContact& c = *r.contact;
        const BlockPoint& p1 = c.points[0];
        const bool two = c.count > 1;
        // A single point's second does nothing: no offset, no mass, no impulse, and a 1
        // where the block would divide by it. Every field is written: a lane kept from the
        // last layout may have held two points.
        const BlockPoint none{};
        const BlockPoint& p2 = two ? c.points[1] : none;
        block.a_inv_mass[l] = bodies[r.a].inv_mass;
        block.a_inv_inertia[l] = bodies[r.a].inv_inertia;
        block.b_inv_mass[l] = bodies[r.b].inv_mass;
        block.b_inv_inertia[l] = bodies[r.b].inv_inertia;
        block.normal_x[l] = c.normal.x();
        block.normal_y[l] = c.normal.y();
        block.ra1_x[l] = p1.ra.x();
        block.ra1_y[l] = p1.ra.y();
        block.rb1_x[l] = p1.rb.x();
        block.rb1_y[l] = p1.rb.y();
        block.tangent_mass1[l] = p1.tangent_mass;
        block.target1[l] = p1.target;
        block.normal1[l] = p1.normal_impulse;
        block.tangent1[l] = p1.tangent_impulse;
        block.friction[l] = c.friction;
        block.k11[l] = c.k11;
        block.inv_k11[l] = c.k11 > 0 ? 1 / c.k11 : 0;
        block.two[l] = two ? 1 : 0;
        block.ra2_x[l] = p2.ra.x();
        block.ra2_y[l] = p2.ra.y();
        block.rb2_x[l] = p2.rb.x();
        block.rb2_y[l] = p2.rb.y();
        block.tangent_mass2[l] = p2.tangent_mass;
        block.target2[l] = p2.target;
        block.normal2[l] = p2.normal_impulse;
        block.tangent2[l] = p2.tangent_impulse;
        block.k12[l] = two ? c.k12 : 0;
        block.k22[l] = two ? c.k22 : 1;
        block.inv_k22[l] = two && c.k22 > 0 ? 1 / c.k22 : 0;
        const double det = c.k11 * c.k22 - c.k12 * c.k12;
        // Points so close together that K is nearly singular are one point: the last cases.
        const bool regular = two && det > 1e-12 * c.k11 * c.k22;
        block.regular[l] = regular ? 1 : 0;
        block.inv_det[l] = regular ? 1 / det : 0;
    }
}

// Built for AVX2 and for baseline x86-64 (clones.hpp): the same IEEE operations, lane by lane.
DISCREEL_CLONES void solve_blocks(std::span<BlockRows::Block> blocks,
                                  std::span<BlockBody> bodies) {
    using Block = BlockRows::Block;
    const Lanes zero{};
    for (Block& r : blocks) {
        Ends a = gather(bodies, r.a, r.a_inv_mass, r.a_inv_inertia);
        Ends b = gather(bodies, r.b, r.b_inv_mass, r.b_inv_inertia);
        const Lanes tx = r.normal_y, ty = -r.normal_x;   // -perp(normal)
        friction_at(a, b, r.ra1_x, r.ra1_y, r.rb1_x, r.rb1_y, tx, ty, r.tangent_mass1,
                    r.friction, r.normal1, r.tangent1);
        friction_at(a, b, r.ra2_x, r.ra2_y, r.rb2_x, r.rb2_y, tx, ty, r.tangent_mass2,
                    r.friction, r.normal2, r.tangent2);

        // The normal block: K x + b = w, x >= 0, w >= 0, x_i w_i = 0 (block_solver.cpp).
        const Lanes old1 = r.normal1, old2 = r.normal2;
        Lanes vn1, vn2;
        along(a, b, r.ra1_x, r.ra1_y, r.rb1_x, r.rb1_y, r.normal_x, r.normal_y, vn1);
        along(a, b, r.ra2_x, r.ra2_y, r.rb2_x, r.rb2_y, r.normal_x, r.normal_y, vn2);
        const Lanes b1 = vn1 - r.target1 - (r.k11 * old1 + r.k12 * old2);
        const Lanes b2 = vn2 - r.target2 - (r.k12 * old1 + r.k22 * old2);
        const Mask two = r.two > zero;
        // Both points pushing.
        const Lanes both1 = (-r.k22 * b1 + r.k12 * b2) * r.inv_det;
        const Lanes both2 = (r.k12 * b1 - r.k11 * b2) * r.inv_det;
        const Mask use_both = (r.regular > zero) & two & (both1 >= zero) & (both2 >= zero);
        // Only the first: the second separates by itself (or there is none).
        const Lanes first = -b1 * r.inv_k11;
        const Mask use_first =
            (r.k11 > zero) & (first >= zero) & (~two | (r.k12 * first + b2 >= zero));
        // Only the second.
        const Lanes second = -b2 * r.inv_k22;
        const Mask use_second =
            two & (r.k22 > zero) & (second >= zero) & (r.k12 * second + b1 >= zero);
        const Lanes first_or_none = use_first ? first : zero;
        const Lanes x1 = use_both ? both1 : first_or_none;
        const Lanes second_or_none = use_second ? second : zero;
        const Lanes x2_single = use_first ? zero : second_or_none;
        const Lanes x2 = use_both ? both2 : x2_single;
        const Lanes d1 = x1 - old1, d2 = x2 - old2;
        push(a, b, r.ra1_x, r.ra1_y, r.rb1_x, r.rb1_y, d1 * r.normal_x, d1 * r.normal_y);
        push(a, b, r.ra2_x, r.ra2_y, r.rb2_x, r.rb2_y, d2 * r.normal_x, d2 * r.normal_y);
        r.normal1 = x1;
        r.normal2 = x2;
        scatter(bodies, r.a, a);
        scatter(bodies, r.b, b);
    }
}

void BlockRows::solve(std::span<BlockBody> bodies) { solve_blocks(blocks_, bodies); }

void BlockRows::store(std::span<const RowRef> rows) const {
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const Block& block = blocks_[lane_of_[i] / width];
        const unsigned l = lane_of_[i] % width;
        BlockContact& c = *rows[i].contact;
        c.points[0].normal_impulse = block.normal1[l];
        c.points[0].tangent_impulse = block.tangent1[l];
        if (c.count < 2) continue;
        c.points[1].normal_impulse = block.normal2[l];
        c.points[1].tangent_impulse = block.tangent2[l];
    }
}

}  // namespace discreel::physics::detail
