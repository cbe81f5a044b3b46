#include "toi.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace discreel::physics::detail {
namespace {

// A shape's core in world coordinates: its vertices and its edges (a circle's one edge is a
// point, a capsule's its segment).
struct Core {
    std::array<V2, max_polygon_vertices> points;
    int count = 0;
    int edges = 0;

    Core(const Polygon& shape, const Transform& xf) : count(shape.count) {
        for (int i = 0; i < count; ++i) points[static_cast<std::size_t>(i)] = xf.apply(shape.vertices[i]);
        edges = count >= 3 ? count : 1;
    }
    const V2& start(int e) const { return points[static_cast<std::size_t>(e)]; }
    const V2& end(int e) const {
        return points[static_cast<std::size_t>(count >= 3 ? (e + 1) % count : count - 1)];
    }
    // Inside or on the boundary of a polygon core (count >= 3, counter-clockwise).
    bool contains(const V2& p) const {
        if (count < 3) return false;
        for (int e = 0; e < count; ++e) {
            if (cross(end(e) - start(e), p - start(e)) < 0) return false;
        }
        return true;
    }
};

bool segments_cross(const V2& a, const V2& b, const V2& c, const V2& d) {
    const double o1 = cross(b - a, c - a), o2 = cross(b - a, d - a);
    const double o3 = cross(d - c, a - c), o4 = cross(d - c, b - c);
    return ((o1 < 0 && o2 > 0) || (o1 > 0 && o2 < 0)) && ((o3 < 0 && o4 > 0) || (o3 > 0 && o4 < 0));
}

}  // namespace

std::optional<Distance> distance(const Polygon& a, const Transform& xa, const Polygon& b,
                                 const Transform& xb) {
    const Core ca(a, xa), cb(b, xb);
    double best = HUGE_VAL;
    V2 from = V2::Zero(), to = V2::Zero();
    const auto consider = [&](const V2& pa, const V2& pb) {
        const double d2 = (pb - pa).squaredNorm();
        if (d2 < best) {
            best = d2;
            from = pa;
            to = pb;
        }
    };
    // Between two disjoint segments the closest pair has an endpoint on one side; crossing
    // segments mean the cores overlap.
    for (int i = 0; i < ca.edges; ++i) {
        const V2 &a0 = ca.start(i), &a1 = ca.end(i);
        for (int j = 0; j < cb.edges; ++j) {
            const V2 &b0 = cb.start(j), &b1 = cb.end(j);
            if (segments_cross(a0, a1, b0, b1)) return std::nullopt;
            consider(a0, closest_on_segment(a0, b0, b1));
            consider(a1, closest_on_segment(a1, b0, b1));
            consider(closest_on_segment(b0, a0, a1), b0);
            consider(closest_on_segment(b1, a0, a1), b1);
        }
    }
    if (best <= 0 || cb.contains(ca.points[0]) || ca.contains(cb.points[0])) return std::nullopt;
    const double core = std::sqrt(best);
    const V2 normal = (to - from) / core;
    const V2 point = 0.5 * ((from + a.radius * normal) + (to - b.radius * normal));
    return Distance{core - a.radius - b.radius, normal, point};
}

TimeOfImpact time_of_impact(const Polygon& a, const Sweep& sa, const Polygon& b, const Sweep& sb,
                            const ImpactQuery& q) {
    const double spin = std::abs(sa.omega) * sa.bound + std::abs(sb.omega) * sb.bound;
    double t = q.t_begin, safe = q.t_begin, safe_gap = 0;
    for (int it = 0;; ++it) {
        const std::optional<Distance> d = distance(a, sa.at(t), b, sb.at(t));
        if (it == 0 && (!d || d->distance <= q.target + q.tolerance)) {
            return {TimeOfImpact::Kind::touching, t, d ? d->distance : 0};
        }
        if (!d) {
            // Spin carried the surfaces past the first-order bound: the touch lies between the
            // last time known apart and now, found by bisection.
            double lo = safe, hi = t, gap = safe_gap;
            for (int k = 0; k < 40 && gap > q.target + q.tolerance; ++k) {
                const double mid = 0.5 * (lo + hi);
                const std::optional<Distance> dm = distance(a, sa.at(mid), b, sb.at(mid));
                if (dm && dm->distance > q.target) {
                    lo = mid;
                    gap = dm->distance;
                } else {
                    hi = mid;
                }
            }
            return {TimeOfImpact::Kind::hit, lo, gap};
        }
        if (d->distance <= q.target + q.tolerance || it == q.max_iterations) {
            return {TimeOfImpact::Kind::hit, t, d->distance};
        }
        const double closing = (sa.v - sb.v).dot(d->normal) + spin;
        if (closing <= 0) return {TimeOfImpact::Kind::apart, t, d->distance};
        safe = t;
        safe_gap = d->distance;
        t += (d->distance - q.target) / closing;
        if (t >= q.t_end) return {TimeOfImpact::Kind::apart, q.t_end, d->distance};
    }
}

double inner_radius(const Polygon& shape) {
    if (shape.count < 3) return shape.radius;
    double inner = HUGE_VAL;
    for (int i = 0; i < shape.count; ++i) inner = std::min(inner, shape.normals[i].dot(shape.vertices[i]));
    return std::max(0.0, inner) + shape.radius;
}

}  // namespace discreel::physics::detail
