#pragma once
// The velocity iterations of many contact manifolds, eight at a time: each manifold is one row
// (its two points' normal impulses solved together as a 2x2 block, block_solver.hpp, and a
// friction impulse per point), and rows are coloured so that no two rows of a colour share a
// moving body. A colour's rows are independent, so eight of them run in the lanes of one vector
// (simd.hpp), each lane doing the IEEE operations one row alone would: the same bits on every
// CPU. The block's four cases are all computed and the first that holds is selected, as the
// scalar solve tries them in order, without a branch.
//
// Pins (revolute joints without motor or limits, joint.hpp) are rows here too: each keeps B's
// anchor on A's with both components solved together (a 2x2 block by its inverse), coloured
// on their own and solved after the contacts in each pass, on the same corrections. The same
// rows solve the joints' position stage, where the corrections are displacements (m) and
// turns (rad) instead of velocities.
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

// A pin's point row: its anchors' relative velocity brought to `target`.
struct PinRef {
    std::uint32_t a = 0, b = 0;   // body indices; at or past the bodies' count: the world
    V2 ra = V2::Zero(), rb = V2::Zero();   // offsets from the centroids, metres
    double k11 = 0, k12 = 0, k22 = 0;      // how an impulse moves the relative velocity, 1/kg
    V2 target = V2::Zero();                // m/s
    V2* impulse = nullptr;   // accumulated, N s: finish() adds the rows' impulses (if set)
};

class BlockRows {
public:
    // Lays out `rows` by colour, prepares their contacts (prepare_block), builds them from the
    // bodies' velocities now and applies the contacts' impulses (the warm start) to the
    // corrections.
    // Pins start from no impulse: their warm start is the caller's.
    void build(std::span<const RowRef> rows, std::span<const PinRef> pins,
               std::span<const BlockBody> bodies);
    void build(std::span<const RowRef> rows, std::span<const BlockBody> bodies) {
        build(rows, {}, bodies);
    }
    // One pass over every contact row, colour by colour, in the order build() was given within
    // one, then `pin_passes` over the pins.
    void solve(int pin_passes = 1);
    // Before a solve in doubles between two passes: the bodies the rows move get their
    // velocities at build() plus the corrections so far.
    void flush(std::span<BlockBody> bodies) const;
    // After it: the corrections taken again from the bodies' velocities now.
    void reload(std::span<const BlockBody> bodies);
    // The end: each row's impulses (since the last reload, if any) applied to its bodies in
    // doubles, pairwise, so that momentum is kept to double rounding; and the accumulated
    // impulses back into the rows' contacts and the pins' impulses.
    void finish(std::span<const RowRef> rows, std::span<const PinRef> pins,
                std::span<BlockBody> bodies) const;
    void finish(std::span<const RowRef> rows, std::span<BlockBody> bodies) const {
        finish(rows, {}, bodies);
    }

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

    struct alignas(32) PinBlock {
        std::uint32_t a[width] = {}, b[width] = {};   // indices into the velocity records
        Floats a_inv_mass{}, a_inv_inertia{}, b_inv_mass{}, b_inv_inertia{};
        Floats ra_x{}, ra_y{}, rb_x{}, rb_y{};   // metres
        Floats i11{}, i12{}, i22{};   // the inverse of the 2x2 block, mass units
        // m/s: the target less the anchors' relative velocity at build().
        Floats bias_x{}, bias_y{};
        Floats px{}, py{};            // accumulated since build(), mass units m/s
    };

private:
    // A pin's ends and whether each moves.
    using PinKey = std::array<std::uint32_t, 3>;
    static PinKey pin_key(const PinRef& p, std::span<const BlockBody> bodies);
    void lay_out_pins(std::span<const PinRef> pins, std::span<const BlockBody> bodies);
    void fill_pin(const PinRef& p, std::span<const BlockBody> bodies, PinBlock& block,
                  unsigned l) const;
    V2 pin_impulse(std::size_t i) const;   // N s
    // The bodies either kind of row moves, ascending.
    void merge_moved();
    // Each of `count` rows a lane of its colour's blocks (colour() before; an overflow row a
    // block of its own), in the rows' order within a colour, into lane_of; its ends' records
    // record(end) (`ends(i)`, still for an immovable one); empty lanes point at `empty`.
    template <class B, class Ends, class Record>
    void place(std::size_t count, Ends&& ends, Record&& record, std::uint32_t empty,
               std::vector<B>& blocks, std::vector<std::uint32_t>& lane_of);
    // A greedy colouring of rows with the ends `ends(i)` (moving ones only, index or -1),
    // into colour_of_ and colour_start_ (the counts per colour, then their starts in lanes,
    // each colour starting on a block).
    template <class Ends>
    void colour(std::size_t count, std::size_t bodies, Ends&& ends);

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
    // Per body, then the pins' immovable ends' (one for all), then one per contact row end on
    // an immovable body (all zeros: it never changes, its velocity is folded into the row),
    // then the empty lanes' scratch one.
    std::vector<Velocity> velocities_;
    std::vector<std::uint32_t> moved_;         // the bodies the rows and pins move, ascending
    std::vector<std::uint32_t> rows_moved_;    // those the contact rows move
    std::vector<std::uint32_t> pins_moved_;    // those the pins move
    std::vector<PinBlock> pin_blocks_;
    std::vector<PinKey> pin_layout_;           // per pin at the last layout
    std::size_t bodies_at_pin_layout_ = 0;
    std::vector<std::uint32_t> pin_lane_of_;   // per pin: block * width + lane
    std::vector<V2> pin_taken_;                // per pin: what the double velocities hold, N s
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
