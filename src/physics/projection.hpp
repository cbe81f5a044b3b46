#pragma once
// The disc solver's last stage of a substep (projection.cpp).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "substep.hpp"

namespace discreel::physics::detail {

// Stage 3: overlap left by unconverged iterations is removed by moving positions only, so it
// never turns into velocity (and kinetic energy). A class only to keep its scratch array.
class PositionProjector {
public:
    void set_mixing(const Mixing& mixing) { mixing_ = mixing; }
    void project(Substep& s, int iterations);
    // Puts back discs that crossed a wall the stages did not see: those that moved farther
    // than their reach (metres) from where they started the substep.
    void contain_runaways(Substep& s, const std::vector<V2>& start,
                                 const std::vector<double>& reach) const {
        for (std::size_t i = 0; i < s.disc_count; ++i) {
            contain_runaway(s.bodies, s.disc_count, s.features, i, start[i], reach[i]);
        }
    }
    // The same for disc i alone (each disc is handled on its own), so that the last substep of
    // a step can leave it to the world's pass over the discs at the end of the step.
    void contain_runaway(std::vector<Body>& bodies, std::size_t disc_count,
                                const std::vector<Feature>& features, std::size_t i,
                                const V2& start, double reach) const {
        // Up to a thousandth of its radius beyond the reach is let through (see projection.cpp).
        const Body& a = bodies[i];
        const V2 path = a.x - start;
        const double unseen = reach + 1e-3 * a.radius;
        if (path.squaredNorm() <= unseen * unseen || !a.falls()) return;  // held: scripted
        stop_at_wall(bodies, disc_count, features, i, start);
    }

private:
    // Moves a and b of contact c apart by most of their overlap; false if they hardly overlap.
    static bool push_apart(Substep& s, const Contact& c);
    // contain_runaway's rare case: disc i moved farther than its reach from `start`.
    void stop_at_wall(std::vector<Body>& bodies, std::size_t disc_count,
                      const std::vector<Feature>& features, std::size_t i, const V2& start) const;
    Mixing mixing_;                           // the world's materials' mixing
    std::vector<std::uint32_t> overlapping_;  // contacts pushed by the first sweep
    std::vector<std::uint32_t> walls_;        // active contacts with a wall
};

}  // namespace discreel::physics::detail
