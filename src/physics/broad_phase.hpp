#pragma once
// Finds the pairs that can touch during the next step. Discs are binned by centre into a
// hashed uniform grid whose cells hold fattened discs (radius + margin); the pair list is
// reused across steps until some disc has used up its margin, so a resting pile rebuilds
// rarely. Cost is linear in the number of discs; pairs come out sorted by (a, b).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "body.hpp"
#include "contact.hpp"
#include "geometry.hpp"

namespace discreel::physics::detail {

class BroadPhase {
public:
    // Keeps `contacts` holding every pair that can come into contact during the next step of
    // length dt, sorted by (a, b); pairs that stay keep their warm-start impulses and history.
    // True when it rebuilt the list (contact indices changed).
    bool update(const std::vector<Body>& bodies, std::size_t disc_count,
                const std::vector<Feature>& features, double dt, double gravity,
                std::vector<Contact>& contacts);

private:
    bool still_valid(const std::vector<Body>& bodies, std::size_t disc_count, double dt,
                     double gravity) const;
    void rebuild(const std::vector<Body>& bodies, std::size_t disc_count,
                 const std::vector<Feature>& features, double dt, double gravity,
                 std::vector<Contact>& contacts);

    // Sorts pairs_ by (a, b); every index is below body_count.
    void sort_pairs(std::size_t body_count);

    bool built_ = false;
    std::vector<V2> anchor_;        // centres at the last rebuild
    std::vector<double> margin_;    // metres each disc may move before a rebuild

    // A disc in the grid, with what the pair search needs of it.
    struct GridItem {
        V2 x = V2::Zero();             // m, centre
        double fat = 0.0;              // m, radius + margin
        std::int64_t cell_x = 0, cell_y = 0;
        std::uint32_t body = 0;
        bool moves = false;
    };

    // Scratch kept to avoid reallocating every rebuild.
    std::vector<std::uint64_t> pairs_;
    std::vector<std::uint64_t> sorted_;
    std::vector<std::uint32_t> digit_count_;
    std::vector<std::uint32_t> bucket_start_;
    std::vector<std::uint32_t> fill_;
    std::vector<GridItem> items_;      // grouped by bucket
    std::vector<std::int64_t> cell_x_, cell_y_;
    std::vector<Contact> merged_;
};

}  // namespace discreel::physics::detail
