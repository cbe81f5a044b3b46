#include "body_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "discreel/physics.hpp"
#include "stage_timer.hpp"

namespace discreel::physics::detail {

void BodySolver::find_pairs(const std::vector<Body>& bodies, double dt, double fall) {
    const std::size_t n = bodies.size();
    boxes_.resize(n);
    margin_.resize(n);
    transforms_.resize(n);
    // An asleep body has not moved since its box was made (a respawn makes bodies afresh,
    // awake, and every body is awake in its first step).
    for (std::size_t i = 0; i < n; ++i) {
        const Body& b = bodies[i];
        if (b.asleep) continue;
        // How far the body's surface can move in the step: the pair's speculative distance
        // is the sum of the two, so contacts are found before a fast body passes through.
        margin_[i] = (b.v.norm() + std::abs(b.omega) * b.radius) * dt +
                     (b.inv_mass > 0 ? fall : 0.0) + 0.5 * def_.speculative;
        transforms_[i] = Transform::of(b.x, b.angle);
        const Transform& xf = transforms_[i];
        std::array<double, 4> box{HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
        const Polygon& shape = shapes_[i];
        for (int k = 0; k < shape.count; ++k) {
            const V2 p = xf.apply(shape.vertices[k]);
            box = {std::min(box[0], p.x()), std::min(box[1], p.y()), std::max(box[2], p.x()),
                   std::max(box[3], p.y())};
        }
        const double grow = shape.radius + margin_[i];
        boxes_[i] = {box[0] - grow, box[1] - grow, box[2] + grow, box[3] + grow};
    }
    // The fat list holds every pair these boxes can make while it is kept (fat_pairs.hpp).
    // Two bodies neither of which a contact can move (walls, pegs, held bodies) make none.
    fat_margin_.resize(n);
    movable_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        fat_margin_[i] = 0.25 * bodies[i].radius + 4 * margin_[i];
        movable_[i] = bodies[i].inv_mass > 0;
    }
    fat_pairs_.update(boxes_, fat_margin_, movable_, fat_list_);
    list_pairs(bodies);
}

void BodySolver::list_pairs(const std::vector<Body>& bodies) {
    // The step's pairs: those of the fat list whose boxes overlap now, in (a, b) order, with
    // an awake body that can move (body_sleep.cpp parks the others).
    const std::size_t n = bodies.size();
    stirring_.resize(n);
    for (std::size_t i = 0; i < n; ++i) stirring_[i] = stirs(bodies[i]);
    pairs_.clear();
    for (const std::uint64_t key : fat_list_) {
        const auto i = static_cast<std::uint32_t>(key >> 32);
        const auto j = static_cast<std::uint32_t>(key & 0xffffffffu);
        if ((stirring_[i] | stirring_[j]) != 0 && boxes_overlap(boxes_[i], boxes_[j]) &&
            !apart(i, j)) {
            pairs_.push_back(key);
        }
    }
}

Manifold BodySolver::manifold_of(PairContact& pc, const PairContact* before,
                                 const std::vector<Body>& bodies) {
    const Body& a = bodies[pc.a];
    const Body& b = bodies[pc.b];
    const Transform& xa = transforms_[pc.a];
    const Transform& xb = transforms_[pc.b];
    const V2 offset = xa.inverse_rotate(xb.p - xa.p);
    const double turn = b.angle - a.angle;
    const bool still = before != nullptr && !fast_[pc.a] && !fast_[pc.b] &&
                       (offset - before->made.offset).norm() <=
                           def_.recycle_travel * std::min(inner_[pc.a], inner_[pc.b]) &&
                       std::abs(turn - before->made.turn) <= def_.recycle_turn;
    Manifold m;
    if (still) {
        // The points stay fixed to the bodies; each one's separation is how far apart its two
        // surface points are along the normal now.
        pc.made = before->made;
        m.normal = xa.rotate(pc.made.normal);
        m.count = pc.made.count;
        for (int k = 0; k < m.count; ++k) {
            const Made::Point& p = pc.made.points[static_cast<std::size_t>(k)];
            const V2 on_a = xa.apply(p.a), on_b = xb.apply(p.b);
            m.points[k] = {0.5 * (on_a + on_b), m.normal.dot(on_b - on_a), p.id};
        }
        return m;
    }
    m = collide(shapes_[pc.a], xa, shapes_[pc.b], xb, margin_[pc.a] + margin_[pc.b]);
    pc.made.normal = xa.inverse_rotate(m.normal);
    pc.made.offset = offset;
    pc.made.turn = turn;
    pc.made.count = m.count;
    for (int k = 0; k < m.count; ++k) {
        const ManifoldPoint& mp = m.points[k];
        const V2 half = 0.5 * mp.separation * m.normal;
        pc.made.points[static_cast<std::size_t>(k)] = {xa.inverse_apply(mp.point - half),
                                                       xb.inverse_apply(mp.point + half), mp.id};
    }
    return m;
}

void BodySolver::apply_totals(const PairContact& pc, double sign) {
    const V2 tangent = -perp(pc.contact.normal);
    for (int k = 0; k < pc.contact.count; ++k) {
        const BlockPoint& p = pc.contact.points[k];
        apply_impulse(state_[pc.a], state_[pc.b], p,
                      sign * (p.normal_impulse * pc.contact.normal + p.tangent_impulse * tangent));
    }
}

void BodySolver::step(std::vector<Body>& bodies, std::span<const Polygon> shapes,
                      const V2& gravity, double dt) {
    shapes_ = shapes;
    fit(bodies.size());
    if (!wake_moved(bodies)) {
        // Every body that can move is asleep and stays so: nothing touches, nothing is swept.
        touches_.clear();
        sensed_.clear();
        impact_touches_.clear();
        struck_impulse_.clear();
        predictions_made_ = 0;
        kept_ = false;
        return;
    }
    begin_step(bodies, gravity, dt);
    // Restitution acts on approaches faster than gravity gives in about two steps: slower
    // ones are a body settling, which would otherwise hop by e g dt every step.
    const double settle = 2 * gravity.norm() * dt;
    const bool kept = keeps_contacts(bodies, dt);
    kept_ = kept;
    if (!kept) {
        const StageTimer timer(profile_, &StepProfile::pairs);
        find_pairs(bodies, dt, 0.5 * gravity.norm() * dt * dt);
        wake_reached(bodies, gravity, dt);
    }
    {
        const StageTimer timer(profile_, &StepProfile::contacts);
        mark_fast(bodies, dt);
        if (kept) {
            move_contacts(bodies, dt);
        } else {
            make_contacts(bodies, dt);
        }
        find_islands(bodies);
    }
    impact_touches_.clear();
    {
        const StageTimer timer(profile_, &StepProfile::impacts);
        strike_touching(bodies, gravity, dt);
    }
    {
        // The islands solved directly first (their bodies have no other contacts), then warm
        // start and the velocity iterations of the rest, body states carried between contacts.
        const StageTimer timer(profile_, &StepProfile::velocities);
        solve_velocities(bodies);
    }
    {
        const StageTimer timer(profile_, &StepProfile::positions);
        integrate_positions(bodies, dt);
    }
    {
        const StageTimer timer(profile_, &StepProfile::velocities);
        bounce(bodies, settle, dt);
    }
    {
        const StageTimer timer(profile_, &StepProfile::positions);
        push_out(bodies);
    }
    {
        const StageTimer timer(profile_, &StepProfile::impacts);
        mark_sunk(bodies);
        time_impacts(bodies, dt, settle);
    }
    if (!joints_.empty() && joints_moved(bodies)) {
        // The impacts moved bodies to where they met, and the push-out's last word is the
        // walls': the joints are corrected again where either moved a body a joint holds.
        const StageTimer timer(profile_, &StepProfile::positions);
        correct_joints(bodies);
    }
    record_touches();
    sense(bodies);
    std::swap(contacts_, fresh_);
    count_motion(bodies, kept);
    fall_asleep(bodies, dt);
}

void BodySolver::begin_step(std::vector<Body>& bodies, const V2& gravity, double dt) {
    start_angle_.resize(bodies.size());
    start_x_.resize(bodies.size());
    start_v_.resize(bodies.size());
    fall_ = gravity * dt;
    dt_ = dt;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        Body& b = bodies[i];
        if (inner_[i] < 0) inner_[i] = inner_radius(shapes_[i]);
        if (b.inv_mass > 0 && !b.asleep) b.v += gravity * dt;
        start_x_[i] = b.x;
        start_angle_[i] = b.angle;
        start_v_[i] = b.v;
    }
}

void BodySolver::mark_fast(const std::vector<Body>& bodies, double dt) {
    // A body that will travel more than impact_travel of its inner radius is fast: its pairs
    // that start the step apart are left to the impacts (body_impacts.cpp), timed exactly,
    // rather than to a speculative contact made from where the step starts.
    fast_.assign(bodies.size(), 0);
    for (std::size_t i = 0; i < bodies.size(); ++i) fast_[i] = moves_fast(bodies, i, dt);
}

bool BodySolver::moves_fast(const std::vector<Body>& bodies, std::size_t i, double dt) const {
    const Body& b = bodies[i];
    const double travel = (b.v.norm() + std::abs(b.omega) * b.radius) * dt;
    return b.inv_mass > 0 && travel > def_.impact_travel * inner_[i];
}

void BodySolver::make_contacts(const std::vector<Body>& bodies, double dt) {
    // fresh_'s elements are reused in place, each field written below before it is read:
    // made afresh, a contact is some hundreds of bytes of zeros written for nothing.
    std::size_t made = 0;
    auto previous = contacts_.begin();
    for (const std::uint64_t key : pairs_) {
        const auto i = static_cast<std::uint32_t>(key >> 32);
        const auto j = static_cast<std::uint32_t>(key & 0xffffffffu);
        const Body& a = bodies[i];
        const Body& b = bodies[j];
        // Taken back if the pair makes none.
        PairContact& pc = made < fresh_.size() ? fresh_[made] : fresh_.emplace_back();
        ++made;
        pc.a = i;
        pc.b = j;
        pc.as_solved = false;
        // The same pair last step (both lists in pair order): its manifold and its impulses.
        while (previous != contacts_.end() &&
               (previous->a < i || (previous->a == i && previous->b < j))) {
            ++previous;
        }
        const bool had = previous != contacts_.end() && previous->a == i && previous->b == j;
        const Manifold m = manifold_of(pc, had ? &*previous : nullptr, bodies);
        if (m.count == 0) {
            --made;
            continue;
        }
        // A fast body's pair that starts apart, against a wall or a body of alike mass, is met
        // at its time of impact instead (body_impacts.cpp): exactly when it happens, bounced
        // by Poisson's rule, where a speculative contact would bounce it at the step's end by
        // Newton's rule at both points, which adds energy to a spinning body. Masses far apart
        // stay speculative: their islands are solved together (island.hpp), which impacts one
        // pair at a time are not.
        const double lighter = std::max(a.inv_mass, b.inv_mass);
        const double heavier = std::min(a.inv_mass, b.inv_mass);
        const bool wall = heavier == 0;
        if ((fast_[i] || fast_[j]) && (wall || lighter < def_.direct_mass_ratio * heavier)) {
            double apart = HUGE_VAL;
            for (int k = 0; k < m.count; ++k) apart = std::min(apart, m.points[k].separation);
            if (apart > def_.slop) {
                --made;
                continue;
            }
        }
        BlockContact& c = pc.contact;
        c = BlockContact{};
        c.normal = m.normal;
        c.count = m.count;
        c.friction = def_.mixing.friction_of(a.friction, b.friction);
        pc.restitution = def_.mixing.restitution_of(a.restitution, b.restitution);
        // Warm start: the impulses of the same features last step.
        pc.touched = had && previous->touched;   // until this step's impulses say otherwise
        const BlockBody va = velocity_of(a), vb = velocity_of(b);
        for (int k = 0; k < c.count; ++k) {
            const ManifoldPoint& mp = m.points[k];
            BlockPoint& p = c.points[k];
            p.ra = mp.point - a.x;
            p.rb = mp.point - b.x;
            pc.anchors[k] = {p.ra, p.rb, mp.separation};
            // Apart: approach at most far enough to touch within the step; touching: stop
            // closing. The bounce comes after the positions move (below), so that a body
            // leaves from the surface at e times the speed it arrived with.
            p.target = mp.separation > 0 ? -mp.separation / dt : 0;
            pc.approach[static_cast<std::size_t>(k)] = normal_velocity(c, p, va, vb);
            if (!had) continue;
            for (int q = 0; q < previous->contact.count; ++q) {
                if (previous->made.points[static_cast<std::size_t>(q)].id != mp.id) continue;
                p.normal_impulse = previous->contact.points[q].normal_impulse;
                p.tangent_impulse = previous->contact.points[q].tangent_impulse;
            }
        }
    }
    fresh_.resize(made);
}

void BodySolver::record_touches() {
    touches_.clear();
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        PairContact& pc = fresh_[i];
        // The rows' impulse and the strikes' (a pair only struck touched too).
        double impulse = i < struck_impulse_.size() ? struck_impulse_[i] : 0;
        for (int k = 0; k < pc.contact.count; ++k) impulse += pc.contact.points[k].normal_impulse;
        const bool touching = impulse > 0;
        if (touching) {
            PairTouch t;
            t.a = pc.a;
            t.b = pc.b;
            t.impulse = impulse;
            t.began = !pc.touched;
            touches_.push_back(t);
        }
        pc.touched = touching;
    }
    // A pair that met at a time of impact touched too: with its contact's impulse if it has
    // one, as a new touch if not.
    if (!impact_touches_.empty()) {
        const auto by_pair = [](const PairTouch& x, const PairTouch& y) {
            return x.a != y.a ? x.a < y.a : x.b < y.b;
        };
        const std::size_t listed = touches_.size();
        for (const PairTouch& t : impact_touches_) {
            const auto end = touches_.begin() + static_cast<std::ptrdiff_t>(listed);
            const auto at = std::lower_bound(touches_.begin(), end, t, by_pair);
            if (at != end && at->a == t.a && at->b == t.b) {
                at->impulse += t.impulse;
            } else {
                touches_.push_back(t);
            }
        }
        std::sort(touches_.begin(), touches_.end(), by_pair);
    }
}

void BodySolver::sense(const std::vector<Body>& bodies) {
    sensed_.clear();
    if (!filter_.any_sensor()) return;
    // The broad phase's pairs hold every pair whose boxes can overlap in the step: a sensor's
    // that overlap now are measured at the step's end.
    sensing_now_.clear();
    const auto watch = [&](std::uint64_t key) {
        const auto i = static_cast<std::uint32_t>(key >> 32);
        const auto j = static_cast<std::uint32_t>(key & 0xffffffffu);
        if (!filter_.senses(i, j) || !boxes_overlap(boxes_[i], boxes_[j])) return;
        const Body& a = bodies[i];
        const Body& b = bodies[j];
        const Manifold m = collide(shapes_[i], Transform::of(a.x, a.angle), shapes_[j],
                                   Transform::of(b.x, b.angle), 0);
        bool overlapping = false;
        for (int k = 0; k < m.count; ++k) overlapping = overlapping || m.points[k].separation < 0;
        if (overlapping) sensing_now_.push_back(key);
    };
    for (const std::uint64_t key : fat_list_) watch(key);
    watch_unpushable(bodies, watch);
    std::sort(sensing_now_.begin(), sensing_now_.end());
    sensing_now_.erase(std::unique(sensing_now_.begin(), sensing_now_.end()),
                       sensing_now_.end());
    // Began: now, not before; ended: before, not now (both lists ascending).
    const auto event = [&](std::uint64_t key, PairTouch::Kind kind) {
        PairTouch t;
        t.a = static_cast<std::uint32_t>(key >> 32);
        t.b = static_cast<std::uint32_t>(key & 0xffffffffu);
        t.began = true;
        t.kind = kind;
        sensed_.push_back(t);
    };
    std::size_t p = 0, q = 0;
    while (p < sensing_.size() || q < sensing_now_.size()) {
        if (q == sensing_now_.size() || (p < sensing_.size() && sensing_[p] < sensing_now_[q])) {
            event(sensing_[p++], PairTouch::Kind::end);
        } else if (p == sensing_.size() || sensing_now_[q] < sensing_[p]) {
            event(sensing_now_[q++], PairTouch::Kind::begin);
        } else {
            ++p;
            ++q;
        }
    }
    std::swap(sensing_, sensing_now_);
}

template <class Watch>
void BodySolver::watch_unpushable(const std::vector<Body>& bodies, Watch&& watch) {
    // The fat list pairs only bodies a contact can move. A sensor no contact moves (a static
    // gate, a kinematic one) and another such body of which one of the two moves as told (a
    // kinematic platform through a static gate) are paired here, each such sensor with each
    // such body: sensors are counted in ones.
    unpushed_sensors_.clear();
    unpushed_.clear();
    for (std::uint32_t i = 0; i < bodies.size(); ++i) {
        if (bodies[i].inv_mass > 0) continue;
        unpushed_.push_back(i);
        if (filter_.sensor(i)) unpushed_sensors_.push_back(i);
    }
    for (const std::uint32_t s : unpushed_sensors_) {
        for (const std::uint32_t o : unpushed_) {
            if (o == s || (bodies[s].motion != Motion::held && bodies[o].motion != Motion::held)) {
                continue;
            }
            watch(std::uint64_t{std::min(s, o)} << 32 | std::max(s, o));
        }
    }
}

BodySolver::Overlap BodySolver::max_overlap(const std::vector<Body>& bodies,
                                            std::span<const Polygon> shapes) const {
    // Every pair of the broad phase's whose boxes overlap (a fast pair left to its impacts has
    // no contact, an asleep one none solved).
    Overlap deepest;
    for (const std::uint64_t key : fat_list_) {
        const auto i = static_cast<std::uint32_t>(key >> 32);
        const auto j = static_cast<std::uint32_t>(key & 0xffffffffu);
        const Body& a = bodies[i];
        const Body& b = bodies[j];
        if (!boxes_overlap(boxes_[i], boxes_[j]) || apart(i, j)) continue;
        const Manifold m = collide(shapes[i], Transform::of(a.x, a.angle), shapes[j],
                                   Transform::of(b.x, b.angle), 0);
        for (int k = 0; k < m.count; ++k) {
            if (-m.points[k].separation <= deepest.depth) continue;
            deepest.depth = -m.points[k].separation;
            deepest.a = i;
            deepest.b = j;
        }
    }
    return deepest;
}

}  // namespace discreel::physics::detail
