#pragma once
// The direct solve of one small contact island of the manifold solver: all its points' normal
// and friction impulses at once, as one boxed LCP (lcp.hpp) in double precision, rather than
// pair by pair. An island is what contacts between moving bodies connect (fixed bodies end it);
// iterating over its pairs transfers force from one body to the next by a fraction set by
// their mass ratio per sweep, so a light body between heavy ones never carries their weight,
// while the direct solve is exact at any ratio. The same matrix, normal rows only, pushes
// overlap out of positions: hard correction, all points together.
#include <cstdint>
#include <span>
#include <vector>

#include "block_solver.hpp"
#include "lcp.hpp"

namespace discreel::physics::detail {

struct IslandContact {
    std::uint32_t a = 0, b = 0;    // indices into the bodies
    BlockContact* contact = nullptr;
    std::uint32_t pair = 0;        // the caller's own index of the contact
};

class DirectSolver {
public:
    // Every point's total normal impulse >= 0 with its normal velocity >= its target, one of
    // the two at its bound; friction at most the coefficient times the normal impulse, as the
    // LCP with the friction bounds of the last pass (three passes, from the points' impulses
    // as given: last step's). The points' impulses become the totals and are applied to bodies,
    // which must hold the velocities before any impulse of these contacts. False: not solved
    // (nothing applied).
    bool velocities(std::span<const IslandContact> island, std::span<BlockBody> bodies);
    // The impulses (N s, one per point in island order, >= 0) that stop every point that
    // pushed (normal impulse > 0) from still closing, together, frictionless; 0 for the
    // others. Applies nothing. False: not solved.
    bool stop(std::span<const IslandContact> island, std::span<const BlockBody> bodies,
              std::vector<double>& impulses);
    // Positional impulses (kg m, one per point in island order, >= 0) that leave every point's
    // separation (metres, in `separation`, same order) >= 0, moving each body by its inverse
    // mass times them as an impulse moves its velocity. False: not solved.
    bool positions(std::span<const IslandContact> island, std::span<const BlockBody> bodies,
                   std::span<const double> separation, std::vector<double>& push);

private:
    struct Row {
        std::uint32_t a = 0, b = 0;
        V2 direction = V2::Zero();         // unit; an impulse along it pushes b, -it pushes a
        double arm_a = 0, arm_b = 0;       // cross(r, direction) at each body
    };
    // rows_ and a_ from the island's points: normal rows only, or a normal and a tangent row
    // per point (normal first).
    void build(std::span<const IslandContact> island, std::span<const BlockBody> bodies,
               bool friction);
    void fill_matrix(std::span<const BlockBody> bodies);
    // Point p's row along `direction` (unit).
    static Row row(const IslandContact& ic, const BlockPoint& p, const V2& direction);
    double velocity(const Row& r, std::span<const BlockBody> bodies) const;
    void apply(const Row& r, double impulse, std::span<BlockBody> bodies) const;

    std::vector<Row> rows_;
    std::vector<double> a_, b_, lo_, hi_, x_;
    std::vector<double> normal_;                               // per point, scratch
    std::vector<std::size_t> point_of_row_;                    // scratch of stop()
    BoxedLcp lcp_;
};

}  // namespace discreel::physics::detail
