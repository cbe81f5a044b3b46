#pragma once
// The disc solver's broad phase: the pairs that can touch during the next step. Discs grown by
// their margins are paired by the grid search (grid_pairs.hpp); the pair list is
// reused across steps until some disc has used up its margin, so a resting pile rebuilds
// rarely. Cost is linear in the number of discs; pairs come out sorted by (a, b).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "body.hpp"
#include "contact.hpp"
#include "grid_pairs.hpp"
#include "geometry.hpp"

namespace discreel::physics::detail {

class BroadPhase {
public:
    // Keeps `contacts` holding every pair that can come into contact during the next step of
    // length dt, sorted by (a, b); pairs that stay keep their warm-start impulses and history.
    // True when it rebuilt the list (contact indices changed).
    // `known_valid`: what keeps() said of every moving disc since the bodies last changed, if
    // the caller asked it (it saves a pass over the bodies).
    bool update(const std::vector<Body>& bodies, std::size_t disc_count,
                const std::vector<Feature>& features, double dt, double gravity,
                std::vector<Contact>& contacts, std::optional<bool> known_valid);

    bool built() const { return built_; }
    // How the contacts it makes mix their bodies' materials.
    void set_mixing(const Mixing& mixing) { mixing_ = mixing; }
    // Bodies [first, last) were replaced: their pairs leave `contacts` (the others keep their
    // history), and the next update() builds the list afresh.
    void forget(std::size_t first, std::size_t last, std::vector<Contact>& contacts);
    // Of the last rebuild, what no result shows: whether it hashed the grid's cells (the discs
    // spread too far apart to number them row by row), and disc i's margin (metres).
    bool hashed() const { return grid_.hashed(); }
    double margin(std::size_t i) const { return margin_[i]; }
    // Whether moving disc i (body b) stays within its margin over a step of length dt: the
    // list stays valid while this holds for every moving disc. Only once built().
    bool keeps(const Body& b, std::size_t i, double dt, double gravity) const {
        // A pair left out was farther apart than the sum of its margins at the rebuild; it
        // cannot touch this step while every disc's drift plus reach stays within its own
        // margin. Most discs are far inside it, which (drift + speed dt)^2 <= 2 (drift^2 +
        // (speed dt)^2) shows without a square root.
        const double drift2 = (b.x - anchor_[i]).squaredNorm();
        const double fall = b.falls() ? 0.5 * gravity * dt * dt : 0.0;
        const double room = margin_[i] - fall;
        if (room >= 0.0 && 2.0 * (drift2 + b.v.squaredNorm() * dt * dt) <= room * room) {
            return true;
        }
        const double left = margin_[i] - (b.v.norm() * dt + fall);
        return !(left < 0.0 || drift2 > left * left);
    }

private:
    Mixing mixing_;
    bool still_valid(const std::vector<Body>& bodies, std::size_t disc_count, double dt,
                     double gravity) const;
    // The pairs of discs whose fattened discs (radius + margin_) overlap, into pairs_.
    void find_disc_pairs(const std::vector<Body>& bodies, std::size_t disc_count);
    // Widens the margins of discs in pairs_ that a faster disc could strike to a speed their
    // margin does not cover; true if any was.
    bool widen_threatened(const std::vector<Body>& bodies, double dt, double gravity);
    void rebuild(const std::vector<Body>& bodies, std::size_t disc_count,
                 const std::vector<Feature>& features, double dt, double gravity,
                 std::vector<Contact>& contacts);

    bool built_ = false;
    std::vector<V2> anchor_;        // centres at the last rebuild
    std::vector<double> margin_;    // metres each disc may move before a rebuild

    // Scratch kept to avoid reallocating every rebuild.
    std::vector<std::uint64_t> pairs_;
    std::vector<std::uint64_t> sorted_;
    std::vector<std::uint32_t> digit_count_;
    GridPairs grid_;
    std::vector<GridCircle> circles_;   // per disc: grown by its margin
    std::vector<Contact> merged_;
    std::vector<std::uint64_t> listed_;  // the pairs of the list last built, as pair keys
};

}  // namespace discreel::physics::detail
