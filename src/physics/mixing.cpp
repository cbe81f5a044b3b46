// Material mixing (docs/physics.md): the bouncier material wins, so a rubber ball bounces on
// any floor and a clay ball on none only if both are clay; friction is the geometric mean, so
// ice (0) on anything slides freely.
#include <algorithm>
#include <cmath>

#include "discreel/physics.hpp"

namespace discreel::physics {

double mix_restitution(double a, double b) { return std::max(a, b); }

double mix_friction(double a, double b) { return std::sqrt(a * b); }

}  // namespace discreel::physics
