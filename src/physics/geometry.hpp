#pragma once
// Shapes and distance queries. Walls are split into features: a box becomes four inward-facing
// planes (each bounded by the box, acting only on discs whose centre is inside it), a segment
// becomes a capsule of radius thickness / 2.
#include <cstddef>
#include <optional>
#include <vector>

#include "body.hpp"
#include "discreel/physics.hpp"

namespace discreel::physics::detail {

struct Feature {
    enum class Kind { plane, capsule };
    Kind kind = Kind::plane;
    std::size_t wall = 0;          // index into WorldDef::walls
    V2 a = V2::Zero();             // plane: a point on it; capsule: start
    V2 b = V2::Zero();             // plane: inward unit normal; capsule: end
    double half_thickness = 0.0;   // capsule radius, metres
    V2 box_min = V2::Zero();       // plane: the box it belongs to
    V2 box_max = V2::Zero();
};

std::vector<Feature> features_of(const std::vector<WallDef>& walls);

// Does the feature act on a disc centred at x? (Box planes only act on discs inside the box.)
// Inline, like the plane case of disc_feature: the broad phase asks it of every disc and wall.
inline bool feature_applies(const Feature& f, const V2& x) {
    if (f.kind == Feature::Kind::capsule) return true;
    return x.x() >= f.box_min.x() && x.x() <= f.box_max.x() && x.y() >= f.box_min.y() &&
           x.y() <= f.box_max.y();
}

struct Proximity {
    V2 normal = V2::UnitY();       // unit, from the other body towards the disc
    double gap = 0.0;              // metres, negative when overlapping
};

// Inline: it runs for every contact several times per substep.
inline Proximity disc_disc(const V2& xa, double ra, const V2& xb, double rb) {
    const V2 d = xa - xb;
    const double dist = d.norm();
    // Coincident centres have no direction; any fixed one keeps the result deterministic.
    const V2 n = dist > 0.0 ? V2(d / dist) : V2(V2::UnitY());
    return {n, dist - ra - rb};
}

// True when centres this far apart (squared distance d2) are certainly more than `gap` apart
// at the surfaces, i.e. disc_disc(...).gap > gap, decided without a square root. The relative
// slack of 1e-9 dwarfs the rounding of both sides, so it never disagrees with disc_disc.
inline bool certainly_farther(double d2, double radius_sum, double gap) {
    const double reach = radius_sum + gap;
    return reach < 0.0 || d2 > reach * reach * (1.0 + 1e-9);
}
// disc_feature's capsule case.
Proximity disc_capsule(const V2& x, double r, const Feature& f);
// Inline: the plane case is one dot product, asked of every wall contact several times per
// substep.
inline Proximity disc_feature(const V2& x, double r, const Feature& f) {
    if (f.kind == Feature::Kind::plane) return {f.b, f.b.dot(x - f.a) - r};
    return disc_capsule(x, r, f);
}

// A body's motion during a substep, valid from t_min on: x(t) = x0 + v t + g t^2 / 2.
struct Trajectory {
    V2 x0 = V2::Zero();
    V2 v = V2::Zero();
    V2 g = V2::Zero();
    V2 at(double t) const { return x0 + v * t + g * (0.5 * t * t); }
};

struct Impact {
    double t = 0.0;                // seconds into the substep
    V2 normal = V2::UnitY();       // unit, from the other body towards the disc, at time t
};

// First time in [t_min, t_max] at which the disc (radius r, trajectory a) touches the other
// body, if it does while approaching. Plane faces are solved exactly (the gap is quadratic in
// t); round features use the chord of the relative trajectory, which matches it at both ends
// of the substep and is off by at most |g| t_max^2 / 8 in between.
std::optional<Impact> impact_disc_disc(const Trajectory& a, double ra, const Trajectory& b,
                                       double rb, double t_min, double t_max);
std::optional<Impact> impact_disc_feature(const Trajectory& a, double r, const Feature& f,
                                          double t_min, double t_max);

}  // namespace discreel::physics::detail
