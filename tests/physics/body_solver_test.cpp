// The shapes' solver on its own, against Newton: a box at rest stays put, a box dropped flat
// rebounds to e^2 h without starting to spin, a box on a slope slides at g (sin - mu cos) or
// sticks, and a short stack stands.
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "body_solver.hpp"

namespace discreel::physics::detail {
namespace {

constexpr double rate = 480;
const V2 gravity(0, -9.81);

RigidBody ground(double angle = 0) {
    RigidBody g;
    g.shape = *make_box(40, 2);
    g.x = V2(0, -1);               // top face at y = 0 when flat
    g.angle = angle;
    g.friction = 0.5;
    return g;
}

RigidBody crate(double w, double h, V2 at, double e = 0, double mu = 0.5) {
    RigidBody b;
    b.shape = *make_box(w, h);
    b.x = at;
    const MassProperties m = mass_properties(b.shape, 1.0);
    b.inv_mass = 1 / m.mass;
    b.inv_inertia = 1 / m.inertia;
    b.restitution = e;
    b.friction = mu;
    return b;
}

TEST(BodySolverTest, ABoxAtRestStaysWithinATenthOfAMillimetreFor10s) {
    std::vector<RigidBody> bodies{ground(), crate(1, 0.5, V2(0.3, 0.25))};
    BodySolver solver;
    double farthest = 0;
    for (int k = 0; k < 10 * rate; ++k) {
        solver.step(bodies, gravity, 1 / rate);
        farthest = std::max(farthest, (bodies[1].x - V2(0.3, 0.25)).norm());
    }
    EXPECT_LT(farthest, 1e-4);
    EXPECT_LT(std::abs(bodies[1].angle), 1e-6);
}

TEST(BodySolverTest, AFlatLandingReboundsToESquaredHWithoutSpin) {
    const double h = 1.0, e = 0.5;
    std::vector<RigidBody> bodies{ground(), crate(1, 0.5, V2(0.3, 0.25 + h), e)};
    BodySolver solver;
    bool landed = false;
    double top = 0;   // the highest the bottom gets after the first landing
    for (int k = 0; k < 2 * rate; ++k) {
        solver.step(bodies, gravity, 1 / rate);
        const double bottom = bodies[1].x.y() - 0.25;
        if (!landed && bodies[1].v.y() > 0) landed = true;
        if (landed) top = std::max(top, bottom);
        if (landed && bodies[1].v.y() < 0 && bottom < 0.01) break;
    }
    EXPECT_NEAR(top, e * e * h, 0.02 * e * e * h);
    EXPECT_LT(std::abs(bodies[1].omega), 1e-9);
    EXPECT_LT(std::abs(bodies[1].angle), 1e-9);
}

// On a 20 degree slope with mu = 0.2 < tan 20 = 0.36 a box slides at g (sin - mu cos); with
// mu = 0.5 it sticks.
TEST(BodySolverTest, ABoxOnASlopeSlidesOrSticksAsCoulombSays) {
    const double theta = 20 * std::numbers::pi / 180;
    for (const double mu : {0.2, 0.5}) {
        RigidBody slope = ground(theta);
        slope.x = V2(0, 0);
        slope.friction = mu;
        // Resting on the slope's top face, 1 m up it from the centre.
        const V2 along(std::cos(theta), std::sin(theta)), up(-std::sin(theta), std::cos(theta));
        RigidBody box = crate(0.5, 0.5, along * 1.0 + up * (1.0 + 0.25), 0, mu);
        box.angle = theta;
        std::vector<RigidBody> bodies{slope, box};
        BodySolver solver;
        for (int k = 0; k < rate; ++k) solver.step(bodies, gravity, 1 / rate);   // 1 s
        const double speed = bodies[1].v.dot(along);
        const double expected = mu < std::tan(theta)
                                    ? -9.81 * (std::sin(theta) - mu * std::cos(theta)) * 1.0
                                    : 0.0;
        EXPECT_NEAR(speed, expected, 0.01 * 9.81) << "mu " << mu;
        EXPECT_LT(std::abs(bodies[1].angle - theta), 1e-3) << "mu " << mu;
    }
}

// The bar: a 20-box stack within 5 mm of its ideal height and 2 mm sideways.
TEST(BodySolverTest, AStackOfTwentyBoxesStands) {
    std::vector<RigidBody> bodies{ground()};
    for (int i = 0; i < 20; ++i) bodies.push_back(crate(1, 1, V2(0, 0.5 + i)));
    BodySolver solver;
    for (int k = 0; k < 5 * rate; ++k) solver.step(bodies, gravity, 1 / rate);
    for (int i = 0; i < 20; ++i) {
        const RigidBody& b = bodies[1 + static_cast<std::size_t>(i)];
        EXPECT_NEAR(b.x.y(), 0.5 + i, 5e-3) << "box " << i;
        EXPECT_NEAR(b.x.x(), 0.0, 2e-3) << "box " << i;
    }
}

// The 20-row pyramid (210 boxes): within 5 mm of its ideal heights and 2 mm sideways.
TEST(BodySolverTest, ATwentyRowPyramidHolds) {
    std::vector<RigidBody> bodies{ground()};
    bodies[0].shape = *make_box(80, 2);
    std::vector<V2> ideal;
    for (int row = 0; row < 20; ++row) {
        const int n = 20 - row;
        for (int i = 0; i < n; ++i) {
            ideal.emplace_back(i - (n - 1) / 2.0, 0.5 + row);
            bodies.push_back(crate(1, 1, ideal.back(), 0, 0.6));
        }
    }
    BodySolver solver;
    for (int k = 0; k < 2 * rate; ++k) solver.step(bodies, gravity, 1 / rate);
    double sag = 0, drift = 0;
    for (std::size_t i = 0; i < ideal.size(); ++i) {
        sag = std::max(sag, std::abs(bodies[i + 1].x.y() - ideal[i].y()));
        drift = std::max(drift, std::abs(bodies[i + 1].x.x() - ideal[i].x()));
    }
    EXPECT_LT(sag, 5e-3);
    EXPECT_LT(drift, 2e-3);
}

}  // namespace
}  // namespace discreel::physics::detail
