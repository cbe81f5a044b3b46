// Material mixing (docs/physics.md): the bouncier material wins, so a rubber ball bounces on
// any floor and a clay ball on none only if both are clay; friction is the geometric mean, so
// ice (0) on anything slides freely.
#include <algorithm>
#include <cmath>

#include "discreel/physics.hpp"

namespace discreel::physics {

double mix(MixRule rule, double a, double b) {
    switch (rule) {
    case MixRule::max: return std::max(a, b);
    case MixRule::min: return std::min(a, b);
    case MixRule::mean: return std::sqrt(a * b);
    case MixRule::product: return a * b;
    }
    return std::max(a, b);
}

double mix_restitution(double a, double b) { return Mixing{}.restitution_of(a, b); }

double mix_friction(double a, double b) { return Mixing{}.friction_of(a, b); }

}  // namespace discreel::physics
