#pragma once
// The scene the rendering benches share: discs covering about a fifth of a 12.8 x 7.2 m box,
// moving without gravity or losses, so every frame differs from the last (what makes x264 work
// hard).
#include <cmath>
#include <sstream>
#include <string>

namespace discreel::bench {

// `discs` discs at width x height, 60 fps, `frames` frames.
inline std::string gas_scene(int discs, int width, int height, int frames) {
    const double radius = std::sqrt(0.2 * 12.8 * 7.2 / (M_PI * discs));
    std::ostringstream yaml;
    yaml << "version: 1\nvideo:\n  size: [" << width << ", " << height << "]\n  fps: 60\n"
         << "  duration: " << frames / 60.0 << "\nphysics:\n  gravity: [0, 0]\n"
         << "  restitution: 1.0\n  friction: 0\n  seed: 7\n"
         << "walls:\n  - box: [[0, 0], [12.8, 7.2]]\n"
         << "discs:\n  - random:\n      count: " << discs << "\n"
         << "      region: [[0.1, 0.1], [12.7, 7.1]]\n"
         << "      radius: [" << 0.7 * radius << ", " << radius << "]\n"
         << "      speed: [0.5, 2]\n"
         << "      colors: [\"#e4572e\", \"#76b041\", \"#17bebb\", \"#f4d35e\"]\n";
    return yaml.str();
}

}  // namespace discreel::bench
