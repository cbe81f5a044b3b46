#include "manifold.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace discreel::physics::detail {
namespace {

// Feature ids: which vertex or edge of each shape a point comes from, a byte each.
std::uint16_t make_id(int a, int b) {
    return static_cast<std::uint16_t>((a & 0xff) << 8 | (b & 0xff));
}

// Circle against circle: centres c1, c2 (world), radii summed.
Manifold circles(const Polygon& a, const Transform& xa, const Polygon& b, const Transform& xb,
                 double speculative) {
    Manifold m;
    const V2 ca = xa.apply(a.vertices[0]), cb = xb.apply(b.vertices[0]);
    const V2 d = cb - ca;
    const double distance = d.norm();
    const double separation = distance - a.radius - b.radius;
    if (separation > speculative) return m;
    m.normal = distance > 0 ? V2(d / distance) : V2(V2::UnitY());
    const V2 on_a = ca + a.radius * m.normal, on_b = cb - b.radius * m.normal;
    m.points[0] = {0.5 * (on_a + on_b), separation, 0};
    m.count = 1;
    return m;
}

// A polygon (1..8 vertices swept by its radius, so capsules too) against a circle, by the
// Voronoi regions of the polygon's core: the face the circle's centre is most in front of,
// or, beyond a face's ends, the nearest vertex.
Manifold polygon_circle(const Polygon& a, const Transform& xa, const Polygon& b,
                        const Transform& xb, double speculative) {
    Manifold m;
    const V2 c = xa.inverse_apply(xb.apply(b.vertices[0]));   // the circle in A's frame
    const double radius = a.radius + b.radius;
    // The face of greatest separation.
    int face = 0;
    double best = -std::numeric_limits<double>::max();
    for (int i = 0; i < a.count; ++i) {
        const double s = a.normals[i].dot(c - a.vertices[i]);
        if (s > best) {
            best = s;
            face = i;
        }
    }
    if (best - radius > speculative) return m;
    const V2& v1 = a.vertices[face];
    const V2& v2 = a.vertices[(face + 1) % a.count];
    V2 normal;
    V2 closest;
    int feature = face;
    const double along1 = (c - v1).dot(v2 - v1);
    const double along2 = (c - v2).dot(v1 - v2);
    if (along1 <= 0) {
        closest = v1;
    } else if (along2 <= 0) {
        closest = v2;
        feature = (face + 1) % a.count;
    } else {
        normal = a.normals[face];
        closest = c - best * normal;
    }
    double separation = best;
    if (along1 <= 0 || along2 <= 0) {
        const V2 d = c - closest;
        const double distance = d.norm();
        separation = distance;
        normal = distance > 0 ? V2(d / distance) : a.normals[face];
    }
    separation -= radius;
    if (separation > speculative) return m;
    const V2 on_a = closest + a.radius * normal, on_b = c - b.radius * normal;
    m.normal = xa.rotate(normal);
    m.points[0] = {xa.apply(0.5 * (on_a + on_b)), separation, make_id(feature, 0)};
    m.count = 1;
    return m;
}

// Greatest separation of `poly` (in its frame) from `other` (in the same frame) along poly's
// face normals: the face and the distance.
std::pair<int, double> max_separation(const Polygon& poly, const Polygon& other) {
    int face = 0;
    double best = -std::numeric_limits<double>::max();
    for (int i = 0; i < poly.count; ++i) {
        const V2& n = poly.normals[i];
        double deepest = std::numeric_limits<double>::max();
        for (int j = 0; j < other.count; ++j) {
            deepest = std::min(deepest, n.dot(other.vertices[j] - poly.vertices[i]));
        }
        if (deepest > best) {
            best = deepest;
            face = i;
        }
    }
    return {face, best};
}

// A reference face [v1, v2] and an incident face [w1, w2] that do not overlap sideways (corner
// against corner): the contact is between their nearest points, along the line joining them,
// one point. Faces in the same frame; `radius` the two radii summed, `ref_radius` the
// reference shape's; the normal from the reference shape to the incident one.
struct CornerContact {
    V2 normal = V2::UnitY();
    V2 point = V2::Zero();       // midway between the surfaces
    double separation = 0;       // metres
};
std::optional<CornerContact> corner_to_corner(const V2& v1, const V2& v2, const V2& w1,
                                              const V2& w2, double radius, double ref_radius) {
    // Between two segments that do not cross, the nearest pair has an end on one of them.
    const std::array<std::pair<V2, V2>, 4> candidates{{{v1, closest_on_segment(v1, w1, w2)},
                                                       {v2, closest_on_segment(v2, w1, w2)},
                                                       {closest_on_segment(w1, v1, v2), w1},
                                                       {closest_on_segment(w2, v1, v2), w2}}};
    const auto* best = &candidates[0];
    for (const auto& c : candidates) {
        if ((c.second - c.first).squaredNorm() < (best->second - best->first).squaredNorm()) {
            best = &c;
        }
    }
    const double distance = (best->second - best->first).norm();
    if (distance <= 0) return std::nullopt;
    CornerContact c;
    c.normal = (best->second - best->first) / distance;
    c.separation = distance - radius;
    c.point = best->first + c.normal * (ref_radius + 0.5 * c.separation);
    return c;
}

// `poly`'s core in another frame: `to` is where its own frame lies in that one. Only the
// vertices and normals in use are written.
void into_frame(const Polygon& poly, const Transform& to, Polygon& out) {
    out.count = poly.count;
    out.radius = poly.radius;
    for (int i = 0; i < poly.count; ++i) {
        out.vertices[i] = to.apply(poly.vertices[i]);
        out.normals[i] = to.rotate(poly.normals[i]);
    }
}

// Polygon against polygon (capsules included: two vertices, two opposite faces) by separating
// axes on the cores, then the reference face (the one of the axis found) clipped against the
// incident face of the other (the one most against the reference normal): up to two points.
// Everything in A's frame: B is moved into it once.
Manifold polygons(const Polygon& a, const Transform& xa, const Polygon& b, const Transform& xb,
                  double speculative) {
    Manifold m;
    const double radius = a.radius + b.radius;
    // Where B's frame lies in A's: its offset and its turn against A (cos, sin of the angle
    // difference).
    const Transform b_to_a{xa.inverse_rotate(xb.p - xa.p), xa.c * xb.c + xa.s * xb.s,
                           xa.c * xb.s - xa.s * xb.c};
    Polygon b_in_a;
    into_frame(b, b_to_a, b_in_a);
    const auto [face_a, separation_a] = max_separation(a, b_in_a);
    if (separation_a - radius > speculative) return m;
    const auto [face_b, separation_b] = max_separation(b_in_a, a);
    if (separation_b - radius > speculative) return m;
    // The reference is A unless B's axis separates clearly more: the bias (half a millimetre)
    // keeps the choice, and so the feature ids, from flickering between two nearly equal axes
    // (a box resting flat on a box) from one step to the next.
    constexpr double axis_bias = 5e-4;
    const bool flip = separation_b > separation_a + axis_bias;
    const Polygon& ref = flip ? b_in_a : a;
    const Polygon& inc = flip ? a : b_in_a;
    const int face = flip ? face_b : face_a;
    const V2& normal = ref.normals[face];
    const V2& v1 = ref.vertices[face];
    const V2& v2 = ref.vertices[(face + 1) % ref.count];

    // Incident face: the one of `inc` whose normal is most against the reference normal.
    int incident = 0;
    double most_against = std::numeric_limits<double>::max();
    for (int i = 0; i < inc.count; ++i) {
        const double d = normal.dot(inc.normals[i]);
        if (d < most_against) {
            most_against = d;
            incident = i;
        }
    }
    V2 clip[2] = {inc.vertices[incident], inc.vertices[(incident + 1) % inc.count]};
    int clip_ids[2] = {incident, (incident + 1) % inc.count};
    // Clip the incident segment to the reference face's side planes.
    const V2 tangent = (v2 - v1).normalized();
    const double lower = tangent.dot(v1), upper = tangent.dot(v2);
    for (int side = 0; side < 2; ++side) {
        // How far each end lies outside the side plane: before v1 (side 0) or past v2 (1).
        const auto outside = [&](const V2& p) {
            const double along = tangent.dot(p);
            return side == 0 ? lower - along : along - upper;
        };
        const double d0 = outside(clip[0]), d1 = outside(clip[1]);
        if (d0 > 0 && d1 > 0) {
            // The faces do not overlap sideways: corner against corner. Without a point here
            // such a pair would have no contact at all and close unchecked within the step.
            const std::optional<CornerContact> c = corner_to_corner(
                v1, v2, inc.vertices[incident], inc.vertices[(incident + 1) % inc.count], radius,
                ref.radius);
            if (!c || c->separation > speculative) return m;
            const V2 world_normal = xa.rotate(c->normal);
            m.normal = flip ? V2(-world_normal) : world_normal;
            const int corner = 0x40 | incident;
            const std::uint16_t id =
                flip ? make_id(corner, face | 0x40) : make_id(face | 0x40, corner);
            m.points[0] = {xa.apply(c->point), c->separation, id};
            m.count = 1;
            return m;
        }
        if (d0 > 0 || d1 > 0) {
            const V2 cut = clip[0] + (d0 / (d0 - d1)) * (clip[1] - clip[0]);
            const int k = d0 > 0 ? 0 : 1;
            clip[k] = cut;
            // A clipped point belongs to the reference face's end vertex, flagged apart from
            // the incident shape's own vertices.
            clip_ids[k] = 0x80 | (side == 0 ? face : (face + 1) % ref.count);
        }
    }
    const V2 world_normal = xa.rotate(normal);
    m.normal = flip ? V2(-world_normal) : world_normal;
    for (int k = 0; k < 2; ++k) {
        const double separation = normal.dot(clip[k] - v1) - radius;
        if (separation > speculative) continue;
        // Midway between the surfaces: from the incident core point, back along the normal
        // by its radius and half the separation.
        const double inc_radius = flip ? a.radius : b.radius;
        const V2 point = clip[k] - normal * (inc_radius + 0.5 * separation);
        const std::uint16_t id = flip ? make_id(clip_ids[k], face) : make_id(face, clip_ids[k]);
        m.points[m.count++] = {xa.apply(point), separation, id};
    }
    return m;
}

enum class ShapeClass { circle, polygon };

ShapeClass class_of(const Polygon& p) {
    return p.count == 1 ? ShapeClass::circle : ShapeClass::polygon;
}

using PairFunction = Manifold (*)(const Polygon&, const Transform&, const Polygon&,
                                  const Transform&, double);

Manifold circle_polygon(const Polygon& a, const Transform& xa, const Polygon& b,
                        const Transform& xb, double speculative) {
    Manifold m = polygon_circle(b, xb, a, xa, speculative);
    m.normal = -m.normal;
    return m;
}

// [class of A][class of B]
constexpr PairFunction pair_functions[2][2] = {
    {circles, circle_polygon},
    {polygon_circle, polygons},
};

}  // namespace

Manifold collide(const Polygon& a, const Transform& xa, const Polygon& b, const Transform& xb,
                 double speculative) {
    return pair_functions[static_cast<int>(class_of(a))][static_cast<int>(class_of(b))](
        a, xa, b, xb, speculative);
}

}  // namespace discreel::physics::detail
