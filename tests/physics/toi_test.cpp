// Distances and times of impact between shapes (toi.hpp), against hand-worked geometry: the
// closest features of boxes, circles and capsules in any pose, and the first touch of moving,
// spinning bodies, never after it and within the tolerance asked.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>
#include <numbers>
#include <optional>

#include <gtest/gtest.h>

#include "shape.hpp"
#include "toi.hpp"

namespace discreel::physics::detail {
namespace {

constexpr double pi = std::numbers::pi;

Polygon box(double w, double h, double rounding = 0) { return *make_box(w, h, rounding); }

TEST(DistanceTest, ClosestFeaturesInAnyPose) {
    // Face to face: unit boxes 3 m apart centre to centre.
    std::optional<Distance> d = distance(box(1, 1), Transform::of({0, 0}, 0), box(1, 1),
                                         Transform::of({3, 0}, 0));
    ASSERT_TRUE(d);
    EXPECT_NEAR(d->distance, 2.0, 1e-12);
    EXPECT_NEAR(d->normal.x(), 1.0, 1e-12);
    EXPECT_NEAR(d->point.x(), 1.5, 1e-12);
    // Corner to corner: the second turned 45 degrees, its corner on the line y = 0.
    d = distance(box(1, 1), Transform::of({0, 0}, 0), box(1, 1), Transform::of({3, 0.5}, pi / 4));
    ASSERT_TRUE(d);
    EXPECT_NEAR(d->distance, 3 - std::sqrt(0.5) - 0.5, 1e-12);
    // A circle (radius 0.25) off a box's corner, and a rounded box: radii come off the core.
    d = distance(box(1, 1), Transform::of({0, 0}, 0), make_circle(0.25), Transform::of({1.5, 1.5}, 0));
    ASSERT_TRUE(d);
    EXPECT_NEAR(d->distance, std::sqrt(2.0) - 0.25, 1e-12);
    EXPECT_NEAR(d->normal.x(), std::sqrt(0.5), 1e-12);
    d = distance(box(1, 1, 0.1), Transform::of({0, 0}, 0), *make_capsule(2, 0.2),
                 Transform::of({0, 2}, 0));
    ASSERT_TRUE(d);
    EXPECT_NEAR(d->distance, 2 - 0.5 - 0.2, 1e-12);
    // Cores crossing, or one inside the other: no distance.
    EXPECT_FALSE(distance(box(1, 1), Transform::of({0, 0}, 0), box(1, 1), Transform::of({0.9, 0.2}, 0.3)));
    EXPECT_FALSE(distance(box(2, 2), Transform::of({0, 0}, 0), box(0.5, 0.5), Transform::of({0.1, 0}, 0)));
}

// The closest pair of two cores by brute force: every vertex of each against every edge of
// the other (a circle's core is its point, a capsule's its segment); nothing when the cores
// overlap (an edge crossing, or one's vertex inside the other).
std::optional<double> brute_force_core_distance(const Polygon& a, const Transform& xa,
                                                const Polygon& b, const Transform& xb) {
    const auto world = [](const Polygon& p, const Transform& xf) {
        std::vector<V2> points;
        for (int i = 0; i < p.count; ++i) points.push_back(xf.apply(p.vertices[i]));
        return points;
    };
    const std::vector<V2> pa = world(a, xa), pb = world(b, xb);
    const auto edges = [](const std::vector<V2>& p) {
        std::vector<std::pair<V2, V2>> e;
        if (p.size() == 1) e.emplace_back(p[0], p[0]);
        if (p.size() == 2) e.emplace_back(p[0], p[1]);
        if (p.size() >= 3)
            for (std::size_t i = 0; i < p.size(); ++i) e.emplace_back(p[i], p[(i + 1) % p.size()]);
        return e;
    };
    const auto to_segment = [](const V2& p, const std::pair<V2, V2>& e) {
        const V2 d = e.second - e.first;
        const double l2 = d.squaredNorm();
        const double t = l2 > 0 ? std::clamp((p - e.first).dot(d) / l2, 0.0, 1.0) : 0.0;
        return (e.first + t * d - p).norm();
    };
    const auto inside = [](const std::vector<V2>& poly, const V2& p) {
        if (poly.size() < 3) return false;
        for (std::size_t i = 0; i < poly.size(); ++i)
            if (cross(poly[(i + 1) % poly.size()] - poly[i], p - poly[i]) < 0) return false;
        return true;
    };
    const auto crossing = [](const std::pair<V2, V2>& e, const std::pair<V2, V2>& f) {
        const double o1 = cross(e.second - e.first, f.first - e.first);
        const double o2 = cross(e.second - e.first, f.second - e.first);
        const double o3 = cross(f.second - f.first, e.first - f.first);
        const double o4 = cross(f.second - f.first, e.second - f.first);
        return o1 * o2 < 0 && o3 * o4 < 0;
    };
    double best = HUGE_VAL;
    for (const auto& e : edges(pa)) {
        for (const auto& f : edges(pb)) {
            if (crossing(e, f)) return std::nullopt;
            best = std::min({best, to_segment(e.first, f), to_segment(e.second, f),
                             to_segment(f.first, e), to_segment(f.second, e)});
        }
    }
    if (inside(pb, pa[0]) || inside(pa, pb[0])) return std::nullopt;
    return best;
}

// GJK against the brute force on 20 000 random pairs of circles, capsules and polygons of 3 to
// 8 sides, in random poses from touching to apart: the same distance to 1e-12 m, the normal
// along the closest points, and overlap said where the brute force says it.
TEST(DistanceTest, AgreesWithEveryVertexAgainstEveryEdge) {
    std::uint64_t state = 7;
    const auto uniform = [&](double lo, double hi) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return lo + (hi - lo) * static_cast<double>(state >> 11) * 0x1.0p-53;
    };
    const auto shape = [&]() -> Polygon {
        const int kind = static_cast<int>(uniform(0, 8));
        if (kind == 0) return make_circle(uniform(0.05, 0.5));
        if (kind == 1) return *make_capsule(uniform(0.1, 1.0), uniform(0.02, 0.3));
        const int sides = kind + 1;
        std::vector<Vec2> points;
        for (int i = 0; i < sides; ++i) {
            const double angle = 2 * pi * (i + uniform(-0.3, 0.3)) / sides;
            const double r = uniform(0.2, 0.6);
            points.push_back({r * std::cos(angle), r * std::sin(angle)});
        }
        const auto made = make_polygon(points, uniform(0, 1) < 0.3 ? uniform(0.0, 0.05) : 0.0);
        return made ? made->polygon : *make_box(0.5, 0.3);
    };
    int apart = 0, overlapping = 0;
    for (int k = 0; k < 20000; ++k) {
        const Polygon a = shape(), b = shape();
        const Transform xa = Transform::of({uniform(-0.1, 0.1), uniform(-0.1, 0.1)}, uniform(0, 2 * pi));
        const double reach = uniform(0.0, 2.0), direction = uniform(0, 2 * pi);
        const Transform xb = Transform::of({reach * std::cos(direction), reach * std::sin(direction)},
                                           uniform(0, 2 * pi));
        Transform xb_near = xb;
        if (k % 2 == 1) {
            // Half the pairs moved to within a millimetre of touching, either side: the pile's
            // case, where rounding decides between touching and not.
            const std::optional<Distance> far = distance(a, xa, b, xb);
            if (far) xb_near.p -= (far->distance + a.radius + b.radius - uniform(-1e-3, 1e-3)) * far->normal;
        }
        const std::optional<double> expected = brute_force_core_distance(a, xa, b, xb_near);
        const std::optional<Distance> got = distance(a, xa, b, xb_near);
        ASSERT_EQ(expected.has_value(), got.has_value()) << k;
        if (!expected) {
            ++overlapping;
            continue;
        }
        ++apart;
        EXPECT_NEAR(got->distance, *expected - a.radius - b.radius, 1e-12) << k;
        EXPECT_NEAR(got->normal.norm(), 1, 1e-12) << k;
    }
    // Both verdicts are exercised.
    EXPECT_GT(apart, 5000);
    EXPECT_GT(overlapping, 2000);
}

// A box flying at a box: the touch at the analytic time, from the near side.
TEST(TimeOfImpactTest, TranslationMeetsAtTheAnalyticTime) {
    Sweep a;
    a.x0 = {0, 0};
    a.v = {100, 0};
    a.bound = bounding_radius(box(1, 1));
    Sweep b;
    b.x0 = {3, 0.3};
    b.v = {-50, 0};
    b.bound = a.bound;
    ImpactQuery q;
    q.t_end = 0.1;
    q.target = 1e-4;
    q.tolerance = 1e-4;
    const TimeOfImpact hit = time_of_impact(box(1, 1), a, box(1, 1), b, q);
    ASSERT_EQ(hit.kind, TimeOfImpact::Kind::hit);
    // Faces 2 m apart closing at 150 m/s: they touch at 2 / 150 s.
    EXPECT_LE(hit.t, 2.0 / 150);
    EXPECT_GE(hit.t, (2.0 - 2e-4) / 150);
    EXPECT_GE(hit.gap, q.target - 1e-12);
    EXPECT_LE(hit.gap, q.target + q.tolerance);
    // Moving apart, or not yet within reach by the end: none.
    b.v = {150, 0};
    EXPECT_EQ(time_of_impact(box(1, 1), a, box(1, 1), b, q).kind, TimeOfImpact::Kind::apart);
    b.v = {-50, 0};
    q.t_end = 0.01;
    EXPECT_EQ(time_of_impact(box(1, 1), a, box(1, 1), b, q).kind, TimeOfImpact::Kind::apart);
}

// A long thin box spinning at 200 rad/s beside a still one, which it sweeps through in its
// turn: the touch is found before any overlap, at the first angle the bar's end reaches the
// box (found here by a fine scan).
TEST(TimeOfImpactTest, SpinIsNeverOvershot) {
    const Polygon bar = box(2, 0.1), block = box(0.4, 0.4);
    Sweep a;
    a.omega = 200;
    a.bound = bounding_radius(bar);
    Sweep b;
    b.x0 = {0.2, 0.9};
    b.bound = bounding_radius(block);
    ImpactQuery q;
    q.t_end = 0.02;
    q.target = 1e-4;
    q.tolerance = 1e-4;
    const TimeOfImpact hit = time_of_impact(bar, a, block, b, q);
    ASSERT_EQ(hit.kind, TimeOfImpact::Kind::hit);
    double first = q.t_end;
    for (int k = 0; k <= 200000; ++k) {
        const double t = q.t_end * k / 200000;
        const std::optional<Distance> d = distance(bar, a.at(t), block, b.at(t));
        if (!d || d->distance <= 0) {
            first = t;
            break;
        }
    }
    ASSERT_LT(first, q.t_end);
    EXPECT_LE(hit.t, first);
    EXPECT_GT(hit.t, first - 1e-5);   // within 2 mrad of the touch
    const std::optional<Distance> at = distance(bar, a.at(hit.t), block, b.at(hit.t));
    ASSERT_TRUE(at);
    EXPECT_GT(at->distance, 0.0);
    EXPECT_LE(at->distance, q.target + q.tolerance);
}

TEST(TimeOfImpactTest, TouchingAtTheStartIsSaid) {
    Sweep a;
    a.v = {1, 0};
    a.bound = 1;
    Sweep b;
    b.x0 = {1.00005, 0};
    b.bound = 1;
    ImpactQuery q;
    q.t_end = 1;
    q.target = 1e-4;
    q.tolerance = 1e-4;
    EXPECT_EQ(time_of_impact(box(1, 1), a, box(1, 1), b, q).kind, TimeOfImpact::Kind::touching);
}

TEST(InnerRadiusTest, LargestCircleAboutTheCentroid) {
    EXPECT_NEAR(inner_radius(box(0.8, 0.5)), 0.25, 1e-12);
    EXPECT_NEAR(inner_radius(box(0.8, 0.5, 0.05)), 0.25, 1e-12);
    EXPECT_NEAR(inner_radius(make_circle(0.3)), 0.3, 1e-12);
    EXPECT_NEAR(inner_radius(*make_capsule(2, 0.2)), 0.2, 1e-12);
}

}  // namespace
}  // namespace discreel::physics::detail
