#pragma once
// The velocity iterations of many contact manifolds, four at a time: each manifold is one row
// (its two points' normal impulses solved together as a 2x2 block, block_solver.hpp, and a
// friction impulse per point), and rows are coloured so that no two rows of a colour share a
// moving body. A colour's rows are independent, so four of them run in the lanes of one vector
// (simd.hpp), each lane doing the IEEE operations one row alone would: the same bits on every
// CPU. The block's four cases are all computed and the first that holds is selected, as the
// scalar solve tries them in order, without a branch.
//
// Rows read and write the solver's body states directly; an immovable body (wall, peg, held
// body) is never changed by a row, so rows of one colour may share it.
#include <cstdint>
#include <span>
#include <vector>

#include "block_solver.hpp"
#include "simd.hpp"

namespace discreel::physics::detail {

struct RowRef {
    std::uint32_t a = 0, b = 0;    // body indices
    BlockContact* contact = nullptr;   // prepared (prepare_block), impulses accumulated
};

class BlockRows {
public:
    // Lays out `rows` by colour; `bodies` must hold one more record than there are bodies, a
    // scratch record (zero velocity, zero inverse masses) that empty lanes point at.
    void build(std::span<const RowRef> rows, std::span<const BlockBody> bodies);
    // One pass over every row, colour by colour, in the order build() was given within one.
    void solve(std::span<BlockBody> bodies);
    // The accumulated impulses back into the rows' contacts.
    void store(std::span<const RowRef> rows) const;

    using Lanes = simd::Double4;
    static constexpr unsigned width = 4;
    // Rows whose bodies have all 64 colours go to one last group, a row to a block.
    static constexpr unsigned overflow = 64;

    // 32-byte aligned for the AVX2 build's loads: a 256-bit vector type is only 16-byte
    // aligned where the baseline target has no 256-bit registers.
    struct alignas(32) Block {
        std::uint32_t a[width] = {}, b[width] = {};
        // The ends' inverse masses: the iterations never change them, so only velocities are
        // gathered.
        Lanes a_inv_mass{}, a_inv_inertia{}, b_inv_mass{}, b_inv_inertia{};
        Lanes normal_x{}, normal_y{};
        Lanes ra1_x{}, ra1_y{}, rb1_x{}, rb1_y{}, ra2_x{}, ra2_y{}, rb2_x{}, rb2_y{};
        Lanes k11{}, k12{}, k22{};
        Lanes inv_k11{}, inv_k22{}, inv_det{};   // 0 where not usable
        Lanes regular{};                         // 1 where the 2x2 block is well-conditioned
        Lanes two{};                             // 1 for two points, 0 for one
        Lanes tangent_mass1{}, tangent_mass2{};
        Lanes target1{}, target2{};
        Lanes friction{};
        Lanes normal1{}, normal2{}, tangent1{}, tangent2{};   // accumulated impulses
    };

private:
    static std::uint64_t key_of(const RowRef& r, std::span<const BlockBody> bodies);
    bool same_layout(std::span<const RowRef> rows, std::span<const BlockBody> bodies) const;
    void lay_out(std::span<const RowRef> rows, std::span<const BlockBody> bodies);

    std::vector<Block> blocks_;
    std::vector<std::uint64_t> layout_;        // per row at the last layout: bodies, movable
    std::size_t bodies_at_layout_ = 0;
    std::vector<std::uint32_t> lane_of_;       // per row: block * width + lane
    std::vector<std::uint64_t> used_;          // scratch: per body, colours taken
    std::vector<std::uint8_t> colour_of_;      // scratch: per row
    std::vector<std::uint32_t> colour_start_;  // scratch
};

}  // namespace discreel::physics::detail
