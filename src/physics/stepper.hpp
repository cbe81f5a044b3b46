#pragma once
// What World asks of a solver. World owns the bodies (the definition's, in its order, then the
// solver's own fixed bodies for the walls), the throws, the respawns, the events and the
// measures every body shares; a solver owns its contacts and the stages of its step
// (docs/physics.md). Two solvers answer: the disc solver (disc_stepper.hpp) for worlds of plain
// discs, the manifold solver (shape_stepper.hpp) once any body has a shape.
#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "body.hpp"
#include "discreel/physics.hpp"
#include "pair_touch.hpp"

namespace discreel::physics::detail {

class Stepper {
public:
    virtual ~Stepper() = default;
    // A copy of the whole state (contacts, warm starts, caches), stepping on exactly as this
    // one would; its profile is unset (set_profile).
    virtual std::unique_ptr<Stepper> clone() const = 0;
    // Velocity iterations per substep (WorldDef::iterations, or the solver's own for 0).
    virtual int iterations() const = 0;
    // The step from t0 to t1 (seconds; 1 / WorldDef::rate apart); `thrown`: a throw changed a
    // body at its start. Appends the pairs that began to touch, in a deterministic order, to
    // `began`.
    virtual void step(std::vector<Body>& bodies, double t0, double t1, bool thrown,
                      std::vector<PairTouch>& began) = 0;
    // After the throws have put held bodies on their paths, dt the step's length (0: before
    // the first step): the first body whose state is not finite, if any.
    virtual std::optional<std::size_t> end_step(std::vector<Body>& bodies, double dt) = 0;
    // Bodies [first, last) are about to be replaced: their contacts are forgotten.
    virtual void forget(std::vector<Body>& bodies, std::size_t first, std::size_t last) = 0;
    // Body i has been replaced by one of this definition.
    virtual void replaced(std::size_t i, const BodyDef& def) = 0;
    // The wall whose fixed body is bodies[body count + k].
    virtual std::size_t wall_of(std::size_t k) const = 0;
    // The measures only the solver knows: the deepest overlap, the pairs touching, the sweeps.
    virtual void add_stats(const std::vector<Body>& bodies, std::size_t body_count,
                           WorldStats& stats) const = 0;
    // Each joint's state now, in definition order (none: a solver without joints).
    virtual void joint_states(const std::vector<Body>& /*bodies*/,
                              std::vector<JointState>& out) const {
        out.clear();
    }
    // The points where bodies touch now (World::contact_points), walls' as the stepper's
    // fixed body indices (at or past `body_count`; World names their walls), with the last
    // substep's resting normal impulse in `force` (World divides it by the substep's time).
    virtual void contact_points(const std::vector<Body>& bodies, std::size_t body_count,
                                std::vector<ContactPoint>& out) const = 0;
    // Where the stages of each step add their times (stage_timer.hpp); null: not timed.
    virtual void set_profile(StepProfile* profile) { profile_ = profile; }

protected:
    StepProfile* profile_ = nullptr;
};

}  // namespace discreel::physics::detail
