// The direct boxed LCP solve (src/physics/lcp.hpp) against the conditions that define its
// answer, on random positive definite problems, and on the one that motivates it: a light
// body between the ground and one a million times heavier.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "lcp.hpp"
#include "scenes.hpp"

namespace discreel::physics::detail {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

struct Problem {
    int n = 0;
    std::vector<double> a, b, lo, hi;
};

// A = G G^T + a little identity: positive definite, of rank-deficient-looking spread when
// `spread` scales the rows by up to that factor (a mass ratio's effect on the effective mass).
Problem random_problem(testing::Rng& rng, int rows, double spread) {
    Problem p;
    p.n = rows;
    const auto n = static_cast<std::size_t>(rows);
    std::vector<double> g(n * n);
    for (std::size_t i = 0; i < n; ++i) {
        const double scale = std::pow(spread, rng.uniform(0, 1));
        for (std::size_t j = 0; j < n; ++j) g[i * n + j] = scale * rng.uniform(-1, 1);
    }
    p.a.assign(n * n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = 0; j < n; ++j) {
            double s = i == j ? 1e-3 : 0.0;
            for (std::size_t k = 0; k < n; ++k) s += g[i * n + k] * g[j * n + k];
            p.a[i * n + j] = s;
        }
    }
    for (std::size_t i = 0; i < n; ++i) {
        p.b.push_back(rng.uniform(-1, 1) * p.a[i * (n + 1)]);
        // Every kind of row: a floor only (a normal impulse), a box (friction), both at zero.
        const int kind = static_cast<int>(rng.uniform(0, 3));
        const double half = rng.uniform(0, 1);
        p.lo.push_back(kind == 0 ? 0.0 : kind == 1 ? -half : 0.0);
        p.hi.push_back(kind == 0 ? inf : kind == 1 ? half : (rng.uniform(0, 1) < 0.5 ? 0.0 : inf));
    }
    return p;
}

// How far x is from meeting the conditions, relative to the problem's scale.
double violation(const Problem& p, const std::vector<double>& x) {
    const auto n = static_cast<std::size_t>(p.n);
    double worst = 0;
    for (std::size_t row = 0; row < n; ++row) {
        double w = p.b[row], scale = std::abs(p.b[row]);
        for (std::size_t j = 0; j < n; ++j) {
            const double term = p.a[row * n + j] * x[j];
            w += term;
            scale += std::abs(term);
        }
        const double xi = x[row];
        EXPECT_GE(xi, p.lo[row]) << "row " << row;
        EXPECT_LE(xi, p.hi[row]) << "row " << row;
        const double rel = std::abs(w) / scale;
        if (p.lo[row] == p.hi[row]) continue;
        if (xi == p.lo[row]) worst = std::max(worst, w < 0 ? rel : 0.0);
        else if (xi == p.hi[row]) worst = std::max(worst, w > 0 ? rel : 0.0);
        else worst = std::max(worst, rel);
    }
    return worst;
}

TEST(BoxedLcp, MeetsItsConditionsOnRandomProblems) {
    testing::Rng rng(11);
    BoxedLcp lcp;
    int most_pivots = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const int n = 1 + trial % 24;
        const Problem p = random_problem(rng, n, trial % 2 ? 1e3 : 1.0);
        std::vector<double> x(static_cast<std::size_t>(n));
        ASSERT_TRUE(lcp.solve(p.a, p.b, p.lo, p.hi, x, 10 * n)) << "trial " << trial;
        // Rounding of a Cholesky solve of a matrix of condition up to ~1e9.
        EXPECT_LT(violation(p, x), 1e-6) << "trial " << trial;
        most_pivots = std::max(most_pivots, lcp.pivots());
    }
    EXPECT_LE(most_pivots, 3 * 24);   // measured: 53
}

TEST(BoxedLcp, SameInputSameBits) {
    testing::Rng rng(5);
    const Problem p = random_problem(rng, 16, 1e3);
    BoxedLcp one, two;
    std::vector<double> x(16), y(16, 123.0);
    ASSERT_TRUE(one.solve(p.a, p.b, p.lo, p.hi, x, 160));
    ASSERT_TRUE(two.solve(p.a, p.b, p.lo, p.hi, y, 160));
    EXPECT_EQ(x, y);
}

// A 1 kg disc on the ground under 1e6 kg, one step of gravity g dt into both contacts (normal
// rows of unit lever arms): the ground must take (M + m) g dt and the top contact M g dt, to
// the relative 1e-9 that double precision leaves of a 1e-6 determinant.
TEST(BoxedLcp, HoldsAMillionTimesHeavierBodyOnALightOne) {
    const double heavy = 1e6, light = 1.0, g_dt = 9.81 / 480;
    // Rows: 0 ground-light (light's upward velocity), 1 light-heavy (heavy's minus light's).
    const std::vector<double> a{1 / light, -1 / light, -1 / light, 1 / light + 1 / heavy};
    const std::vector<double> b{-g_dt, 0.0};   // both fall at g dt: ground closes, pair does not
    const std::vector<double> lo{0, 0}, hi{inf, inf};
    std::vector<double> x(2);
    BoxedLcp lcp;
    ASSERT_TRUE(lcp.solve(a, b, lo, hi, x, 20));
    EXPECT_NEAR(x[0], (heavy + light) * g_dt, 1e-9 * heavy * g_dt);
    EXPECT_NEAR(x[1], heavy * g_dt, 1e-9 * heavy * g_dt);
}

}  // namespace
}  // namespace discreel::physics::detail
