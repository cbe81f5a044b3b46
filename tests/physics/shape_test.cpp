// Shapes and their contact manifolds, against hand-worked geometry: mass and inertia from the
// textbook formulas, polygons refused for the reasons users meet, and the points, normals,
// separations and feature ids a solver will consume.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "manifold.hpp"
#include "shape.hpp"

namespace discreel::physics::detail {
namespace {

constexpr double pi = std::numbers::pi;

Polygon box(double w, double h, double rounding = 0) {
    auto made = make_box(w, h, rounding);
    EXPECT_TRUE(made.ok());
    return *made;
}

TEST(ShapeTest, MassAndInertiaMatchTheFormulas) {
    // Box w x h: m = rho w h, I = m (w^2 + h^2) / 12.
    const MassProperties b = mass_properties(box(0.8, 0.5), 2.0);
    EXPECT_NEAR(b.mass, 2.0 * 0.4, 1e-12);
    EXPECT_NEAR(b.inertia, 0.8 * (0.64 + 0.25) / 12, 1e-12);
    // Circle: m = rho pi r^2, I = m r^2 / 2.
    const MassProperties c = mass_properties(make_circle(0.3), 1.5);
    EXPECT_NEAR(c.mass, 1.5 * pi * 0.09, 1e-12);
    EXPECT_NEAR(c.inertia, 0.5 * c.mass * 0.09, 1e-12);
    // A capsule of length 0 would be a circle; one of length L is a rectangle L x 2r with two
    // half discs. Check it against numerical integration over its outline.
    const auto capsule = make_capsule(1.0, 0.15);
    ASSERT_TRUE(capsule.ok());
    const MassProperties k = mass_properties(*capsule, 1.0);
    double area = 0, second = 0;
    const int steps = 2000;
    for (int i = 0; i < steps; ++i) {
        for (int j = 0; j < steps; ++j) {
            const double x = -0.65 + 1.3 * (i + 0.5) / steps, y = -0.15 + 0.3 * (j + 0.5) / steps;
            const double cx = std::clamp(x, -0.5, 0.5);
            if ((x - cx) * (x - cx) + y * y > 0.15 * 0.15) continue;
            const double cell = (1.3 / steps) * (0.3 / steps);
            area += cell;
            second += cell * (x * x + y * y);
        }
    }
    EXPECT_NEAR(k.area, area, 1e-4);
    EXPECT_NEAR(k.inertia, second, 1e-4);
    // A rounded box against the same integration: core 0.6 x 0.3 swept by 0.1.
    const MassProperties r = mass_properties(box(0.8, 0.5, 0.1), 1.0);
    area = second = 0;
    for (int i = 0; i < steps; ++i) {
        for (int j = 0; j < steps; ++j) {
            const double x = -0.4 + 0.8 * (i + 0.5) / steps, y = -0.25 + 0.5 * (j + 0.5) / steps;
            const double cx = std::clamp(x, -0.3, 0.3), cy = std::clamp(y, -0.15, 0.15);
            if ((x - cx) * (x - cx) + (y - cy) * (y - cy) > 0.01) continue;
            const double cell = (0.8 / steps) * (0.5 / steps);
            area += cell;
            second += cell * (x * x + y * y);
        }
    }
    EXPECT_NEAR(r.area, 0.6 * 0.3 + 2 * 0.1 * 0.9 + pi * 0.01, 1e-12);
    EXPECT_NEAR(r.area, area, 1e-4);
    EXPECT_NEAR(r.inertia, second, 1e-5);
}

TEST(ShapeTest, PolygonsAreCentredAndWoundCounterClockwise) {
    // A clockwise right triangle: its centroid is the mean of its corners.
    const std::vector<Vec2> points{{0, 0}, {0, 3}, {3, 0}};
    const auto made = make_polygon(points);
    ASSERT_TRUE(made.ok()) << made.error().message;
    EXPECT_NEAR(made->offset.x(), 1.0, 1e-12);
    EXPECT_NEAR(made->offset.y(), 1.0, 1e-12);
    const Polygon& p = made->polygon;
    double area2 = 0;
    for (int i = 0; i < p.count; ++i) area2 += cross(p.vertices[i], p.vertices[(i + 1) % p.count]);
    EXPECT_NEAR(area2, 9.0, 1e-12);   // positive: counter-clockwise
    for (int i = 0; i < p.count; ++i) {   // outward: every other vertex is behind each face
        for (int j = 0; j < p.count; ++j) {
            EXPECT_LE(p.normals[i].dot(p.vertices[j] - p.vertices[i]), 1e-12);
        }
    }
    EXPECT_NEAR(bounding_radius(p), std::hypot(2.0, 1.0), 1e-12);
}

TEST(ShapeTest, BadPolygonsAreRefusedWithTheReason) {
    const auto refuse = [](std::vector<Vec2> points) {
        const auto made = make_polygon(points);
        EXPECT_FALSE(made.ok());
        return made.ok() ? std::string() : made.error().message;
    };
    EXPECT_EQ(refuse({{0, 0}, {1, 0}}), "a polygon needs at least 3 points, got 2");
    EXPECT_EQ(refuse({{0, 0}, {1, 0}, {2, 0}}), "the polygon has no area (its points are on a line)");
    // A bow-tie: its two halves' areas cancel, but its points are not on a line.
    EXPECT_EQ(refuse({{0, 0}, {1, 1}, {1, 0}, {0, 1}}),
              "the polygon's outline crosses itself; list its points in order around it");
    EXPECT_EQ(refuse({{0, 0}, {2, 0}, {1, 0.2}, {2, 2}, {0, 2}}),
              "the polygon is not convex (it turns the other way at point 2); split it into "
              "convex pieces");
    EXPECT_EQ(refuse({{0, 0}, {1, 0}, {2, 0}, {2, 2}}),
              "point 1 lies on the line between its neighbours; remove it");
    std::vector<Vec2> nine;
    for (int i = 0; i < 9; ++i) nine.push_back({std::cos(i * 2 * pi / 9), std::sin(i * 2 * pi / 9)});
    EXPECT_EQ(refuse(nine), "a polygon has at most 8 points, got 9; split it into convex pieces of up to 8");
    std::vector<Vec2> star;   // a pentagram: every turn the same way, but wound twice
    for (int i = 0; i < 5; ++i) star.push_back({std::cos(i * 4 * pi / 5), std::sin(i * 4 * pi / 5)});
    EXPECT_EQ(refuse(star), "the polygon's outline crosses itself; list its points in order around it");
    EXPECT_FALSE(make_box(0, 1).ok());
    EXPECT_FALSE(make_box(1, 1, 0.5).ok());   // rounding must leave a core
    EXPECT_FALSE(make_capsule(1, 0).ok());
}

// A 1 x 1 box resting on a 4 x 1 box with a 2 mm gap: two points under its bottom corners,
// normal straight up, separation the gap.
TEST(ManifoldTest, BoxOnBoxHasTwoPointsUnderItsCorners) {
    const Polygon ground = box(4, 1), crate = box(1, 1);
    const Transform xg = Transform::of(V2(0, 0), 0), xc = Transform::of(V2(0.3, 1.002), 0);
    const Manifold m = collide(ground, xg, crate, xc, 0.01);
    ASSERT_EQ(m.count, 2);
    EXPECT_NEAR(m.normal.x(), 0, 1e-12);
    EXPECT_NEAR(m.normal.y(), 1, 1e-12);
    std::vector<double> xs;
    for (int k = 0; k < 2; ++k) {
        EXPECT_NEAR(m.points[k].separation, 0.002, 1e-12);
        EXPECT_NEAR(m.points[k].point.y(), 0.501, 1e-12);   // midway across the gap
        xs.push_back(m.points[k].point.x());
    }
    std::sort(xs.begin(), xs.end());
    EXPECT_NEAR(xs[0], -0.2, 1e-12);
    EXPECT_NEAR(xs[1], 0.8, 1e-12);
    EXPECT_NE(m.points[0].id, m.points[1].id);
    // Swapped, the normal flips and the points stay.
    const Manifold swapped = collide(crate, xc, ground, xg, 0.01);
    ASSERT_EQ(swapped.count, 2);
    EXPECT_NEAR(swapped.normal.y(), -1, 1e-12);
    // Beyond the speculative distance: nothing.
    EXPECT_EQ(collide(ground, xg, crate, Transform::of(V2(0.3, 1.02), 0), 0.01).count, 0);
}

// Feature ids stay the same while the same features touch: a small slide and a tiny tilt.
TEST(ManifoldTest, FeatureIdsAreStableWhileTheSameFeaturesTouch) {
    const Polygon ground = box(4, 1), crate = box(1, 1);
    const Transform xg = Transform::of(V2(0, 0), 0);
    const Manifold before = collide(ground, xg, crate, Transform::of(V2(0.3, 0.999), 0), 0.01);
    const Manifold after = collide(ground, xg, crate, Transform::of(V2(0.31, 0.9985), 1e-4), 0.01);
    ASSERT_EQ(before.count, 2);
    ASSERT_EQ(after.count, 2);
    for (int k = 0; k < 2; ++k) EXPECT_EQ(before.points[k].id, after.points[k].id);
}

// A box standing on its corner (rotated 45 degrees) touches at one point, below the corner.
TEST(ManifoldTest, BoxOnItsCornerHasOnePoint) {
    const Polygon ground = box(4, 1), crate = box(1, 1);
    const double half_diagonal = std::sqrt(0.5);
    const Transform xc = Transform::of(V2(0, 0.5 + half_diagonal - 0.001), pi / 4);
    const Manifold m = collide(ground, Transform::of(V2(0, 0), 0), crate, xc, 0.01);
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].separation, -0.001, 1e-12);
    EXPECT_NEAR(m.points[0].point.x(), 0, 1e-12);
    EXPECT_NEAR(m.normal.y(), 1, 1e-12);
}

// Two unit boxes corner to corner along the diagonal, 1 cm apart: no face overlaps the other
// sideways, so clipping leaves nothing; the contact is the one point between the corners,
// along the diagonal, apart by the corners' distance (without it such a pair had no contact
// at all and could close a whole step's travel into each other).
TEST(ManifoldTest, BoxesCornerToCornerHaveOnePointBetweenTheCorners) {
    const Polygon crate = box(1, 1);
    const double gap = 0.01, offset = 1 + gap / std::sqrt(2.0);
    const Transform xa = Transform::of(V2(0, 0), 0), xb = Transform::of(V2(offset, offset), 0);
    for (const bool swapped : {false, true}) {
        const Manifold m = swapped ? collide(crate, xb, crate, xa, 0.02) : collide(crate, xa, crate, xb, 0.02);
        ASSERT_EQ(m.count, 1) << swapped;
        EXPECT_NEAR(m.points[0].separation, gap, 1e-12);
        const double toward = swapped ? -std::sqrt(0.5) : std::sqrt(0.5);   // from A to B
        EXPECT_NEAR(m.normal.x(), toward, 1e-12);
        EXPECT_NEAR(m.normal.y(), toward, 1e-12);
        const double middle = 0.5 + 0.25 * gap * std::sqrt(2.0);
        EXPECT_NEAR(m.points[0].point.x(), middle, 1e-12);
        EXPECT_NEAR(m.points[0].point.y(), middle, 1e-12);
    }
    // Beyond the speculative distance, nothing.
    EXPECT_EQ(collide(crate, xa, crate, xb, 0.005).count, 0);
}

// A circle against a box: in front of a face the face's normal; beyond a corner the direction
// from the corner to the centre.
TEST(ManifoldTest, CircleAgainstABoxFaceAndCorner) {
    const Polygon crate = box(2, 2), ball = make_circle(0.5);
    const Transform xb = Transform::of(V2(0, 0), 0);
    Manifold m = collide(crate, xb, ball, Transform::of(V2(0.4, 1.49), 0), 0.01);
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.normal.y(), 1, 1e-12);
    EXPECT_NEAR(m.points[0].separation, -0.01, 1e-12);
    EXPECT_NEAR(m.points[0].point.x(), 0.4, 1e-12);
    EXPECT_NEAR(m.points[0].point.y(), 0.995, 1e-12);

    const V2 centre = V2(1, 1) + V2(1, 1).normalized() * 0.505;
    m = collide(crate, xb, ball, Transform::of(centre, 0), 0.01);
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.normal.x(), std::sqrt(0.5), 1e-12);
    EXPECT_NEAR(m.normal.y(), std::sqrt(0.5), 1e-12);
    EXPECT_NEAR(m.points[0].separation, 0.005, 1e-12);
    // The other way round, the normal flips.
    const Manifold back = collide(ball, Transform::of(centre, 0), crate, xb, 0.01);
    EXPECT_NEAR(back.normal.x(), -std::sqrt(0.5), 1e-12);
    // Circles: the line between the centres.
    const Transform origin = Transform::of(V2(0, 0), 0), apart = Transform::of(V2(0.6, 0.8), 0);
    EXPECT_EQ(collide(ball, origin, make_circle(0.25), apart, 0.01).count, 0);
    m = collide(ball, origin, make_circle(0.25), apart, 0.3);   // within a large speculative
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.normal.x(), 0.6, 1e-12);
    EXPECT_NEAR(m.normal.y(), 0.8, 1e-12);
    EXPECT_NEAR(m.points[0].separation, 0.25, 1e-12);
}

// Two parallel capsules lying one above the other touch along their overlap: two points at
// its ends; crossed at right angles, one point.
TEST(ManifoldTest, CapsulesParallelAndCrossed) {
    const auto capsule = make_capsule(2, 0.1);
    ASSERT_TRUE(capsule.ok());
    const Transform lower = Transform::of(V2(0, 0), 0);
    Manifold m = collide(*capsule, lower, *capsule, Transform::of(V2(1, 0.199), 0), 0.01);
    ASSERT_EQ(m.count, 2);
    EXPECT_NEAR(m.normal.y(), 1, 1e-12);
    std::vector<double> xs{m.points[0].point.x(), m.points[1].point.x()};
    std::sort(xs.begin(), xs.end());
    EXPECT_NEAR(xs[0], 0, 1e-12);
    EXPECT_NEAR(xs[1], 1, 1e-12);
    EXPECT_NEAR(m.points[0].separation, -0.001, 1e-12);
    // Standing upright on it: the upright one's lower end is 0.199 above the lying one's axis.
    m = collide(*capsule, lower, *capsule, Transform::of(V2(0.5, 1.199), pi / 2), 0.01);
    ASSERT_EQ(m.count, 1);
    EXPECT_NEAR(m.points[0].separation, -0.001, 1e-12);
    EXPECT_NEAR(m.points[0].point.x(), 0.5, 1e-12);
    EXPECT_NEAR(m.normal.y(), 1, 1e-12);
}

// Box walls as slabs around the container's inside: a crate on the floor touches the floor
// slab at its two bottom corners and nothing else; one pushed into a corner touches two slabs.
TEST(ManifoldTest, ContainerSlabsHoldBodiesInside) {
    const auto slabs = container_slabs(V2(0, 0), V2(10, 5));
    const Polygon crate = box(1, 1);
    const auto touching = [&](const V2& at, double angle) {
        std::vector<Manifold> found;
        for (const Slab& s : slabs) {
            const Manifold m = collide(s.shape, Transform::of(s.centre, 0), crate,
                                       Transform::of(at, angle), 0.01);
            if (m.count > 0) found.push_back(m);
        }
        return found;
    };
    auto found = touching(V2(5, 0.501), 0);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].count, 2);
    EXPECT_NEAR(found[0].normal.y(), 1, 1e-12);   // from the slab into the container
    EXPECT_NEAR(found[0].points[0].separation, 0.001, 1e-12);
    found = touching(V2(9.5, 4.5), 0);   // the top right corner
    ASSERT_EQ(found.size(), 2u);
    for (const Manifold& m : found) EXPECT_NEAR(m.points[0].separation, 0, 1e-12);
}

}  // namespace
}  // namespace discreel::physics::detail
