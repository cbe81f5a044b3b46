// A scene whose masses or speeds fall outside the range in which the physics is measured to keep
// a crowd of bodies apart (physics::envelope) is rendered all the same, with a warning at the
// value to change: small groups of bodies hold beyond it, and which a scene makes is not known
// before it runs.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "discreel/physics.hpp"
#include "loader.hpp"

namespace discreel::scene::detail {
namespace {

struct Extremes {
    std::size_t lightest = 0, heaviest = 0, smallest = 0;   // disc indices
};

std::optional<Extremes> dynamic_extremes(const std::vector<Body>& discs) {
    std::optional<Extremes> e;
    for (std::size_t i = 0; i < discs.size(); ++i) {
        if (discs[i].is_static) continue;
        if (!e) {
            e = Extremes{i, i, i};
            continue;
        }
        if (discs[i].mass < discs[e->lightest].mass) e->lightest = i;
        if (discs[i].mass > discs[e->heaviest].mass) e->heaviest = i;
        if (discs[i].radius < discs[e->smallest].radius) e->smallest = i;
    }
    return e;
}

double speed_of(Vec2 v) { return std::hypot(v.x, v.y); }

// What a mass ratio beyond the crowd's does, and where to read more (small groups hold: both
// solvers solve them directly).
std::string crowd_sinks_in(double ratio) {
    return "where many bodies " + format_short(ratio) + " times apart in mass touch at once, "
           "heavy ones may sink into light ones and the crowd may gain energy "
           "(docs/physics.md, Limits)";
}

// "`speed` m/s: crowds ... stay apart up to `limit`": what the limit is in radii per step, and
// the rate that would hold the speed. `smallest_id` names the smallest moving body when known.
std::string too_fast(double speed, double limit, double rate, double radii_per_step,
                     double smallest, const std::string& smallest_id, double ratio) {
    const double needed = std::ceil(speed / (radii_per_step * smallest));
    return format_short(speed) + " m/s: crowds of this scene's bodies are measured to stay " +
           "apart up to " + format_short(limit) + " m/s at " + format_number(rate) + " Hz (" +
           format_short(radii_per_step) + " radii of the smallest moving body, " +
           (smallest_id.empty() ? "" : "'" + smallest_id + "', ") + format_number(smallest) +
           " m, per physics step" +
           (ratio > 1 ? " for masses differing by a factor of " + format_short(ratio)
                      : std::string()) +
           "); where several bodies this fast meet at once they may overlap" +
           (needed <= 100000 ? "; physics.rate " + format_number(needed) +
                                   " or more keeps them apart"
                             : std::string()) +
           " (docs/physics.md, Limits)";
}

// The moving bodies alive at one time: their masses, radii and speeds (with their slots, the
// index in Scene::discs whose entry a message points at), kept as respawns replace bodies.
class Alive {
public:
    void add(const Body& body, std::size_t slot) {
        if (body.is_static) return;
        masses_.insert(body.mass);
        radii_.insert(body.radius);
        speeds_.emplace(speed_of(body.velocity), slot);
    }
    void remove(const Body& body, std::size_t slot) {
        if (body.is_static) return;
        masses_.erase(masses_.find(body.mass));
        radii_.erase(radii_.find(body.radius));
        auto [from, to] = speeds_.equal_range(speed_of(body.velocity));
        while (from->second != slot) ++from;
        speeds_.erase(from);
    }
    bool empty() const { return masses_.empty(); }
    std::size_t size() const { return masses_.size(); }
    double mass_ratio() const { return *masses_.rbegin() / *masses_.begin(); }
    double smallest_radius() const { return *radii_.begin(); }
    std::pair<double, std::size_t> fastest() const { return *speeds_.rbegin(); }

private:
    std::multiset<double> masses_, radii_;
    std::multimap<double, std::size_t> speeds_;
};

// Each respawned set is judged with the bodies alive beside it, not with the sets it replaces
// or that replace it: a body is never in contact with its own successor. The first time the
// moving bodies leave the envelope is reported, at the entry of the generator that respawned.
void check_respawns(Loader& loader, bool manifold) {
    const Scene& scene = loader.scene;
    if (scene.respawns.empty()) return;
    std::vector<const Body*> current;
    Alive alive;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        current.push_back(&scene.bodies[i]);
        alive.add(scene.bodies[i], i);
    }
    for (std::size_t n = 0; n < scene.respawns.size(); ++n) {
        const Respawn& r = scene.respawns[n];
        for (std::size_t k = 0; k < r.bodies.size(); ++k) {
            alive.remove(*current[r.first + k], r.first + k);
            current[r.first + k] = &r.bodies[k];
            alive.add(r.bodies[k], r.first + k);
        }
        // Respawns at one time are judged together.
        if (n + 1 < scene.respawns.size() && scene.respawns[n + 1].at == r.at) continue;
        if (alive.empty()) continue;
        const BodySource& source = loader.sources[r.first];
        const std::string when = "the respawn at t = " + format_number(r.at) + " s";
        const double ratio = alive.mass_ratio();
        if (ratio > physics::envelope.crowd_mass_ratio) {
            loader.diagnostics.warn(
                source.entry, source.where + ": after " + when +
                                  ", the moving bodies differ in mass by a factor of " +
                                  format_short(ratio) + "; " + crowd_sinks_in(ratio));
            return;
        }
        const double radii_per_step = physics::envelope.radii_per_step(
            ratio, manifold);
        const double limit = radii_per_step * alive.smallest_radius() * scene.physics.rate;
        const auto [speed, slot] = alive.fastest();
        if (speed > limit && alive.size() >= physics::envelope.crowd_bodies) {
            const BodySource& fast = loader.sources[slot];
            loader.diagnostics.warn(
                fast.velocity_where,
                fast.velocity_path + ": after " + when + ", " +
                    too_fast(speed, limit, scene.physics.rate, radii_per_step,
                             alive.smallest_radius(), "", ratio));
            return;
        }
    }
}

}  // namespace

void check_envelope(Loader& loader) {
    auto& d = loader.diagnostics;
    const Scene& scene = loader.scene;
    const auto extremes = dynamic_extremes(scene.bodies);
    if (!extremes) return;
    // Too few moving bodies to make a crowd: their speeds are not judged (three bullets fired at
    // a wall). A respawned set is judged with those alive beside it.
    const auto moving = static_cast<std::size_t>(std::count_if(
        scene.bodies.begin(), scene.bodies.end(),
        [](const Body& b) { return !b.is_static && !b.kinematic; }));

    const Body& light = scene.bodies[extremes->lightest];
    const Body& heavy = scene.bodies[extremes->heaviest];
    const double ratio = heavy.mass / light.mass;
    const auto shaped = [](const Body& body) { return body.shape.has_value(); };
    const bool manifold = physics::uses_manifold_solver(
        std::any_of(scene.bodies.begin(), scene.bodies.end(), shaped) ||
        std::any_of(scene.respawns.begin(), scene.respawns.end(), [&](const Respawn& r) {
            return std::any_of(r.bodies.begin(), r.bodies.end(), shaped);
        }),
        !scene.joints.empty() ||
            std::any_of(scene.bodies.begin(), scene.bodies.end(),
                        [](const Body& b) {
                            return b.sensor || physics::filters(b.category, b.collides, false);
                        }) ||
            std::any_of(scene.walls.begin(), scene.walls.end(), [](const Wall& w) {
                return physics::filters(w.category, w.collides, true);
            }));
    if (ratio > physics::envelope.crowd_mass_ratio) {
        // A crowd this far apart in mass sinks in at any speed: the speeds are not judged.
        const BodySource& source = loader.sources[extremes->heaviest];
        // A body of `bodies:` (a shape) is a body to its author, not a disc.
        const auto noun = [](const Body& body) { return body.shape ? "body" : "disc"; };
        d.warn(source.entry,
               source.where + ": " + noun(heavy) + " '" + heavy.id + "' (" +
                   format_short(heavy.mass) + " kg) is " + format_short(ratio) +
                   " times as heavy as " + noun(light) + " '" + light.id + "' (" +
                   format_short(light.mass) + " kg, line " +
                   std::to_string(loader.sources[extremes->lightest].entry.line) + "); " +
                   crowd_sinks_in(ratio));
        return;
    }

    if (moving < physics::envelope.crowd_bodies) {
        check_respawns(loader, manifold);
        return;
    }
    const Body& smallest = scene.bodies[extremes->smallest];
    const double radii_per_step = physics::envelope.radii_per_step(ratio, manifold);
    const double rate = scene.physics.rate;
    const double limit = radii_per_step * smallest.radius * rate;   // m/s
    const auto check = [&](double speed, const Location& where, const std::string& path) {
        if (speed <= limit) return;
        d.warn(where, path + ": " + too_fast(speed, limit, rate, radii_per_step, smallest.radius,
                                             smallest.id, ratio));
    };
    // The discs of a generator share where their speed was written (a run of equal locations):
    // the fastest moving one speaks for all, once.
    for (std::size_t first = 0; first < scene.bodies.size();) {
        const BodySource& source = loader.sources[first];
        std::optional<double> fastest;
        std::size_t end = first;
        for (; end < scene.bodies.size() &&
               loader.sources[end].velocity_where == source.velocity_where;
             ++end) {
            if (scene.bodies[end].is_static) continue;
            fastest = std::max(fastest.value_or(0.0), speed_of(scene.bodies[end].velocity));
        }
        if (fastest) check(*fastest, source.velocity_where, source.velocity_path);
        first = end;
    }
    for (std::size_t k = 0; k < scene.throws.size(); ++k) {
        const Throw& t = scene.throws[k];
        const ThrowSource& source = loader.throw_sources[k];
        if (t.velocity) check(speed_of(*t.velocity), source.velocity_where, source.velocity_path);
        if (t.release) check(speed_of(*t.release), source.velocity_where, source.velocity_path);
        double fastest = 0;   // the grab's speed along its path, from the disc's start on
        if (!t.path.empty() && t.path.front().t > 0) {
            const Vec2 from = scene.bodies[t.body].position, to = t.path.front().position;
            fastest = speed_of({to.x - from.x, to.y - from.y}) / t.path.front().t;
        }
        for (std::size_t p = 1; p < t.path.size(); ++p) {
            const Vec2 from = t.path[p - 1].position, to = t.path[p].position;
            fastest = std::max(fastest, speed_of({to.x - from.x, to.y - from.y}) /
                                            (t.path[p].t - t.path[p - 1].t));
        }
        check(fastest, source.path_where, source.path_path);
    }
    check_respawns(loader, manifold);
}

}  // namespace discreel::scene::detail
