#pragma once
// The velocity iterations of many contact manifolds, eight at a time: each manifold is one row
// (its two points' normal impulses solved together as a 2x2 block, block_solver.hpp, and a
// friction impulse per point), and rows are coloured so that no two rows of a colour share a
// moving body. A colour's rows are independent, so eight of them run in the lanes of one vector
// (simd.hpp), each lane doing the IEEE operations one row alone would: the same bits on every
// CPU. The block's four cases are all computed and the first that holds is selected, as the
// scalar solve tries them in order, without a branch.
//
// As in the disc solver's rows (contact_solver.hpp), the iterations run in single precision on
// corrections only: each row is built in doubles with its bodies' velocities at build() folded
// into its bounds, and floats carry each body's change of velocity, added to its double
// velocity by flush(). A body no row moves keeps its velocity bit for bit; the rounding left is
// about 1e-7 of the corrections. Masses and impulses are in units of a power of two near the
// heaviest moving body's mass, which keeps them inside a float's range whatever the scene's
// masses.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "block_solver.hpp"
#include "simd.hpp"

namespace discreel::physics::detail {

struct RowRef {
    std::uint32_t a = 0, b = 0;    // body indices
    BlockContact* contact = nullptr;   // impulses accumulated; build() prepares it
    // Its contact's normal, offsets, friction and impulses are as the last build() left them
    // (and finish() wrote them): while the layout and the mass unit hold, only the bounds
    // that fold in the velocities are built again.
    bool unchanged = false;
};

class BlockRows {
public:
    // Lays out `rows` by colour, prepares their contacts (prepare_block), builds them from the
    // bodies' velocities now and applies the contacts' impulses (the warm start) to the
    // corrections.
    void build(std::span<const RowRef> rows, std::span<const BlockBody> bodies);
    // One pass over every row, colour by colour, in the order build() was given within one.
    void solve();
    // Before a solve in doubles between two passes: the bodies the rows move get their
    // velocities at build() plus the corrections so far.
    void flush(std::span<BlockBody> bodies) const;
    // After it: the corrections taken again from the bodies' velocities now.
    void reload(std::span<const BlockBody> bodies);
    // The end: each row's impulses (since the last reload, if any) applied to its bodies in
    // doubles, pairwise, so that momentum is kept to double rounding; and the accumulated
    // impulses back into the rows' contacts.
    void finish(std::span<const RowRef> rows, std::span<BlockBody> bodies) const;

    using Floats = simd::Float8;
    static constexpr unsigned width = 8;
    // Rows whose bodies have all 64 colours go to one last group, a row to a block.
    static constexpr unsigned overflow = 64;

    // What the iterations change of a body: dv x, dv y (m/s), d omega (rad/s), and a pad, in
    // one 16-byte record that a block gathers with one load (simd.hpp's transposes).
    struct alignas(16) Velocity {
        simd::Float4 packed = {};
    };
    // 32-byte aligned for the AVX2 build's loads: a 256-bit vector type is only 16-byte
    // aligned where the baseline target has no 256-bit registers.
    struct alignas(32) Block {
        std::uint32_t a[width] = {}, b[width] = {};   // indices into the velocity records
        // The ends' inverse masses in mass units: the iterations never change them, so only
        // velocities are gathered.
        Floats a_inv_mass{}, a_inv_inertia{}, b_inv_mass{}, b_inv_inertia{};
        Floats normal_x{}, normal_y{};
        Floats k11{}, k12{}, k22{};               // mass units
        Floats inv_k11{}, inv_k22{}, inv_det{};   // 0 where not usable
        Floats regular{};                         // 1 where the 2x2 block is well-conditioned
        Floats two{};                             // 1 for two points, 0 for one
        Floats friction{};
        // Per point of the manifold (a single point's second is all zeros):
        Floats ra_x[2]{}, ra_y[2]{}, rb_x[2]{}, rb_y[2]{};   // metres
        Floats tangent_mass[2]{};                 // mass units
        // m/s: the point's target less its normal velocity at build(), the bound on the
        // corrections' normal velocity; and its tangential velocity at build().
        Floats bias[2]{}, slip[2]{};
        Floats normal[2]{}, tangent[2]{};         // accumulated impulses, mass units m/s
    };

private:
    static std::uint64_t key_of(const RowRef& r, std::span<const BlockBody> bodies);
    bool same_layout(std::span<const RowRef> rows, std::span<const BlockBody> bodies) const;
    void lay_out(std::span<const RowRef> rows, std::span<const BlockBody> bodies);
    void fill(const RowRef& r, std::span<const BlockBody> bodies, Block& block, unsigned l) const;
    // The bounds only: each point's bias and slip from the bodies' velocities now.
    static void fill_bounds(const RowRef& r, std::span<const BlockBody> bodies, Block& block,
                            unsigned l);
    // Row i's accumulated impulses (normal, normal, tangent, tangent), N s.
    std::array<double, 4> impulses_of(std::size_t i) const;

    std::vector<Block> blocks_;
    // Per row: its points' impulses (normal, normal, tangent, tangent; N s) that the bodies'
    // double velocities already hold: none after build(), all at the last reload().
    std::vector<std::array<double, 4>> taken_;
    // Per body, then one per row end on an immovable body (all zeros: it never changes, its
    // velocity is folded into the row), then the empty lanes' scratch one.
    std::vector<Velocity> velocities_;
    std::vector<std::uint32_t> moved_;         // the bodies the rows move, ascending
    std::vector<BlockBody> start_;             // per body: its velocities at build()
    double mass_unit_ = 1;                     // kg, a power of two
    std::vector<std::uint64_t> layout_;        // per row at the last layout: bodies, movable
    std::size_t bodies_at_layout_ = 0;
    std::vector<std::uint32_t> lane_of_;       // per row: block * width + lane
    std::vector<std::uint64_t> used_;          // scratch: per body, colours taken
    std::vector<std::uint8_t> colour_of_;      // scratch: per row
    std::vector<std::uint32_t> colour_start_;  // scratch
};

}  // namespace discreel::physics::detail
