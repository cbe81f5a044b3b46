#pragma once
// Internal representation shared by the solver stages. Discs come first in World's body array,
// followed by one fixed body per wall feature, so every contact is a pair of body indices.
#include <algorithm>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace discreel::physics::detail {

using V2 = Eigen::Vector2d;

inline double cross(const V2& a, const V2& b) { return a.x() * b.y() - a.y() * b.x(); }
inline V2 perp(const V2& a) { return V2(-a.y(), a.x()); }
// The point of segment [a, b] nearest to x.
inline V2 closest_on_segment(const V2& x, const V2& a, const V2& b) {
    const V2 ab = b - a;
    const double length2 = ab.squaredNorm();
    if (length2 <= 0) return a;
    const double s = std::clamp((x - a).dot(ab) / length2, 0.0, 1.0);
    return a + s * ab;
}

enum class Motion : std::uint8_t {
    dynamic,  // moved by gravity and contacts
    fixed,    // pegs and walls: never moves, infinitely heavy
    held,     // grabbed: follows a scripted path, infinitely heavy to the others
};

struct Body {
    V2 x = V2::Zero();             // metres
    V2 v = V2::Zero();             // m/s
    double angle = 0.0;            // radians
    double omega = 0.0;            // rad/s
    double radius = 0.0;           // metres; 0 for wall features (contact offset is then zero)
    double mass = 0.0;             // kg
    double inertia = 0.0;          // kg m^2, m r^2 / 2
    double inv_mass = 0.0;         // 0 when fixed or held
    double inv_inertia = 0.0;
    double restitution = 0.0;
    double friction = 0.0;
    Motion motion = Motion::fixed;

    // Substep scratch. The impulsive stage applies an impulse at a time tau inside the substep;
    // the body then covers (v_new - v_old) * tau less ground than a start-of-substep impulse
    // would give it, which `shift` and `turn` record so that integration stays exact.
    V2 v_begin = V2::Zero();       // velocity after the impulsive stage, before gravity
    double omega_begin = 0.0;
    V2 shift = V2::Zero();         // metres
    double turn = 0.0;             // radians
    double t_last = 0.0;           // seconds into the substep of its latest impulse
    std::uint32_t strikes = 0;     // impacts applied to it in this substep

    bool moves() const { return motion != Motion::fixed; }
    bool falls() const { return motion == Motion::dynamic; }
};

}  // namespace discreel::physics::detail
