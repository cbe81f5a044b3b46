#include "lcp.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace discreel::physics::detail {
namespace {

// Changes of side smaller than this, relative to the terms they come from, are rounding: a row
// that sits on its bound with w = -1e-17 is not made free (and put back, and made free...).
constexpr double tolerance = 1e-11;

}  // namespace

bool BoxedLcp::solve_free(std::span<const double> a, std::span<const double> b,
                          std::span<double> x, double regularise) {
    const std::size_t n = b.size();
    const std::size_t m = free_.size();
    factor_.assign(m * m, 0.0);
    rhs_.resize(m);
    for (std::size_t p = 0; p < m; ++p) {
        const std::size_t i = static_cast<std::size_t>(free_[p]);
        double r = -b[i];
        for (std::size_t j = 0; j < n; ++j) {
            if (side_[j] != Side::free) r -= a[i * n + j] * x[j];
        }
        rhs_[p] = r;
        for (std::size_t q = 0; q <= p; ++q) {
            factor_[p * m + q] = a[i * n + static_cast<std::size_t>(free_[q])];
        }
        factor_[p * m + p] *= 1.0 + regularise;
    }
    // Cholesky, lower triangle in place: a pivot that is not positive (beyond rounding of the
    // diagonal it came from) means the free rows are dependent.
    for (std::size_t p = 0; p < m; ++p) {
        const double diagonal = a[static_cast<std::size_t>(free_[p]) * (n + 1)];
        for (std::size_t q = 0; q <= p; ++q) {
            double s = factor_[p * m + q];
            for (std::size_t k = 0; k < q; ++k) s -= factor_[p * m + k] * factor_[q * m + k];
            if (q < p) {
                factor_[p * m + q] = s / factor_[q * m + q];
            } else {
                if (!(s > 1e-13 * diagonal)) return false;
                factor_[p * m + p] = std::sqrt(s);
            }
        }
    }
    for (std::size_t p = 0; p < m; ++p) {   // L y = rhs
        double s = rhs_[p];
        for (std::size_t k = 0; k < p; ++k) s -= factor_[p * m + k] * rhs_[k];
        rhs_[p] = s / factor_[p * m + p];
    }
    for (std::size_t p = m; p-- > 0;) {     // L^T x = y
        double s = rhs_[p];
        for (std::size_t k = p + 1; k < m; ++k) s -= factor_[k * m + p] * rhs_[k];
        rhs_[p] = s / factor_[p * m + p];
    }
    for (std::size_t p = 0; p < m; ++p) x[static_cast<std::size_t>(free_[p])] = rhs_[p];
    return true;
}

bool BoxedLcp::solve(std::span<const double> a, std::span<const double> b,
                     std::span<const double> lo, std::span<const double> hi, std::span<double> x,
                     int max_pivots) {
    const std::size_t n = b.size();
    side_.resize(n);
    // Rows that may be either sign (friction) start free, rows with a floor (normal impulses)
    // on it: a resting contact is then settled in one solve.
    for (std::size_t i = 0; i < n; ++i) {
        const bool both_signs = lo[i] < 0 && hi[i] > 0;
        side_[i] = both_signs ? Side::free : Side::lower;
        x[i] = both_signs ? 0.0 : lo[i];
    }
    for (pivots_ = 0; pivots_ <= max_pivots; ++pivots_) {
        free_.clear();
        for (std::size_t i = 0; i < n; ++i) {
            if (side_[i] == Side::free) free_.push_back(static_cast<int>(i));
        }
        if (!solve_free(a, b, x, 0.0) && !solve_free(a, b, x, 1e-10)) return false;
        // The row of least index that breaks its condition changes side.
        std::size_t broken = n;
        for (std::size_t i = 0; i < n && broken == n; ++i) {
            if (side_[i] == Side::free) {
                const double bound = std::max(std::isfinite(lo[i]) ? std::abs(lo[i]) : 0.0,
                                              std::isfinite(hi[i]) ? std::abs(hi[i]) : 0.0);
                const double slack = tolerance * std::max(bound, std::abs(x[i]));
                if (x[i] < lo[i] - slack) {
                    side_[i] = Side::lower;
                    x[i] = lo[i];
                    broken = i;
                } else if (x[i] > hi[i] + slack) {
                    side_[i] = Side::upper;
                    x[i] = hi[i];
                    broken = i;
                }
                continue;
            }
            if (lo[i] == hi[i]) continue;
            double w = b[i], scale = std::abs(b[i]);
            for (std::size_t j = 0; j < n; ++j) {
                const double term = a[i * n + j] * x[j];
                w += term;
                scale += std::abs(term);
            }
            const bool wrong = side_[i] == Side::lower ? w < -tolerance * scale
                                                        : w > tolerance * scale;
            if (wrong) {
                side_[i] = Side::free;
                broken = i;
            }
        }
        if (broken == n) return true;
    }
    for (std::size_t i = 0; i < n; ++i) x[i] = std::clamp(x[i], lo[i], hi[i]);
    return false;
}

}  // namespace discreel::physics::detail
