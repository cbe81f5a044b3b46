// Distances and times of impact between shapes (toi.hpp), against hand-worked geometry: the
// closest features of boxes, circles and capsules in any pose, and the first touch of moving,
// spinning bodies, never after it and within the tolerance asked.
#include <cmath>
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
