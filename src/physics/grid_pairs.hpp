#pragma once
// The one pair search of both broad phases: which circles of a set overlap. The disc solver's
// circles are its discs grown by their margins (broad_phase.hpp), the manifold solver's the
// circles around its bodies' fattened bounding boxes (fat_pairs.hpp); each broad phase decides
// for itself how long its list holds. Circles are binned by centre into a uniform grid of cells
// twice the largest ordinary radius wide, so each is compared with those of its own and the
// neighbouring cells only: linear in the number of circles. A circle much larger than the
// typical one (a long wall's, a very fast body's) would force huge cells on everyone; it is
// compared with every other one instead.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry.hpp"

namespace discreel::physics::detail {

// A pair of bodies as one sortable key: the lower index in the high half.
inline std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
    return (static_cast<std::uint64_t>(a) << 32) | b;
}

// Sorts pair keys (a << 32 | b, both below body_count) in ascending order. scratch and count
// are scratch space, kept by the caller so that a rebuild does not reallocate them.
void sort_pair_keys(std::vector<std::uint64_t>& keys, std::size_t body_count,
                    std::vector<std::uint64_t>& scratch, std::vector<std::uint32_t>& count);

struct GridCircle {
    V2 centre = V2::Zero();   // metres
    double radius = 0;        // metres
    bool moves = false;       // a pair of two circles that do not move is never wanted
};

class GridPairs {
public:
    // Appends to `pairs`, in no particular order, pair_key(i, j) (i < j, indices into
    // `circles`) of every two circles that overlap or touch, at least one of which moves.
    void find(std::span<const GridCircle> circles, std::vector<std::uint64_t>& pairs);
    // Whether the last find() hashed its cells (the circles spread too far apart to number the
    // cells row by row in a table of twice their count).
    bool hashed() const { return hashed_; }

private:
    // A circle in the grid, with what the search needs of it.
    struct Item {
        V2 x = V2::Zero();             // m, centre
        double radius = 0.0;           // m
        std::int64_t cell_x = 0, cell_y = 0;
        std::uint32_t index = 0;
        bool moves = false;
    };
    struct CellBuckets;   // which bucket of the table holds a cell (grid_pairs.cpp)

    // The stages of find(): the circles of cells `cell` wide (those up to `limit` in radius)
    // copied into items_ by bucket; each one met with those after it in its own and the
    // neighbouring cells, cells numbered row by row or hashed; each oversized circle met with
    // every other.
    CellBuckets bin(std::span<const GridCircle> circles, double limit, double cell);
    static void meet(const Item& item, const Item& other, std::vector<std::uint64_t>& pairs);
    void meet_in_rows(std::uint64_t row, std::vector<std::uint64_t>& pairs) const;
    void meet_hashed(const CellBuckets& bucket, std::vector<std::uint64_t>& pairs) const;
    void meet_oversized(std::span<const GridCircle> circles, double limit,
                        std::vector<std::uint64_t>& pairs) const;

    bool hashed_ = false;
    // Scratch kept to avoid reallocating every search.
    std::vector<std::uint32_t> bucket_start_;
    std::vector<std::uint32_t> fill_;
    std::vector<Item> items_;      // grouped by bucket
    std::vector<std::int64_t> cell_x_, cell_y_;
    std::vector<std::uint32_t> oversized_;
};

}  // namespace discreel::physics::detail
