#include "block_rows.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <iterator>
#include <utility>

#include "discreel/clones.hpp"

namespace discreel::physics::detail {
namespace {

using Floats = simd::Float8;
using Mask = decltype(Floats{} < Floats{});
using Velocity = BlockRows::Velocity;

// An end that does not move, in the colouring.
constexpr std::uint32_t still = 0xffffffffu;

// One end of eight rows: its velocity corrections (gathered) and inverse masses (the block's),
// lane by lane.
struct Ends {
    Floats vx, vy, w, pad, inv_mass, inv_inertia;
};

// One end of a block's rows gathered into lanes, and scattered back (simd.hpp). The lanes of a
// block share no record but the scratch one: a colour shares no moving body, a contact row's
// immovable ends have private records, and empty lanes all point at the scratch record and all
// store back the zeros it holds (a pin's immovable ends and empty lanes likewise share the
// pins' still record, whose inverse masses of zero leave it zero).
[[gnu::always_inline]] inline Ends gather(const Velocity* v, const std::uint32_t (&at)[8],
                                          const Floats& inv_mass, const Floats& inv_inertia) {
    Ends e;
    simd::gather8(v, at, e.vx, e.vy, e.w, e.pad);
    e.inv_mass = inv_mass;
    e.inv_inertia = inv_inertia;
    return e;
}

[[gnu::always_inline]] inline void scatter(Velocity* v, const std::uint32_t (&at)[8],
                                           const Ends& e) {
    simd::scatter8(v, at, e.vx, e.vy, e.w, e.pad);
}

// The impulse (px, py) on B, and its opposite on A, at offsets ra and rb.
[[gnu::always_inline]] inline void push(Ends& a, Ends& b, const Floats& ra_x, const Floats& ra_y,
                                        const Floats& rb_x, const Floats& rb_y, const Floats& px,
                                        const Floats& py) {
    a.vx = a.vx - a.inv_mass * px;
    a.vy = a.vy - a.inv_mass * py;
    a.w = a.w - a.inv_inertia * (ra_x * py - ra_y * px);
    b.vx = b.vx + b.inv_mass * px;
    b.vy = b.vy + b.inv_mass * py;
    b.w = b.w + b.inv_inertia * (rb_x * py - rb_y * px);
}

// The corrections' velocity of B's point relative to A's, along (dx, dy), into `out`. (The
// helpers here return vectors through references: a 256-bit vector returned by value is an ABI
// that clang refuses to call without AVX, even inlined.)
[[gnu::always_inline]] inline void along(const Ends& a, const Ends& b, const Floats& ra_x,
                                         const Floats& ra_y, const Floats& rb_x,
                                         const Floats& rb_y, const Floats& dx, const Floats& dy,
                                         Floats& out) {
    const Floats rel_x = (b.vx - b.w * rb_y) - (a.vx - a.w * ra_y);
    const Floats rel_y = (b.vy + b.w * rb_x) - (a.vy + a.w * ra_x);
    out = rel_x * dx + rel_y * dy;
}

// One point's friction: the tangent impulse that stops its sliding, within +- friction times
// its normal impulse (std::clamp's order of tests).
[[gnu::always_inline]] inline void friction_at(Ends& a, Ends& b, const Floats& ra_x,
                                               const Floats& ra_y, const Floats& rb_x,
                                               const Floats& rb_y, const Floats& tx,
                                               const Floats& ty, const Floats& slip,
                                               const Floats& mass, const Floats& friction,
                                               const Floats& normal, Floats& tangent) {
    Floats vt;
    along(a, b, ra_x, ra_y, rb_x, rb_y, tx, ty, vt);
    vt = vt + slip;
    const Floats limit = friction * normal;
    const Floats wanted = tangent - vt * mass;
    const Floats low = -limit;
    const Floats capped = limit < wanted ? limit : wanted;
    const Floats total = wanted < low ? low : capped;
    const Mask active = mass > Floats{};
    const Floats change = active ? total - tangent : Floats{};
    tangent = active ? total : tangent;
    push(a, b, ra_x, ra_y, rb_x, rb_y, change * tx, change * ty);
}

// The warm start: each row's accumulated impulses, applied to the corrections.
DISCREEL_CLONES void warm_blocks(std::span<const BlockRows::Block> blocks, Velocity* records) {
    for (const BlockRows::Block& r : blocks) {
        Ends a = gather(records, r.a, r.a_inv_mass, r.a_inv_inertia);
        Ends b = gather(records, r.b, r.b_inv_mass, r.b_inv_inertia);
        const Floats tx = r.normal_y, ty = -r.normal_x;   // -perp(normal)
        for (unsigned k = 0; k < 2; ++k) {
            push(a, b, r.ra_x[k], r.ra_y[k], r.rb_x[k], r.rb_y[k],
                 r.normal[k] * r.normal_x + r.tangent[k] * tx,
                 r.normal[k] * r.normal_y + r.tangent[k] * ty);
        }
        scatter(records, r.a, a);
        scatter(records, r.b, b);
    }
}

// Built for AVX2 and for baseline x86-64 (clones.hpp): the same IEEE operations, lane by lane.
DISCREEL_CLONES void solve_blocks(std::span<BlockRows::Block> blocks, Velocity* records) {
    using Block = BlockRows::Block;
    const Floats zero{};
    for (Block& r : blocks) {
        Ends a = gather(records, r.a, r.a_inv_mass, r.a_inv_inertia);
        Ends b = gather(records, r.b, r.b_inv_mass, r.b_inv_inertia);
        const Floats tx = r.normal_y, ty = -r.normal_x;   // -perp(normal)
        for (unsigned k = 0; k < 2; ++k) {
            friction_at(a, b, r.ra_x[k], r.ra_y[k], r.rb_x[k], r.rb_y[k], tx, ty, r.slip[k],
                        r.tangent_mass[k], r.friction, r.normal[k], r.tangent[k]);
        }

        // The normal block: K x + b = w, x >= 0, w >= 0, x_i w_i = 0 (block_solver.cpp).
        const Floats old1 = r.normal[0], old2 = r.normal[1];
        Floats vn1, vn2;
        along(a, b, r.ra_x[0], r.ra_y[0], r.rb_x[0], r.rb_y[0], r.normal_x, r.normal_y, vn1);
        along(a, b, r.ra_x[1], r.ra_y[1], r.rb_x[1], r.rb_y[1], r.normal_x, r.normal_y, vn2);
        const Floats b1 = vn1 - r.bias[0] - (r.k11 * old1 + r.k12 * old2);
        const Floats b2 = vn2 - r.bias[1] - (r.k12 * old1 + r.k22 * old2);
        const Mask two = r.two > zero;
        // Both points pushing.
        const Floats both1 = (-r.k22 * b1 + r.k12 * b2) * r.inv_det;
        const Floats both2 = (r.k12 * b1 - r.k11 * b2) * r.inv_det;
        const Mask use_both = (r.regular > zero) & two & (both1 >= zero) & (both2 >= zero);
        // Only the first: the second separates by itself (or there is none).
        const Floats first = -b1 * r.inv_k11;
        const Mask use_first =
            (r.k11 > zero) & (first >= zero) & (~two | (r.k12 * first + b2 >= zero));
        // Only the second.
        const Floats second = -b2 * r.inv_k22;
        const Mask use_second =
            two & (r.k22 > zero) & (second >= zero) & (r.k12 * second + b1 >= zero);
        const Floats first_or_none = use_first ? first : zero;
        const Floats x1 = use_both ? both1 : first_or_none;
        const Floats second_or_none = use_second ? second : zero;
        const Floats x2_single = use_first ? zero : second_or_none;
        const Floats x2 = use_both ? both2 : x2_single;
        const Floats d1 = x1 - old1, d2 = x2 - old2;
        push(a, b, r.ra_x[0], r.ra_y[0], r.rb_x[0], r.rb_y[0], d1 * r.normal_x, d1 * r.normal_y);
        push(a, b, r.ra_x[1], r.ra_y[1], r.rb_x[1], r.rb_y[1], d2 * r.normal_x, d2 * r.normal_y);
        r.normal[0] = x1;
        r.normal[1] = x2;
        scatter(records, r.a, a);
        scatter(records, r.b, b);
    }
}

// The pins: each lane's anchors brought together by the block's inverse, both components at
// once.
DISCREEL_CLONES void solve_pin_blocks(std::span<BlockRows::PinBlock> blocks, Velocity* records) {
    for (BlockRows::PinBlock& r : blocks) {
        Ends a = gather(records, r.a, r.a_inv_mass, r.a_inv_inertia);
        Ends b = gather(records, r.b, r.b_inv_mass, r.b_inv_inertia);
        const Floats rel_x = (b.vx - b.w * r.rb_y) - (a.vx - a.w * r.ra_y);
        const Floats rel_y = (b.vy + b.w * r.rb_x) - (a.vy + a.w * r.ra_x);
        const Floats ex = r.bias_x - rel_x, ey = r.bias_y - rel_y;
        const Floats px = r.i11 * ex + r.i12 * ey;
        const Floats py = r.i12 * ex + r.i22 * ey;
        r.px = r.px + px;
        r.py = r.py + py;
        push(a, b, r.ra_x, r.ra_y, r.rb_x, r.rb_y, px, py);
        scatter(records, r.a, a);
        scatter(records, r.b, b);
    }
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

template <class Ends>
void BlockRows::colour(std::size_t count, std::size_t bodies, Ends&& ends) {
    // Greedy, in the rows' order: each row takes the lowest colour none of its moving bodies
    // has yet.
    used_.assign(bodies, 0);
    colour_of_.resize(count);
    colour_start_.assign(overflow + 2, 0);
    for (std::size_t i = 0; i < count; ++i) {
        const std::array<std::uint32_t, 2> end = ends(i);
        std::uint64_t taken = 0;
        for (const std::uint32_t e : end) taken |= e != still ? used_[e] : 0;
        const auto c = static_cast<unsigned>(std::countr_one(taken));
        colour_of_[i] = static_cast<std::uint8_t>(c);
        ++colour_start_[c + 1];
        if (c == overflow) continue;
        for (const std::uint32_t e : end) {
            if (e != still) used_[e] |= std::uint64_t{1} << c;
        }
    }
    // Each colour starts on a block; an overflow row has a block to itself.
    colour_start_[overflow + 1] *= width;
    for (unsigned c = 0; c <= overflow; ++c) {
        const std::uint32_t n = colour_start_[c + 1];
        colour_start_[c + 1] = colour_start_[c] + (n + width - 1) / width * width;
    }
}

// The bodies that rows with these moving ends move, ascending.
template <class Ends>
void moved_by(std::size_t count, std::size_t bodies, Ends&& ends,
              std::vector<std::uint64_t>& scratch, std::vector<std::uint32_t>& out) {
    scratch.assign(bodies, 0);
    for (std::size_t i = 0; i < count; ++i) {
        for (const std::uint32_t e : ends(i)) {
            if (e != still) scratch[e] = 1;
        }
    }
    out.clear();
    for (std::size_t i = 0; i < bodies; ++i) {
        if (scratch[i] != 0) out.push_back(static_cast<std::uint32_t>(i));
    }
}

void BlockRows::lay_out(std::span<const RowRef> rows, std::span<const BlockBody> bodies) {
    const std::size_t n = bodies.size();
    layout_.resize(rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) layout_[i] = key_of(rows[i], bodies);
    bodies_at_layout_ = n;
    const auto ends = [&](std::size_t i) {
        return std::array<std::uint32_t, 2>{(layout_[i] & 2) != 0 ? rows[i].a : still,
                                            (layout_[i] & 1) != 0 ? rows[i].b : still};
    };
    colour(rows.size(), n, ends);
    std::uint32_t copies = 0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        for (const std::uint32_t e : ends(i)) copies += e == still ? 1 : 0;
    }
    moved_by(rows.size(), n, ends, used_, rows_moved_);
    // A row end on an immovable body gets its own record, so that rows on one wall do not
    // chain through one record.
    const auto scratch = static_cast<std::uint32_t>(n + 1 + copies);
    velocities_.assign(n + copies + 2, Velocity{});
    auto copy = static_cast<std::uint32_t>(n + 1);
    place(rows.size(), ends, [&](std::uint32_t e) { return e != still ? e : copy++; }, scratch,
          blocks_, lane_of_);
}

template <class B, class Ends, class Record>
void BlockRows::place(std::size_t count, Ends&& ends, Record&& record, std::uint32_t empty,
                      std::vector<B>& blocks, std::vector<std::uint32_t>& lane_of) {
    blocks.assign(colour_start_[overflow + 1] / width, B{});
    for (B& block : blocks) {
        std::fill(std::begin(block.a), std::end(block.a), empty);
        std::fill(std::begin(block.b), std::end(block.b), empty);
    }
    lane_of.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        const unsigned c = colour_of_[i];
        const std::uint32_t slot = colour_start_[c];
        colour_start_[c] += c == overflow ? width : 1;
        lane_of[i] = slot;
        B& block = blocks[slot / width];
        const auto [a, b] = ends(i);
        block.a[slot % width] = record(a);
        block.b[slot % width] = record(b);
    }
}

BlockRows::PinKey BlockRows::pin_key(const PinRef& p, std::span<const BlockBody> bodies) {
    const auto moves = [&](std::uint32_t i) {
        return i < bodies.size() && (bodies[i].inv_mass > 0 || bodies[i].inv_inertia > 0);
    };
    return {p.a, p.b, (moves(p.a) ? 2u : 0u) | (moves(p.b) ? 1u : 0u)};
}

void BlockRows::lay_out_pins(std::span<const PinRef> pins, std::span<const BlockBody> bodies) {
    const std::size_t n = bodies.size();
    pin_layout_.resize(pins.size());
    for (std::size_t i = 0; i < pins.size(); ++i) pin_layout_[i] = pin_key(pins[i], bodies);
    bodies_at_pin_layout_ = n;
    const auto ends = [&](std::size_t i) {
        const PinKey& k = pin_layout_[i];
        return std::array<std::uint32_t, 2>{(k[2] & 2) != 0 ? k[0] : still,
                                            (k[2] & 1) != 0 ? k[1] : still};
    };
    colour(pins.size(), n, ends);
    moved_by(pins.size(), n, ends, used_, pins_moved_);
    // Immovable ends and empty lanes share the pins' still record (index n): its corrections
    // are zero and stay so, as their inverse masses are.
    const auto still_record = static_cast<std::uint32_t>(n);
    place(pins.size(), ends, [&](std::uint32_t e) { return e != still ? e : still_record; },
          still_record, pin_blocks_, pin_lane_of_);
}

void BlockRows::merge_moved() {
    moved_.clear();
    std::set_union(rows_moved_.begin(), rows_moved_.end(), pins_moved_.begin(),
                   pins_moved_.end(), std::back_inserter(moved_));
}

void BlockRows::fill(const RowRef& r, std::span<const BlockBody> bodies, Block& block,
                     unsigned l) const {
    const BlockBody& a = bodies[r.a];
    const BlockBody& b = bodies[r.b];
    prepare_block(*r.contact, a, b);
    const BlockContact& c = *r.contact;
    const double unit = mass_unit_;
    const auto f = [](double x) { return static_cast<float>(x); };
    const bool two = c.count > 1;
    // A single point's second does nothing: no offset, no mass, no impulse, and a 1 where the
    // block would divide by it. Every field is written: a lane kept from the last layout may
    // have held two points.
    block.a_inv_mass[l] = f(a.inv_mass * unit);
    block.a_inv_inertia[l] = f(a.inv_inertia * unit);
    block.b_inv_mass[l] = f(b.inv_mass * unit);
    block.b_inv_inertia[l] = f(b.inv_inertia * unit);
    block.normal_x[l] = f(c.normal.x());
    block.normal_y[l] = f(c.normal.y());
    block.friction[l] = f(c.friction);
    block.two[l] = two ? 1 : 0;
    fill_bounds(r, bodies, block, l);
    const BlockPoint none{};
    for (unsigned k = 0; k < 2; ++k) {
        const bool used = k < static_cast<unsigned>(c.count);
        const BlockPoint& p = used ? c.points[k] : none;
        block.ra_x[k][l] = f(p.ra.x());
        block.ra_y[k][l] = f(p.ra.y());
        block.rb_x[k][l] = f(p.rb.x());
        block.rb_y[k][l] = f(p.rb.y());
        block.tangent_mass[k][l] = f(p.tangent_mass / unit);
        block.normal[k][l] = f(p.normal_impulse / unit);
        block.tangent[k][l] = f(p.tangent_impulse / unit);
    }
    const double k11 = c.k11 * unit;
    const double k12 = two ? c.k12 * unit : 0;
    const double k22 = two ? c.k22 * unit : 1;
    block.k11[l] = f(k11);
    block.k12[l] = f(k12);
    block.k22[l] = f(k22);
    block.inv_k11[l] = c.k11 > 0 ? f(1 / k11) : 0;
    block.inv_k22[l] = two && c.k22 > 0 ? f(1 / k22) : 0;
    const double det = k11 * k22 - k12 * k12;
    // Points so close together that K is nearly singular are one point (the last cases): in
    // single precision a condition number over about 1 000 would amplify the rounding of the
    // velocities into the impulses (Box2D v2.4's bound).
    const bool regular = two && det > 1e-3 * k11 * k22;
    block.regular[l] = regular ? 1 : 0;
    block.inv_det[l] = regular ? f(1 / det) : 0;
}

void BlockRows::fill_bounds(const RowRef& r, std::span<const BlockBody> bodies, Block& block,
                            unsigned l) {
    // The velocities at build(), folded into the bounds in doubles: each point's bias (its
    // target less its normal velocity) and slip (its tangential velocity). A single point's
    // second has neither.
    const BlockContact& c = *r.contact;
    const V2 tangent(c.normal.y(), -c.normal.x());
    for (unsigned k = 0; k < 2; ++k) {
        const bool used = k < static_cast<unsigned>(c.count);
        const V2 rel = used ? relative_velocity(c.points[k], bodies[r.a], bodies[r.b])
                            : V2(V2::Zero());
        const double target = used ? c.points[k].target : 0.0;
        block.bias[k][l] = static_cast<float>(target - rel.dot(c.normal));
        block.slip[k][l] = static_cast<float>(rel.dot(tangent));
    }
}

void BlockRows::fill_pin(const PinRef& p, std::span<const BlockBody> bodies, PinBlock& block,
                         unsigned l) const {
    const BlockBody world{};
    const BlockBody& a = p.a < bodies.size() ? bodies[p.a] : world;
    const BlockBody& b = p.b < bodies.size() ? bodies[p.b] : world;
    const double unit = mass_unit_;
    const auto f = [](double x) { return static_cast<float>(x); };
    block.a_inv_mass[l] = f(a.inv_mass * unit);
    block.a_inv_inertia[l] = f(a.inv_inertia * unit);
    block.b_inv_mass[l] = f(b.inv_mass * unit);
    block.b_inv_inertia[l] = f(b.inv_inertia * unit);
    block.ra_x[l] = f(p.ra.x());
    block.ra_y[l] = f(p.ra.y());
    block.rb_x[l] = f(p.rb.x());
    block.rb_y[l] = f(p.rb.y());
    // The inverse in doubles; none where the block is singular (neither end can move the
    // anchors), as the joints' own 2x2 solve.
    const double k11 = p.k11 * unit, k12 = p.k12 * unit, k22 = p.k22 * unit;
    const double det = k11 * k22 - k12 * k12;
    const double inv_det = std::abs(det) > 0 ? 1 / det : 0;
    block.i11[l] = f(k22 * inv_det);
    block.i12[l] = f(-k12 * inv_det);
    block.i22[l] = f(k11 * inv_det);
    // The velocities at build(), folded into the bias in doubles.
    const V2 rel = velocity_at(b, p.rb) - velocity_at(a, p.ra);
    block.bias_x[l] = f(p.target.x() - rel.x());
    block.bias_y[l] = f(p.target.y() - rel.y());
    block.px[l] = 0;
    block.py[l] = 0;
}

void BlockRows::build(std::span<const RowRef> rows, std::span<const PinRef> pins,
                      std::span<const BlockBody> bodies) {
    // The colours and lanes hold while the rows are those of the last layout, the same pairs
    // in the same order with the same bodies movable: a resting pile lays out rarely, a
    // jointed scene's pins once.
    const bool laid_out = same_layout(rows, bodies);
    if (!laid_out) lay_out(rows, bodies);
    bool pins_laid_out = pins.size() == pin_layout_.size() && bodies.size() == bodies_at_pin_layout_;
    for (std::size_t i = 0; pins_laid_out && i < pins.size(); ++i) {
        const PinKey key = pin_key(pins[i], bodies);
        const PinKey& was = pin_layout_[i];
        pins_laid_out = key[0] == was[0] && key[1] == was[1] && key[2] == was[2];
    }
    if (!pins_laid_out) lay_out_pins(pins, bodies);
    if (!laid_out || !pins_laid_out) merge_moved();
    const double unit_before = mass_unit_;
    // The mass unit: a power of two at the heaviest moving body's mass (scaling by it is exact).
    double lightest_inverse = HUGE_VAL;
    start_.resize(bodies.size());
    for (const std::uint32_t i : moved_) {
        start_[i] = bodies[i];
        velocities_[i] = Velocity{};
        if (bodies[i].inv_mass > 0) {
            lightest_inverse = std::min(lightest_inverse, bodies[i].inv_mass);
        }
    }
    mass_unit_ =
        std::isfinite(lightest_inverse) ? std::ldexp(1.0, std::ilogb(1 / lightest_inverse)) : 1;
    const bool kept = laid_out && mass_unit_ == unit_before;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        Block& block = blocks_[lane_of_[i] / width];
        const unsigned lane = lane_of_[i] % width;
        if (kept && rows[i].unchanged) {
            fill_bounds(rows[i], bodies, block, lane);
        } else {
            fill(rows[i], bodies, block, lane);
        }
    }
    for (std::size_t i = 0; i < pins.size(); ++i) {
        fill_pin(pins[i], bodies, pin_blocks_[pin_lane_of_[i] / width], pin_lane_of_[i] % width);
    }
    // The bodies' double velocities hold none of the rows' impulses yet: the warm start is
    // the first change of the corrections.
    taken_.assign(rows.size(), {});
    pin_taken_.assign(pins.size(), V2::Zero());
    warm_blocks(blocks_, velocities_.data());
}

void BlockRows::solve(int pin_passes) {
    solve_blocks(blocks_, velocities_.data());
    for (int pass = 0; pass < pin_passes; ++pass) solve_pin_blocks(pin_blocks_, velocities_.data());
}

void BlockRows::flush(std::span<BlockBody> bodies) const {
    for (const std::uint32_t i : moved_) {
        const simd::Float4& d = velocities_[i].packed;
        bodies[i].v = start_[i].v + V2(d[0], d[1]);
        bodies[i].omega = start_[i].omega + d[2];
    }
}

void BlockRows::reload(std::span<const BlockBody> bodies) {
    for (const std::uint32_t i : moved_) {
        const V2 dv = bodies[i].v - start_[i].v;
        velocities_[i].packed = simd::Float4{static_cast<float>(dv.x()), static_cast<float>(dv.y()),
                                             static_cast<float>(bodies[i].omega - start_[i].omega),
                                             0.0F};
    }
    for (std::size_t i = 0; i < taken_.size(); ++i) taken_[i] = impulses_of(i);
    for (std::size_t i = 0; i < pin_taken_.size(); ++i) pin_taken_[i] = pin_impulse(i);
}

V2 BlockRows::pin_impulse(std::size_t i) const {
    const PinBlock& block = pin_blocks_[pin_lane_of_[i] / width];
    const unsigned l = pin_lane_of_[i] % width;
    return V2(block.px[l], block.py[l]) * mass_unit_;
}

std::array<double, 4> BlockRows::impulses_of(std::size_t i) const {
    const Block& block = blocks_[lane_of_[i] / width];
    const unsigned l = lane_of_[i] % width;
    return {block.normal[0][l] * mass_unit_, block.normal[1][l] * mass_unit_,
            block.tangent[0][l] * mass_unit_, block.tangent[1][l] * mass_unit_};
}

void BlockRows::finish(std::span<const RowRef> rows, std::span<const PinRef> pins,
                       std::span<BlockBody> bodies) const {
    BlockBody world{};
    for (std::size_t i = 0; i < pins.size(); ++i) {
        const PinRef& p = pins[i];
        const V2 now = pin_impulse(i);
        BlockBody& a = p.a < bodies.size() ? bodies[p.a] : world;
        BlockBody& b = p.b < bodies.size() ? bodies[p.b] : world;
        const V2 change = now - pin_taken_[i];
        a.v -= a.inv_mass * change;
        a.omega -= a.inv_inertia * cross(p.ra, change);
        b.v += b.inv_mass * change;
        b.omega += b.inv_inertia * cross(p.rb, change);
        if (p.impulse != nullptr) *p.impulse += now;
    }
    for (std::size_t i = 0; i < rows.size(); ++i) {
        BlockContact& c = *rows[i].contact;
        const V2 tangent(c.normal.y(), -c.normal.x());
        const std::array<double, 4> now = impulses_of(i);
        for (int k = 0; k < c.count; ++k) {
            const auto q = static_cast<std::size_t>(k);
            BlockPoint& p = c.points[k];
            apply_impulse(bodies[rows[i].a], bodies[rows[i].b], p,
                          (now[q] - taken_[i][q]) * c.normal +
                              (now[q + 2] - taken_[i][q + 2]) * tangent);
            p.normal_impulse = now[q];
            p.tangent_impulse = now[q + 2];
        }
    }
}

}  // namespace discreel::physics::detail
