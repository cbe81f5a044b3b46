#pragma once
// The disc solver's small islands of discs far apart in mass, solved directly. Sequential
// impulses pass force from one disc to the next by a fraction set by their mass ratio per
// sweep, and the resting stage's single-precision rows cannot even hold a light disc's share
// of a disc a million times heavier: iterated, a heavy disc on a light one sinks into it every
// substep, and a light disc between two heavy ones closing on it is squeezed into them. An island
// of the resting stage's rows (what rows between moving discs connect; walls and pegs end it)
// of at most `largest` rows, joining moving discs `ratio` or more times apart in mass, all of
// whose pairs touch at the start of the substep, is solved as one boxed LCP in double
// precision (island.hpp, the manifold solver's), twice:
//   - in place of the impacts stage (which leaves its pairs alone): its collisions at the start
//     of the substep, together, each pair leaving at e times its approach;
//   - after the iterations, from the velocities before any row, to the rows' own targets (the
//     gap at the end no smaller than at the start if that was an overlap, else no overlap; a
//     bounce at most); its discs take those velocities instead of the iterations'.
// Newton's rule at every pair at once can add energy where several pairs of a crowd hit
// together: a solve whose impulses would do positive work is done again without bounces, and
// an island whose collision still cannot be solved goes back to the impacts stage. Only
// touching islands: a pair still closing from afar is the impacts stage's, which times it. The
// solved impulses do not warm-start the next substep: at an impact they are the collision's,
// not a lasting load, and fed to the iterations of a crowd they launch light discs
// (docs/tried.md).
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "block_solver.hpp"
#include "contact.hpp"
#include "island.hpp"

namespace discreel::physics::detail {

struct Substep;

// One of the resting stage's rows as the direct solve takes it, in double precision.
struct IslandRow {
    V2 normal = V2::UnitY();         // unit, from b towards a, at the predicted end
    double target = 0;               // m/s, the least end velocity n.(v_a - v_b) it asks for
    double normal_impulse = 0;       // N s, the iterations': the friction bounds' first guess
};

class DiscIslands {
public:
    static constexpr double ratio = 10.0;
    static constexpr std::size_t largest = 16;   // rows

    // Whether the moving discs differ in mass by `ratio` or more: otherwise nothing is planned.
    void set_masses(double lightest, double heaviest) {
        far_apart_ = heaviest >= ratio * lightest;
    }
    bool far_apart() const { return far_apart_; }
    // After the rows are listed (row_contacts: each row's contact, in row order), before the
    // impacts stage: the islands to solve directly.
    // Their pairs' collisions at the start of the substep are solved here, together, in
    // place of the impacts stage's (bodies' velocities change).
    void plan(Substep& s, std::span<const std::uint32_t> row_contacts);
    // The discs whose velocity plan()'s collisions changed: the impacts stage widens their
    // reach and predicts their other pairs, as after an impact of its own.
    std::span<const std::uint32_t> collided() const { return collided_; }
    // Whether contact (index into Substep::contacts) is in a planned island.
    bool in_island(std::uint32_t contact) const {
        return contact < marked_.size() && marked_[contact] != 0;
    }
    // The planned rows (indices into the plan's row_contacts), island by island.
    std::span<const std::uint32_t> planned() const { return planned_; }
    // rows: the planned ones, in planned() order. Bodies hold their velocities before any row.
    void solve(const Substep& s, std::span<const IslandRow> rows);
    // What the direct solve gives a disc of a solved island: its velocity at the end of the
    // substep.
    struct Solved {
        V2 v = V2::Zero();         // m/s
        double omega = 0;          // rad/s
        bool valid = false;
    };
    // Disc i's, if its island was solved.
    const Solved* solved(std::size_t i) const {
        return i < solved_.size() && solved_[i].valid ? &solved_[i] : nullptr;
    }
    // Each solved row's normal impulse counted in its contact's step_impulse in place of the
    // iterations' (c.normal_impulse, which stays the next substep's warm start).
    void count_impulses(std::vector<Contact>& contacts) const;

private:
    // The island of planned rows [first, last) gathered for the direct solver: bodies_ (with
    // their velocities now) and contacts_; normal of row j: normal(j).
    template <class Normal>
    void gather(const Substep& s, std::size_t first, std::size_t last, Normal normal);

    // The planned islands' collisions: each row bounces at e times its approach.
    void collide(Substep& s);
    // Solves the gathered island into state_ to targets_ and from guesses_; false: not solved
    // (state_ undefined).
    bool solve_island();
    // Whether the gathered island's solved impulses, taking start_ to state_, do no positive
    // work (to rounding).
    bool dissipates() const;

    bool far_apart_ = false;
    std::vector<std::uint32_t> parent_;     // per disc: union-find over the rows' moving discs
    std::vector<std::uint64_t> keyed_;      // (root << 32) | row, sorted
    std::vector<std::uint32_t> planned_;    // rows, island by island
    std::vector<std::uint32_t> island_end_; // per island: its end in planned_
    std::vector<std::uint8_t> marked_;      // per contact: 1 when in a planned island
    std::vector<std::uint32_t> marked_list_;
    std::vector<std::uint32_t> row_contact_;  // per planned row: its contact
    std::vector<std::pair<std::uint32_t, std::uint32_t>> solved_islands_;  // ranges of planned_
    std::vector<double> solved_impulse_;    // per planned row, N s (valid in solved islands)
    std::vector<Solved> solved_;            // per disc
    std::vector<std::uint32_t> solved_bodies_;
    std::vector<std::uint32_t> collided_;
    // Scratch of one island.
    std::vector<std::uint32_t> bodies_;     // indices into Substep::bodies
    std::vector<BlockBody> state_, start_;
    std::vector<BlockContact> contacts_;
    std::vector<IslandContact> island_;
    std::vector<double> targets_, guesses_;  // per row: m/s, and N s (friction's first bound)
    DirectSolver direct_;
};

}  // namespace discreel::physics::detail
