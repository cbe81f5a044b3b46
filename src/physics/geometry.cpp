#include "geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace discreel::physics::detail {
namespace {

// Smallest s in [0, s_max] with c0 + c1 s + c2 s^2 = 0, given c0 > 0 (separated now).
std::optional<double> first_root(double c0, double c1, double c2, double s_max) {
    if (c2 == 0.0) {
        if (c1 >= 0.0) return std::nullopt;
        const double s = -c0 / c1;
        return s <= s_max ? std::optional<double>(s) : std::nullopt;
    }
    const double disc = c1 * c1 - 4.0 * c2 * c0;
    if (disc < 0.0) return std::nullopt;
    const double sq = std::sqrt(disc);
    // Cancellation-free pair of roots: q / c2 and c0 / q.
    const double q = -0.5 * (c1 >= 0.0 ? c1 + sq : c1 - sq);
    double best = std::numeric_limits<double>::infinity();
    for (double s : {q / c2, q != 0.0 ? c0 / q : best}) {
        if (s >= 0.0 && s < best) best = s;
    }
    return best <= s_max ? std::optional<double>(best) : std::nullopt;
}

// A point with trajectory p (relative to a fixed circle of radius R at the origin), linear
// motion along the chord from t_min to t_max.
std::optional<Impact> impact_circle(const Trajectory& p, double R, double t_min, double t_max) {
    const V2 p0 = p.at(t_min);
    const V2 chord = (p.at(t_max) - p0) / (t_max - t_min);
    const double c0 = p0.squaredNorm() - R * R;
    if (c0 <= 0.0) {
        // Touching or overlapping already: an impact now if closing.
        if (p0.dot(p.v + p.g * t_min) >= 0.0) return std::nullopt;
        const double n = p0.norm();
        return Impact{t_min, n > 0.0 ? V2(p0 / n) : V2(V2::UnitY())};
    }
    const auto s = first_root(c0, 2.0 * p0.dot(chord), chord.squaredNorm(), t_max - t_min);
    if (!s) return std::nullopt;
    const V2 at = p0 + chord * *s;
    const double n = at.norm();
    return Impact{t_min + *s, n > 0.0 ? V2(at / n) : V2(V2::UnitY())};
}

// Gap to the plane {y: m.(y - q) = 0}, offset by `reach`, along trajectory p: exact quadratic.
std::optional<double> impact_plane(const Trajectory& p, const V2& q, const V2& m, double reach,
                                   double t_min, double t_max) {
    const double g0 = m.dot(p.at(t_min) - q) - reach;
    const double rate = m.dot(p.v + p.g * t_min);
    if (g0 <= 0.0) return rate < 0.0 ? std::optional<double>(t_min) : std::nullopt;
    const auto s = first_root(g0, rate, 0.5 * m.dot(p.g), t_max - t_min);
    if (!s) return std::nullopt;
    return t_min + *s;
}

}  // namespace

std::vector<Feature> features_of(const std::vector<WallDef>& walls) {
    std::vector<Feature> out;
    for (std::size_t i = 0; i < walls.size(); ++i) {
        const WallDef& w = walls[i];
        if (w.shape == WallDef::Shape::box) {
            const V2 lo(std::min(w.a.x, w.b.x), std::min(w.a.y, w.b.y));
            const V2 hi(std::max(w.a.x, w.b.x), std::max(w.a.y, w.b.y));
            const V2 points[4] = {lo, lo, hi, hi};
            const V2 normals[4] = {V2(0, 1), V2(1, 0), V2(0, -1), V2(-1, 0)};
            for (int k = 0; k < 4; ++k) {
                Feature f;
                f.kind = Feature::Kind::plane;
                f.wall = i;
                f.a = points[k];
                f.b = normals[k];
                f.box_min = lo;
                f.box_max = hi;
                out.push_back(f);
            }
        } else {
            Feature f;
            f.kind = Feature::Kind::capsule;
            f.wall = i;
            f.a = to_v2(w.a);
            f.b = to_v2(w.b);
            f.half_thickness = 0.5 * w.thickness;
            out.push_back(f);
        }
    }
    return out;
}

Proximity disc_capsule(const V2& x, double r, const Feature& f) {
    const V2 q = closest_on_segment(x, f.a, f.b);
    const V2 d = x - q;
    const double dist = d.norm();
    V2 n;
    if (dist > 0.0) {
        n = d / dist;
    } else {
        const V2 ab = f.b - f.a;
        n = ab.squaredNorm() > 0.0 ? V2(perp(ab).normalized()) : V2(V2::UnitY());
    }
    return {n, dist - r - f.half_thickness};
}

std::optional<Impact> impact_disc_disc(const Trajectory& a, double ra, const Trajectory& b,
                                       double rb, double t_min, double t_max) {
    const Trajectory rel{a.x0 - b.x0, a.v - b.v, a.g - b.g};
    return impact_circle(rel, ra + rb, t_min, t_max);
}

std::optional<Impact> impact_disc_feature(const Trajectory& a, double r, const Feature& f,
                                          double t_min, double t_max) {
    if (f.kind == Feature::Kind::plane) {
        const auto t = impact_plane(a, f.a, f.b, r, t_min, t_max);
        if (!t) return std::nullopt;
        return Impact{*t, f.b};
    }
    const double reach = r + f.half_thickness;
    std::optional<Impact> best;
    auto consider = [&](const std::optional<Impact>& hit) {
        if (hit && (!best || hit->t < best->t)) best = hit;
    };
    // End caps.
    consider(impact_circle(Trajectory{a.x0 - f.a, a.v, a.g}, reach, t_min, t_max));
    consider(impact_circle(Trajectory{a.x0 - f.b, a.v, a.g}, reach, t_min, t_max));
    // The long face on the disc's side, valid where the contact lies within the segment.
    const V2 ab = f.b - f.a;
    const double len2 = ab.squaredNorm();
    if (len2 > 0.0) {
        V2 m = perp(ab).normalized();
        if (m.dot(a.at(t_min) - f.a) < 0.0) m = -m;
        if (const auto t = impact_plane(a, f.a, m, reach, t_min, t_max)) {
            const double s = (a.at(*t) - f.a).dot(ab) / len2;
            if (s >= 0.0 && s <= 1.0) consider(Impact{*t, m});
        }
    }
    return best;
}

}  // namespace discreel::physics::detail
