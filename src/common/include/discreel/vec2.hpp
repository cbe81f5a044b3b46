#pragma once
// A plain 2-D vector for public interfaces. Modules do their arithmetic in their own types
// (physics uses Eigen internally); this keeps third-party types out of public headers.

namespace discreel {

struct Vec2 {
    double x = 0.0;
    double y = 0.0;
    friend bool operator==(const Vec2&, const Vec2&) = default;
};

}  // namespace discreel
