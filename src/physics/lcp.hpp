#pragma once
// A boxed linear complementarity problem of a few rows, solved directly: find x with
//     w = A x + b,   lo <= x <= hi,
//     x_i = lo_i  =>  w_i >= 0,    x_i = hi_i  =>  w_i <= 0,    lo_i < x_i < hi_i  =>  w_i = 0,
// for a symmetric positive (semi)definite A, by principal pivoting: the rows are split into
// free ones (solved exactly together, in double precision, by a Cholesky factorisation) and
// ones held at a bound, and the row of least index that breaks its condition changes sides,
// one at a time, until none does (Murty's least-index rule: it ends for a positive definite A
// and makes the answer independent of anything but the input). Contact impulses between a
// light body and one a million times heavier need this: an iteration converges at a rate set
// by the mass ratio, and single precision cannot even represent the answer.
#include <span>
#include <vector>

namespace discreel::physics::detail {

class BoxedLcp {
public:
    // A: n x n, row-major; b, lo, hi, x: n each. x is the answer (its input is ignored). lo_i
    // may equal hi_i: that row is held there. False when `max_pivots` changes of side did not
    // settle it (x is then the last try, inside its bounds), or A was not positive definite on
    // the free rows even after a relative 1e-10 was added to its diagonal.
    bool solve(std::span<const double> a, std::span<const double> b, std::span<const double> lo,
               std::span<const double> hi, std::span<double> x, int max_pivots);

    int pivots() const { return pivots_; }   // of the last solve

private:
    enum class Side : unsigned char { lower, upper, free };
    bool solve_free(std::span<const double> a, std::span<const double> b, std::span<double> x,
                    double regularise);

    std::vector<Side> side_;
    std::vector<int> free_;       // indices of the free rows, ascending
    std::vector<double> factor_;  // Cholesky factor of A on the free rows
    std::vector<double> rhs_;
    int pivots_ = 0;
};

}  // namespace discreel::physics::detail
