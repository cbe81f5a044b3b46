#pragma once
// The disc solver's resting stage of a substep (contact_solver.cpp).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "discreel/clones.hpp"
#include "disc_islands.hpp"
#include "simd.hpp"
#include "substep.hpp"

namespace discreel::physics::detail {

// The resting stage's colouring (contact_solver.cpp): greedy, in list order, each contact
// taking the lowest colour that no earlier contact of its discs has, so that no two contacts of
// one colour share a disc (a wall feature, b >= disc_count, takes no colour: no row changes
// it). A contact whose discs already have all overflow_colour colours between them gets
// overflow_colour, which promises nothing. colour_of: per contact; used: scratch, per disc,
// bit c set once it is in a contact of colour c.
inline constexpr unsigned overflow_colour = 64;
void colour_greedily(std::span<const Contact> contacts, std::size_t disc_count,
                     std::vector<std::uint64_t>& used, std::vector<std::uint8_t>& colour_of);

// Stage 2: resting contact. Sequential impulses with accumulated clamping and warm starting,
// acting like forces spread over the substep; then positions are integrated. A class only to
// keep its scratch arrays between substeps.
class ContactSolver {
public:
    // Before the active contacts are listed.
    void begin(const Substep& s);
    // The active contacts of a block as they are listed (their indices into s.contacts), while
    // they are in cache: each one's colour is counted and it is queued for the row build.
    void list(const Substep& s, std::span<const std::uint32_t> listed) {
        const Body* const bodies = s.bodies.data();
        const Contact* const contacts = s.contacts.data();
        const std::uint8_t* const colour_of = colour_of_.data();
        std::uint32_t* const colour_start = colour_start_.data();
        for (const std::uint32_t index : listed) {
            const Contact& c = contacts[index];
            const bool a_moves = bodies[c.a].inv_mass != 0.0;
            const bool b_moves = bodies[c.b].inv_mass != 0.0;
            if (!a_moves && !b_moves) continue;  // two immovable bodies: nothing to solve
            const unsigned colour = colour_of[index];
            ++colour_start[colour + 1];
            Pending p{index, c.a, c.b, colour};
            // A row end on an immovable body gets its own velocity record, appended after the
            // bodies' (all zeros: it never changes, and its velocity is folded into the row),
            // so that rows on one wall do not chain through its record.
            if (!a_moves) p.a = fresh_copy(s);
            if (!b_moves) p.b = fresh_copy(s);
            pending_.push_back(p);
        }
    }
    void solve(Substep& s, int iterations);
    // After the listing, before the impacts stage: plans the direct islands
    // (disc_islands.hpp), whose contacts the impacts stage leaves to solve().
    void plan_islands(Substep& s);
    const DiscIslands& islands() const { return islands_; }

private:
    // Four doubles (see simd.hpp): the row build's geometry, half a block at a time, in
    // double precision. Where this file is not built for AVX, GCC aligns the type to 16 bytes
    // only, so the structs holding it ask for the 32 that AVX loads need.
    using Lanes = simd::Double4;
    // Eight floats, one per row of a block: one AVX register in the AVX2 build of solve_rows,
    // two SSE (or NEON) registers in the baseline one.
    using Floats = simd::Float8;
    using Quad = simd::Float4;  // one velocity record
    static constexpr unsigned width = 8;  // rows per block, the lanes of Floats
    static constexpr unsigned half = 4;   // the lanes of Lanes
    // What the iterations change of a body: the change of its velocity over the iterations,
    // dv.x, dv.y (m/s) and r d(omega) (m/s), with its inverse mass in mass units (see
    // mass_unit_), so that a block gathers each of its records with one aligned load (see
    // load()). The velocities themselves stay in the bodies, in doubles; a row folds its bodies'
    // start velocities into its constants, in doubles, so the floats carry only corrections.
    struct alignas(16) Velocity {
        Quad packed = {};
    };
    // Eight contacts of one colour (they share no moving body, so solving them side by side gives
    // the same result as one after the other), with what stays constant over the substep
    // precomputed in doubles and rounded once. A lane without a contact points both ends at a
    // scratch record, with zero coefficients, so it computes zero impulses.
    struct alignas(32) RowBlock {
        std::uint32_t a[width] = {}, b[width] = {};  // indices into velocities_
        Floats normal_x = {}, normal_y = {};  // unit, from b towards a, at the predicted end
        Floats bias = {};            // m/s, lower bound on n.(dv_a - dv_b)
        Floats slip = {};            // m/s, the contact points' tangential velocity at the start
        Floats normal_mass = {};     // mass units
        Floats tangent_mass = {};    // mass units
        Floats friction = {};
        Floats normal_impulse = {};  // mass units m/s, accumulated
        Floats tangent_impulse = {}; // mass units m/s, accumulated
    };
    // What the row build needs of a body, in one cache line of two records that a half block
    // gathers with a transpose each (see build_rows()).
    struct alignas(32) Predicted {
        Lanes motion = {};  // end x, y (m, where it ends up without contact forces); v_begin x, y
        Lanes now = {};     // v x, y (m/s, after gravity), omega (rad/s), radius (m)
    };
    // A contact to solve: its velocity records and colour (see contact_solver.cpp).
    struct Pending {
        std::uint32_t contact = 0;     // index into Substep::contacts
        std::uint32_t a = 0, b = 0;    // indices into velocities_
        unsigned colour = 0;
    };
    // Rows whose discs have all 64 colours go to one last group, solved a row at a time.
    static constexpr unsigned overflow = overflow_colour;
    void colour_contacts(const Substep& s);
    std::uint32_t fresh_copy(const Substep& s) {
        return static_cast<std::uint32_t>(s.bodies.size() + copies_++);
    }
    // The code that runs on whole blocks, on x86-64 built for AVX2 and for the baseline, the
    // one the CPU can run chosen at load time (DISCREEL_CLONES): the warm start and the
    // iterations over rows_, and the row build.
    DISCREEL_CLONES void solve_rows(int iterations);
    DISCREEL_CLONES void build_rows(const Substep& s, double inv_h);
    [[gnu::always_inline]] static void transpose(const Lanes& r0, const Lanes& r1,
                                                 const Lanes& r2, const Lanes& r3, Lanes& c0,
                                                 Lanes& c1, Lanes& c2, Lanes& c3);
    // Inlined, so that they are built for the caller's instruction set.
    [[gnu::always_inline]] void load(const std::uint32_t (&records)[width], Floats& x,
                                     Floats& y, Floats& u, Floats& inv_mass) const;
    [[gnu::always_inline]] void store(const std::uint32_t (&records)[width], const Floats& x,
                                      const Floats& y, const Floats& u, const Floats& inv_mass);

    std::vector<Predicted> predicted_;  // per body
    // Per body, then one per row end on an immovable body, then the empty lanes' scratch one.
    std::vector<Velocity> velocities_;
    std::vector<RowBlock> rows_;        // grouped by colour: no two rows of one share a disc
    std::vector<Pending> pending_;      // in active order
    std::vector<std::uint32_t> lane_of_;  // per pending row, its lane in rows_
    std::vector<std::uint32_t> pending_of_lane_;  // per lane of rows_, index into pending_
    std::vector<std::uint32_t> empty_lanes_;      // lanes of rows_ without a row
    std::uint32_t copies_ = 0;           // velocity records after the bodies', one per row end
                                         // on an immovable body (all zeros)
    // What a contact's rows need of its bodies' masses, which only change with the contact
    // list or a throw: two divisions per row less in every substep.
    struct Masses {
        float normal = 0.0F;           // mass units
        float tangent = 0.0F;          // mass units
    };
    void compute_masses(const Substep& s);
    std::vector<Masses> masses_;       // per contact
    // The rows' masses and impulses are in units of this many kg, a power of two near the
    // heaviest moving disc's mass (so scaling by it is exact), which keeps them far inside the
    // range of a float whatever the masses of a scene.
    double mass_unit_ = 1.0;
    std::uint64_t massed_contacts_ = ~std::uint64_t{0};  // the versions masses_ is for
    std::uint64_t massed_bodies_ = ~std::uint64_t{0};
    std::vector<std::uint64_t> colours_used_;  // per disc, bit c: in a row of colour c
    std::vector<std::uint8_t> colour_of_;      // per contact

    // The direct islands (disc_islands.hpp), and what their rows need of the row build in
    // double precision, per lane of rows_ (written only while the masses are far apart; the
    // impulse is filled in after the iterations).
    DiscIslands islands_;
    std::vector<IslandRow> geometry_;
    std::vector<std::uint32_t> row_contacts_;  // per pending row, its contact (plan_islands)
    std::vector<IslandRow> island_rows_;
    std::uint64_t coloured_version_ = ~std::uint64_t{0};  // the contact list colour_of_ is for
    std::vector<std::uint32_t> colour_start_;
};

}  // namespace discreel::physics::detail
