#pragma once
// The manifold solver: one step of rigid bodies of any shape (shape.hpp) against each other.
// A sweep over bounding boxes finds the pairs; each near pair gets its contact manifold
// (manifold.hpp, speculative by as far as the pair can close within the step, which is what
// keeps a fast body from passing through a thin wall), warm-started from the last step by
// feature id, touching pairs that close fast struck two bodies at a time (body_strikes.cpp),
// solved with the two-point block solve (block_solver.hpp); then positions are
// integrated, bounces added, and whatever overlap remains is pushed out point by point from
// each manifold's anchors. The solver sees contact rows, never shapes: `collide` is the only
// place shapes meet.
#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "block_rows.hpp"
#include "block_solver.hpp"
#include "fat_pairs.hpp"
#include "island.hpp"
#include "joint.hpp"
#include "manifold.hpp"
#include "pair_filter.hpp"
#include "pair_touch.hpp"
#include "shape.hpp"
#include "toi.hpp"

namespace discreel::physics::detail {

// Awake and able to move (held bodies too): a pair needs one such body to be solved.
inline bool stirs(const Body& b) { return !b.asleep && b.motion != Motion::fixed; }

// v turned by the angle whose cosine and sine are `spin` (BodySolver's spin_: each body's
// turn in the step).
inline V2 turned_by(const V2& v, const std::pair<double, double>& spin) {
    const auto [c, s] = spin;
    return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

// A body's velocities and inverse masses as the block solve reads them.
inline BlockBody velocity_of(const Body& b) {
    return BlockBody{b.v, b.omega, b.inv_mass, b.inv_inertia};
}

struct BodySolverDef {
    int iterations = 6;            // velocity iterations per step (docs/physics.md)
    Mixing mixing;                 // how two materials make a contact's
    int position_iterations = 8;   // overlap-removal sweeps per step
    // Passes over the joints' rows after each velocity iteration's pass over the contacts:
    // the tail of a 20-link chain whipping round gains energy and parts its pins at one or
    // two, holds them within 0.7 mm at four (docs/tried.md).
    int joint_passes = 4;
    // The position passes of the joints other than pins (body_joints.cpp), each time they
    // run, at most: Box2D v2.4's three. At eight, a sagging 50 x 50 grid of pins cost 1.8 times
    // as much for 0.1 of its 1.7 mm widest gap.
    int joint_position_passes = 3;
    // The pins' position passes in the coloured rows, each time they run (once a step, twice
    // where the push-out or an impact moved a jointed body): a colour passes a correction one
    // link on, so a chain needs more than one by one; at three a 20-link chain's pins opened
    // 1.2 mm, at six 0.7 mm, for a tenth of the grid's time.
    int pin_position_passes = 6;
    double speculative = 0.02;     // metres: points this far apart are already contacts
    double slop = 5e-4;            // metres of overlap left alone (resting contact jitters less)
    // Metres of overlap a push-out leaves: under the slop, so that a point just pushed is not
    // pushed again by the sliver its neighbours' pushes give back.
    double push_to = 2.5e-4;
    double max_correction = 0.02;  // metres pushed out per point and sweep at most
    // The push-out moves the bodies of an island or block of masses far apart (pushed
    // together) as if none were more than this many times heavier than its lightest: a heavy
    // body driving a light one into a third is pushed back too, where true masses would move
    // only the light one, from one neighbour into the next (the disc solver's projection caps
    // its ratio too). Contacts iterated alike keep their own masses: capped there, the pile of
    // polygons overlapped deeper (docs/tried.md). Positions only: no velocity changes.
    double push_mass_ratio = 10;
    // An island (bodies that contacts between moving bodies connect) whose moving bodies'
    // masses differ by this factor or more is solved directly (island.hpp) when it has at most
    // `direct_points` contact points; the others iterate (docs/physics.md, "Limits").
    double direct_mass_ratio = 10;
    int direct_points = 16;
    // A larger island whose masses differ by this factor or more iterates by blocks: each
    // contact with the others of its lighter body, solved together; it does not bounce.
    double block_mass_ratio = 100;
    // A body that travels more than this many of its inner radii in a step is swept against
    // whatever its path reaches and meets it at the time of impact (body_impacts.cpp): a
    // speculative contact, made where the step starts, may miss the features that meet.
    double impact_travel = 0.5;
    // Impacts per such body and step at most; beyond, bodies keep the motion they have and
    // the next step's contacts push out what overlaps.
    int impacts_per_fast_body = 64;
    // Touching pairs of two moving bodies closing at the step's start faster than a settle
    // speed (the disc solver's rule) are struck two bodies at a time before the rows, each
    // blow passed on to the struck bodies' other touching pairs (body_strikes.cpp); at most
    // this many strikes per body and step.
    int strikes_per_body = 64;
    // Sweeps (times of impact of one pair) per step at most: `predictions_per_body` for each
    // body, plus `predictions_base`. A body whose new sweep is left unchecked once they are
    // spent stays where its last impact put it for the rest of the step, so the work of a step
    // is bounded however fast its bodies move and however many their paths cross.
    int predictions_per_body = 512;
    int predictions_base = 1024;
    // A pair's manifold is made again only once its bodies have moved against each other by
    // more than this fraction of the smaller one's inner radius, or turned by more than this
    // angle (radians), since it was made; until then it moves with them, its separations
    // following its points (a resting pile collides rarely).
    double recycle_travel = 0.002;
    double recycle_turn = 0.002;
    // The step's contacts are the last step's, moved with their bodies (no pair search, no
    // manifold made or matched), while no body has moved or turned by half the recycling
    // bounds above (for the world's smallest inner radius) or by a quarter of the speculative
    // distance since the last step that made them, nor will in this one at its speed now (a
    // resting pile makes its contacts rarely; anything moving makes them every step).
    bool keep_contacts = true;
    // An island that presses on a wall or a fixed body (a contact that pushed in the step)
    // and whose every body has moved slower
    // than `sleep_speed` (m/s, at its centroid and at its bounding radius from its spin) for
    // `sleep_after` seconds falls asleep: its bodies stop and cost nothing until an awake body
    // comes within reach of one of them. An island floating free keeps its momentum.
    bool sleep = true;
    double sleep_speed = 0.01;     // m/s
    double sleep_after = 0.5;      // s
};

class BodySolver {
public:
    explicit BodySolver(BodySolverDef def = {}) : def_(def) {}
    const BodySolverDef& def() const { return def_; }
    // `shapes`: each body's, in the bodies' order; `radius` of each body is its shape's
    // bounding radius.
    void step(std::vector<Body>& bodies, std::span<const Polygon> shapes, const V2& gravity,
              double dt);

    // The pairs that touched during the last step, in (a, b) order.
    std::span<const PairTouch> touches() const { return touches_; }
    // The deepest overlap between two bodies now (depth 0 when none overlap).
    struct Overlap {
        double depth = 0;              // metres
        std::uint32_t a = 0, b = 0;    // the pair
    };
    Overlap max_overlap(const std::vector<Body>& bodies, std::span<const Polygon> shapes) const;
    // The points of the contacts that touched in the last step, awake ones then asleep ones
    // (World::contact_points; `other` a body index, walls' fixed bodies included).
    void contact_points(const std::vector<Body>& bodies, std::vector<ContactPoint>& out) const;
    // Times of impact computed during the last step (at most the budget of BodySolverDef).
    std::size_t sweeps() const { return predictions_made_; }
    // Whether the last step kept the contacts of the step before (BodySolverDef::keep_contacts).
    bool kept_contacts() const { return kept_; }
    // A throw changed some body's velocity or mass (a grab, a release) before this step: it
    // makes its contacts again, as after forget().
    void thrown() { contacts_kept_ = false; }
    // Forgets contacts of bodies [first, last): they were replaced. The islands they slept in
    // wake (they may have rested on them).
    void forget(std::vector<Body>& bodies, std::size_t first, std::size_t last);
    // Pairs touching now: those that touched in the last step and those asleep touching.
    std::size_t touching() const;
    // Where the stages of each step add their times (stage_timer.hpp); null: not timed.
    void set_profile(StepProfile* profile) { profile_ = profile; }
    // The world's joints (joint.hpp), solved with the contacts from the next step on.
    void set_joints(Joints joints) { joints_ = std::move(joints); }
    const Joints& joints() const { return joints_; }
    // Which pairs may touch (pair_filter.hpp): categories, sensors.
    PairFilter& filter() { return filter_; }
    // The sensors' overlaps that began or ended in the last step, in pair order.
    std::span<const PairTouch> sensed() const { return sensed_; }

private:
    struct Anchor {
        V2 ra = V2::Zero(), rb = V2::Zero();   // world offsets from each centroid, metres
        double separation = 0;                 // metres, when the manifold was made
    };
    // A manifold as it was made, fixed to the bodies: each point's two surface points in
    // their own body's frame, the normal in A's, and where B was relative to A then.
    struct Made {
        struct Point {
            V2 a = V2::Zero(), b = V2::Zero();   // on A's surface in A's frame, B's in B's
            std::uint16_t id = 0;
        };
        std::array<Point, 2> points{};
        int count = 0;                 // points
        V2 normal = V2::UnitY();       // in A's frame
        V2 offset = V2::Zero();        // B's centroid in A's frame, metres
        double turn = 0;               // B's angle less A's, radians
    };
    struct PairContact {
        std::uint32_t a = 0, b = 0;    // body indices, a < b
        Made made;
        BlockContact contact;
        std::array<Anchor, 2> anchors{};
        double restitution = 0;
        std::array<double, 2> approach{};   // normal velocity before the solve, m/s
        bool touched = false;
        // Its normal, offsets and impulses are as the rows' last finish left them (set there;
        // a new manifold, a bounce and an island's push-out clear it): kept by the next step,
        // BlockRows builds only its bounds again.
        bool as_solved = false;
    };
    // The stages of a step, in order (body_solver.cpp unless said).
    void begin_step(std::vector<Body>& bodies, const V2& gravity, double dt);
    void find_pairs(const std::vector<Body>& bodies, double dt, double fall);
    void list_pairs(const std::vector<Body>& bodies);
    void mark_fast(const std::vector<Body>& bodies, double dt);
    // Whether a body at its velocities now travels more than impact_travel of its inner
    // radius in a step (it cannot move: never).
    bool moves_fast(const std::vector<Body>& bodies, std::size_t i, double dt) const;
    void make_contacts(const std::vector<Body>& bodies, double dt);
    // (body_keep.cpp) Whether this step may keep the last step's contacts
    // (BodySolverDef::keep_contacts); the last step's contacts moved with their bodies into
    // fresh_; the bodies' motion since the contacts were made, counted at the step's end.
    bool keeps_contacts(const std::vector<Body>& bodies, double dt) const;
    void move_contacts(const std::vector<Body>& bodies, double dt);
    void count_motion(const std::vector<Body>& bodies, bool kept);
    // (body_strikes.cpp) Pairs touching, or meeting within the step, closing faster than
    // their strike speed, resolved two bodies at a time before the rows at the time they
    // meet, the blows passed on through touching pairs.
    void strike_touching(std::vector<Body>& bodies, const V2& gravity, double dt);
    double strike_speed(const PairContact& pc, double g, double dt) const;   // m/s
    // When point k of pc meets at the step's start velocities, seconds into the step (0: it
    // touches now); nothing when it does not close faster than `settle` m/s or not within dt.
    std::optional<double> meets(const PairContact& pc, int k, const BlockBody& va,
                                const BlockBody& vb, double settle, double dt) const;
    // When the pair's first point meets (as meets()), if any point does.
    std::optional<double> strikes_at(const PairContact& pc, const std::vector<Body>& bodies,
                                     double g, double dt) const;
    // Strikes pc's meeting points at `t` seconds into the step: its bodies' velocities change
    // now, their positions move on as if they changed at t (strike_shift_). Its impulse, N s.
    double strike(std::vector<Body>& bodies, const PairContact& pc, double t, double g,
                  double dt);
    // c's normal and offsets moved on to t seconds into the step (strike).
    void at_time(BlockContact& c, const PairContact& pc, const std::vector<Body>& bodies,
                 double t) const;
    // How near a pair's points must be to touch, metres.
    double touch_distance(const PairContact& pc) const;
    // A body's velocities at the step's start, before begin_step's gravity.
    BlockBody start_velocity(const Body& b) const;
    void solve_velocities(std::vector<Body>& bodies);       // body_velocities.cpp
    void integrate_positions(std::vector<Body>& bodies, double dt);   // body_positions.cpp
    void bounce(std::vector<Body>& bodies, double settle, double dt);  // body_velocities.cpp
    void limit_bounce_energy(const std::vector<Body>& bodies);          // body_velocities.cpp
    // (body_velocities.cpp) A bounce of one moving body off a fixed one, timed within the
    // step: sets the points' targets (velocities at the step's end) and gives the gap the
    // body is to end the step with, metres; nothing where the pair is not such a bounce.
    std::optional<double> time_bounce(PairContact& pc, const std::vector<Body>& bodies,
                                      double dt) const;
    // A direct island's bounce by Poisson's rule, undone if it would add energy; the kinetic
    // energy of the island's bodies (members_) at these velocities, J.
    void bounce_together(std::span<const IslandContact> island);
    double island_kinetic(const std::vector<BlockBody>& states) const;
    // Solves again, from their arrival and with less of the warm start, the islands of masses
    // far apart that the iterations left with more kinetic energy than they came with.
    void solve_gainers_again(const std::vector<Body>& bodies);   // body_velocities.cpp
    // (body_joints.cpp) Scales back the velocities of groups of jointed bodies that the rows
    // left with more kinetic energy than they arrived with.
    void limit_joint_energy(const std::vector<Body>& bodies);
    void push_out(std::vector<Body>& bodies);               // body_positions.cpp
    // The joints' position passes (body_joints.cpp): before the contacts' push-out, and at
    // the step's end where the impacts or the push-out moved a jointed body (joints_moved).
    void correct_joints(std::vector<Body>& bodies);
    // Its first part: the pins', in the coloured rows.
    void correct_pins(std::vector<Body>& bodies);
    // Whether a body a joint holds has moved since correct_joints last ran.
    bool joints_moved(const std::vector<Body>& bodies) const;
    // Its parts: point k's separation now from its anchors (and its offsets now, into ra and
    // rb); a body's turn in the step grown by `by` radians; a positional impulse of `amount`
    // (kg m) along the normal at ra, rb; an island's or block's points pushed together; one
    // contact's points pushed.
    double separation_now(const PairContact& pc, int k, V2& ra, V2& rb) const;
    // The offsets ra0, rb0 (from each body's centroid, at the step's start) of a point of pc,
    // turned with the bodies' turns in the step into ra, rb.
    void offsets_now(const PairContact& pc, const V2& ra0, const V2& rb0, V2& ra, V2& rb) const;
    void turn_body(std::uint32_t i, double by);
    void push_apart(std::vector<Body>& bodies, const PairContact& pc, const V2& ra,
                    const V2& rb, double amount);
    void push_out_together(std::vector<Body>& bodies, std::span<const IslandContact> island);
    void push_out_contact(std::vector<Body>& bodies, const PairContact& pc);
    // The inverse masses a push moves bodies by (push_mass_): body i's own, raised to within
    // def_.push_mass_ratio of `lightest` (the inverse mass of the lightest body it is pushed
    // with; 0: its own); and those of every body of an island or block, pushed together.
    void set_push_mass(std::uint32_t i, double lightest, const std::vector<Body>& bodies);
    void set_push_masses(std::span<const IslandContact> group, const std::vector<Body>& bodies);
    // Pairs that started apart and sank in deeper than the slop: their bodies are fast.
    void mark_sunk(const std::vector<Body>& bodies);        // body_positions.cpp
    void record_touches();
    // (body_sleep.cpp) Wakes the sleeping islands that a throw or an impact moved; whether
    // any body that can move is awake now (if none, the step has nothing to do).
    bool wake_moved(std::vector<Body>& bodies);
    void count_parked();   // parked_touching_ from parked_
    // Moves the parked contacts of awake islands back into contacts_.
    void unpark(const std::vector<Body>& bodies);
    // Wakes the sleeping islands an awake body can reach within the step.
    void wake_reached(std::vector<Body>& bodies, const V2& gravity, double dt);
    // Wakes the islands flagged in waking_, adding `kick` to their velocities; whether there
    // were any.
    bool wake_flagged(std::vector<Body>& bodies, const V2& kick);
    // Counts each awake body's time at rest, puts islands at rest long enough to sleep and
    // parks their contacts.
    void fall_asleep(std::vector<Body>& bodies, double dt);
    // The manifold of pc's pair now: the one made before, moved with the bodies, while they
    // moved little against each other since (def_.recycle_*), else a new one from collide
    // (kept in pc.made).
    Manifold manifold_of(PairContact& pc, const PairContact* before,
                         const std::vector<Body>& bodies);
    // Sweeps the pairs with a fast body (or one fast_ marks) from the step's start to its end
    // and takes their impacts in time order (body_impacts.cpp); approaches slower than `settle`
    // are not impacts.
    void time_impacts(std::vector<Body>& bodies, double dt, double settle);
    // The stages of time_impacts: each body's sweep over the step, fast_ marking those that
    // travel far (how many); the swept boxes and what each can reach (still_, moving_ by low
    // x); one impact taken (stopped and bounced, the bodies' sweeps begun again from it and
    // what they now reach predicted); and the bodies left with impacts or unchecked sweeps
    // when the budgets ran out, stopped.
    std::size_t begin_sweeps(const std::vector<Body>& bodies, double dt);
    void list_reach(const std::vector<Body>& bodies, double dt);
    template <class F>
    void for_each_reachable(std::uint32_t i, F&& f) const;   // f(j) for each j i's box overlaps
    struct PredictedImpact;
    void take_impact(std::vector<Body>& bodies, const PredictedImpact& predicted, double dt);
    // The impact moved on to the time its surfaces touch: the advancement stops up to twice
    // the target short of it.
    PredictedImpact touching_time(const PredictedImpact& e, double dt) const;
    // Adds an impact's impulse (N s) to its pair's touch in impact_touches_, or
    // lists the pair with it (`began`: a new contact) when it has none and the impulse is > 0.
    void add_impact_touch(std::uint32_t a, std::uint32_t b, double impulse, bool began);
    void stop_unfinished(std::vector<Body>& bodies);
    // Predicts the first impact of bodies i < j from `t_begin` into impacts_ (`after_only`:
    // only one after t_begin).
    void predict_impact(const std::vector<Body>& bodies, std::uint32_t i, std::uint32_t j,
                        double t_begin, double dt, bool after_only = false);
    // (body_islands.cpp) Groups the contacts of the islands to solve directly into islands_ (island_start_
    // delimits them, direct_ marks them) and those of larger islands of masses far apart by
    // block into blocks_ (block_start_, blocked_).
    void find_islands(const std::vector<Body>& bodies);
    std::uint32_t root(std::uint32_t i);
    // The root of i in a union-find forest of parents (halving the path to it).
    static std::uint32_t root_in(std::vector<std::uint32_t>& parent, std::uint32_t i);
    // The island of a contact: its moving body's root (a wall, peg or held body joins none).
    std::uint32_t island_of(const PairContact& pc, const std::vector<Body>& bodies);
    // Joins the islands of i and j under the lower root: (that root, the other), or nothing
    // when they were one already.
    std::optional<std::pair<std::uint32_t, std::uint32_t>> unite(std::uint32_t i, std::uint32_t j);
    // Groups the contacts selected (per contact of fresh_) by group_key_ into `grouped`, the
    // groups delimited by `starts`.
    void group(const std::vector<unsigned char>& selected, std::vector<IslandContact>& grouped,
               std::vector<std::size_t>& starts);
    // Calls f with each group of `grouped` that `starts` delimits.
    template <class F>
    static void for_each_group(std::span<const IslandContact> grouped,
                               std::span<const std::size_t> starts, F&& f) {
        for (std::size_t k = 0; k + 1 < starts.size(); ++k) {
            f(grouped.subspan(starts[k], starts[k + 1] - starts[k]));
        }
    }
    // Applies sign times a contact's accumulated impulses to state_.
    void apply_totals(const PairContact& pc, double sign);
    // The pair an island contact's manifold belongs to.
    PairContact* pair_of(const IslandContact& ic) { return &fresh_[ic.pair]; }

    BodySolverDef def_;
    StepProfile* profile_ = nullptr;
    Joints joints_;
    PairFilter filter_;
    // Whether bodies i < j make no contact: a joint or their categories keep them apart, or
    // one is a sensor.
    bool apart(std::uint32_t i, std::uint32_t j) const {
        return filter_.excludes(i, j) || joints_.keeps_apart(i, j);
    }
    // (body_solver.cpp) The sensors' overlaps now against the
    // last step's: sensing_ (a << 32 | b, ascending) and the events in sensed_.
    void sense(const std::vector<Body>& bodies);
    // Calls watch(key) for each pair of a sensor and a body, neither of which a contact moves
    // and one of which moves as told: pairs the fat list leaves out.
    template <class Watch>
    void watch_unpushable(const std::vector<Body>& bodies, Watch&& watch);
    std::vector<std::uint64_t> sensing_, sensing_now_;
    std::vector<std::uint32_t> unpushed_, unpushed_sensors_;   // scratch of watch_unpushable
    std::vector<PairTouch> sensed_;
    double dt_ = 0;                         // s: this step's
    std::span<const Polygon> shapes_;       // each body's shape: set by step(), read within it
    // Per body: its shape's inner radius (toi.hpp), metres (< 0: not computed yet), and how
    // long it has moved slower than def_.sleep_speed, seconds. fit() sizes them.
    std::vector<double> inner_, still_for_;
    void fit(std::size_t bodies) {
        inner_.resize(bodies, -1.0);
        still_for_.resize(bodies, 0.0);
    }
    std::vector<PairContact> contacts_;     // the last step's, in (a, b) order
    // Whether contacts_ may be kept by the next step (forget(), thrown(), a fast body and an
    // island falling asleep end it); per body, how far it moved (metres, its bounding
    // radius's arc included) and turned (radians) since they were made.
    bool contacts_kept_ = false;
    bool kept_ = false;                     // the last step kept them
    std::vector<double> travelled_, turned_since_;
    std::vector<PairContact> fresh_;        // scratch
    FatPairs fat_pairs_;
    std::vector<std::uint64_t> fat_list_;   // the pairs whose fat boxes overlap: a << 32 | b
    std::vector<double> fat_margin_;        // scratch: metres each box is fattened by
    std::vector<unsigned char> movable_;    // scratch: per body, whether a contact moves it
    // The step's: those of fat_list_ near enough with an awake body that can move.
    std::vector<std::uint64_t> pairs_;
    std::vector<unsigned char> stirring_;   // scratch: per body, awake and able to move
    // Contacts of pairs with no awake body (asleep, or asleep against a wall), in (a, b)
    // order: kept as they were, for the warm start and the events when they wake.
    std::vector<PairContact> parked_;
    std::size_t asleep_count_ = 0;
    std::size_t parked_touching_ = 0;       // parked contacts that touched
    std::vector<unsigned char> waking_;     // scratch: per island (a body index), to wake
    std::vector<std::uint32_t> order_;      // scratch: bodies by the low x of their box
    std::vector<std::array<double, 4>> boxes_;   // scratch: lo x, lo y, hi x, hi y
    std::vector<double> margin_;            // scratch: metres a body can close in the step
    std::vector<Transform> transforms_;     // scratch: each body's at the step's start
    std::vector<V2> start_x_;               // scratch: each body's centroid at the step's start
    std::vector<double> start_angle_;       // scratch: each body's angle at the step's start
    // Scratch: each body's velocity with this step's gravity (begin_step's), before any
    // contact, strike or impact changes it, m/s (a body woken in the step gets its gravity
    // after this, and so moves by its end velocity in that step).
    std::vector<V2> start_v_;
    // Scratch: the body moves by its mean velocity in this step (integrate_positions).
    std::vector<unsigned char> free_;
    std::vector<BlockBody> state_;          // scratch
    // Scratch of the energy checks of islands of masses far apart (body_velocities.cpp):
    // every body's velocities before the solve; per island root, the kinetic energy then and
    // after the iterations, and whether to solve it again (1; 2: a held body pushes it); a
    // direct island's bodies, their velocities and its points' impulses before its bounce,
    // and the impulses that stopped it.
    std::vector<BlockBody> arrived_;          // scratch: velocities before the rows
    // Scratch of bounce: the pairs it bounced (indices into fresh_), each body's count of
    // them, the velocities the rows left and the points' impulses before the bounce (two
    // per pair), the bounces' clusters of moving bodies (union-find), their points, whether a
    // held body pushes them, energies and scales.
    std::vector<std::uint32_t> bounced_, hits_of_, cluster_, cluster_points_;
    std::vector<unsigned char> cluster_held_;
    // The timed bounces' shifts (time_bounce), made once the energy check has kept them.
    struct TimedShift {
        std::uint32_t body = 0;
        V2 shift = V2::Zero();   // metres
    };
    std::vector<TimedShift> timed_shifts_;
    std::vector<BlockBody> rows_state_;
    std::vector<double> bounce_impulses_, energy_, scale_;
    std::vector<double> arrived_energy_, solved_energy_;
    std::vector<unsigned char> again_;
    // Per contact of fresh_: its points' warm-start impulses (normal, tangent), N s.
    std::vector<std::array<std::array<double, 2>, 2>> warm_;
    std::vector<std::uint32_t> members_;
    std::vector<BlockBody> kept_states_;
    std::vector<double> kept_impulses_, stopping_;
    std::vector<V2> moved_;                 // scratch: metres each body moved this step
    std::vector<double> turned_;            // scratch: radians each body turned
    std::vector<std::pair<double, double>> spin_;   // scratch: cos and sin of turned_
    std::vector<PairTouch> touches_;
    // The islands of the step: union-find parents per body, each root's lightest and heaviest
    // body's inverse mass (1/kg) and point count, and per contact of fresh_ whether it is in a
    // direct one.
    std::vector<std::uint32_t> parent_;
    std::vector<double> lightest_, heaviest_;
    std::vector<std::uint8_t> grounded_;   // fall_asleep's: the island rests on a fixed body
    std::vector<unsigned char> jointed_;    // find_islands': per root, a joint holds a body
    std::vector<Joints::Moved> joint_moves_;   // scratch of correct_joints, per body
    std::vector<PinRef> pins_;              // the pins' velocity rows of the step
    std::vector<PinRef> pin_gaps_;          // scratch of correct_pins: its position rows
    std::vector<BlockBody> pin_moves_;      // scratch of correct_pins: per body, its move
    BlockRows pin_positions_;               // the pins' position rows
    // The held bodies' centroids and angles as correct_joints left them, in held_bodies order.
    std::vector<std::pair<V2, double>> joint_poses_;
    bool far_islands_ = false;              // some island's masses are direct_mass_ratio apart
    std::vector<int> points_;
    std::vector<unsigned char> direct_;
    std::vector<IslandContact> islands_;    // grouped by island, each in fresh_'s order
    std::vector<std::size_t> island_start_;
    std::vector<std::size_t> island_fill_;    // scratch
    // The contacts of larger islands of masses block_mass_ratio apart, grouped by block
    // (blocked_: per contact of fresh_).
    std::vector<unsigned char> blocked_;
    // Every moving body within direct_mass_ratio of every other (find_islands): no island
    // can have masses far apart, and touching pairs are struck (body_strikes.cpp).
    bool even_world_ = true;
    std::vector<IslandContact> blocks_;
    std::vector<std::size_t> block_start_;
    std::vector<std::uint32_t> group_key_;    // per contact: its island root or block's body
    DirectSolver direct_solver_;
    std::vector<RowRef> rows_;              // the contacts the iterations solve, in fresh_'s order
    BlockRows block_rows_;
    // Impacts between moving bodies (body_impacts.cpp): each body's motion since its latest
    // impact, its swept box, how many impacts changed it (stale predictions name an older
    // count), the predicted impacts as a heap, and the pairs that met.
    struct PredictedImpact {
        double t = 0;                        // seconds into the step
        double gap = 0;                      // metres between the surfaces then
        std::uint32_t a = 0, b = 0;
        std::uint32_t version_a = 0, version_b = 0;
    };
    std::vector<Sweep> sweeps_;
    std::vector<std::array<double, 4>> swept_;
    std::vector<std::uint32_t> versions_;
    std::vector<unsigned char> fast_;
    std::vector<unsigned char> nudged_;      // fast only because an impact struck it, slowly
    std::vector<PredictedImpact> impacts_;
    std::vector<PairTouch> impact_touches_;  // this step's impacts'
    // Scratch of strike_touching: the contacts to look at (indices into fresh_) and whether
    // queued, each body's contacts (contacts_of_, delimited by contact_start_), its strikes
    // in the step and whether struck.
    std::vector<std::uint32_t> queue_, contact_start_, contacts_of_, strikes_of_;
    std::vector<unsigned char> queued_, struck_;
    std::vector<double> struck_impulse_;     // N s per contact of fresh_: its strikes' this step
    // Per body: when its latest strike of the step was (seconds into it), and how far its
    // position and angle are to move besides its end velocity's motion (metres, radians),
    // which puts its strikes at their times; `shifted_`: some strike was after the start.
    std::vector<double> struck_at_;
    std::vector<V2> strike_shift_;
    std::vector<double> strike_turn_;
    bool shifted_ = false;
    V2 fall_ = V2::Zero();                   // m/s: gravity times the step, this step's
    std::vector<std::uint32_t> still_, moving_, changed_;   // scratch: see time_impacts
    std::vector<double> moving_lo_;
    double widest_ = 0;                      // metres: the widest moving swept box in x
    std::vector<unsigned char> changed_flag_;
    std::vector<unsigned char> unchecked_;   // its sweep's pairs were not all predicted
    std::size_t predictions_left_ = 0;
    std::size_t predictions_made_ = 0;       // in the last step
    double settle_ = 0;                      // m/s: slower approaches are not impacts
    std::vector<double> separation_, push_;   // scratch, per point of an island
    // Scratch of push_out: how far an island's push would move and turn each of its bodies.
    struct Shift {
        std::uint32_t body = 0;
        V2 by = V2::Zero();        // metres
        double turn = 0;           // radians
    };
    std::vector<Shift> shifts_;
    // Scratch of push_out: pushes so far in the step, per body the count after its last push,
    // per contact the count when its separations were last looked at.
    std::uint32_t pushes_ = 0;
    std::vector<std::uint32_t> pushed_at_, seen_at_;
    // Scratch of push_out: per body, the inverse masses its latest push moved it by (its own,
    // or, pushed with an island or block, raised to within push_mass_ratio of its lightest
    // body); velocities unused.
    std::vector<BlockBody> push_mass_;
};

}  // namespace discreel::physics::detail
