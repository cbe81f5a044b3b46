// `joints:` — pins, rods, ropes, springs, sliders and welds between bodies (or a body and the
// world), each a mapping with one key that names its kind.
#include <array>
#include <set>
#include <string>
#include <string_view>

#include "disc_ref.hpp"
#include "entries.hpp"
#include "loader.hpp"

namespace discreel::scene::detail {
namespace {

using Kind = physics::JointDef::Kind;

constexpr std::array<std::string_view, 4> kinds{"revolute", "distance", "prismatic", "weld"};
constexpr std::array<std::string_view, 7> revolute_keys{"a",      "b",     "anchor", "limits",
                                                        "motor",  "collide", "id"};
constexpr std::array<std::string_view, 9> distance_keys{
    "a", "b", "anchor_a", "anchor_b", "length", "rope", "spring", "collide", "id"};
constexpr std::array<std::string_view, 8> prismatic_keys{"a",     "b",     "anchor",  "axis",
                                                         "limits", "motor", "collide", "id"};
constexpr std::array<std::string_view, 6> weld_keys{"a", "b", "anchor", "spring", "collide", "id"};
constexpr std::array<std::string_view, 2> spring_keys{"frequency", "damping"};
constexpr std::array<std::string_view, 2> torque_motor_keys{"speed", "max_torque"};
constexpr std::array<std::string_view, 2> force_motor_keys{"speed", "max_force"};

std::span<const std::string_view> keys_of(Kind kind) {
    switch (kind) {
    case Kind::revolute: return revolute_keys;
    case Kind::distance: return distance_keys;
    case Kind::prismatic: return prismatic_keys;
    case Kind::weld: return weld_keys;
    }
    return revolute_keys;
}

// One joint's fields, read into `j`; false when any is wrong (each reported).
class JointReader {
public:
    JointReader(Loader& loader, const Fields& fields, const DiscIds& ids, Kind kind,
                physics::JointDef& j)
        : loader_(loader), d_(loader.diagnostics), fields_(fields), ids_(ids), kind_(kind), j_(j) {}

    bool read() {
        read_ends();
        if (kind_ == Kind::distance) {
            j_.anchor_a = required_point("anchor_a");
            j_.anchor_b = required_point("anchor_b");
            read_length();
            if (const auto v = fields_.get("rope")) j_.rope = flag(*v);
        } else {
            j_.anchor_a = j_.anchor_b = required_point("anchor");
        }
        if (const auto v = fields_.get("axis")) read_axis(*v);
        if (kind_ == Kind::prismatic && !fields_.has("axis")) missing("axis");
        if (const auto v = fields_.get("limits")) read_limits(*v);
        if (const auto v = fields_.get("motor")) read_motor(*v);
        if (const auto v = fields_.get("spring")) read_spring(*v);
        if (const auto v = fields_.get("collide")) j_.collide = flag(*v);
        if (const auto v = fields_.get("id")) ok_ = read_id(*v, d_).has_value() && ok_;
        return ok_;
    }

private:
    void missing(std::string_view key) {
        d_.error(fields_.where(), fields_.path() + ": missing required key '" + std::string(key) +
                                      "'");
        ok_ = false;
    }

    void read_ends() {
        std::optional<std::size_t>* ends[] = {&j_.a, &j_.b};
        std::array<std::optional<Value>, 2> values{fields_.get("a"), fields_.get("b")};
        for (int k = 0; k < 2; ++k) {
            if (!values[k]) continue;
            const auto index = resolve_disc(loader_, *values[k], ids_);
            ok_ = ok_ && index;
            *ends[k] = index;
            if (index && respawned(*index)) {
                d_.error(values[k]->where,
                         values[k]->path + ": body '" + loader_.scene.bodies[*index].id +
                             "' is replaced by its generator's respawns; a joint cannot hold it");
                ok_ = false;
            }
        }
        if (!values[0] && !values[1]) {
            d_.error(fields_.where(), fields_.path() +
                                          ": a joint needs a body: give 'b' (and 'a', or leave "
                                          "it out to join 'b' to the world)");
            ok_ = false;
        } else if (j_.a && j_.b && *j_.a == *j_.b) {
            d_.error(values[1]->where, values[1]->path + ": joins body '" +
                                           loader_.scene.bodies[*j_.b].id +
                                           "' to itself; 'a' and 'b' must be different bodies");
            ok_ = false;
        }
    }

    bool respawned(std::size_t body) const {
        for (const Respawn& r : loader_.scene.respawns) {
            if (body >= r.first && body < r.first + r.bodies.size()) return true;
        }
        return false;
    }

    Vec2 required_point(std::string_view key) {
        const auto v = fields_.get(key);
        if (!v) {
            missing(key);
            return {};
        }
        const auto p = read_vec2(*v, "[x, y]", d_);
        ok_ = ok_ && p;
        return p.value_or(Vec2{});
    }

    bool flag(const Value& v) {
        const auto b = read_bool(v, d_);
        ok_ = ok_ && b;
        return b.value_or(false);
    }

    void read_length() {
        if (const auto v = fields_.get("length")) {
            const auto length = read_positive(*v, d_);
            ok_ = ok_ && length;
            j_.length = length.value_or(-1.0);
        } else if (ok_ && j_.anchor_a.x == j_.anchor_b.x && j_.anchor_a.y == j_.anchor_b.y) {
            // A length of 0 has no direction to hold along.
            const auto at = fields_.get("anchor_b");
            d_.error(at->where, at->path + ": the anchors are the same point, so the length "
                                          "would be 0; give 'length', or use a revolute joint "
                                          "to pin them together");
            ok_ = false;
        }
    }

    void read_axis(const Value& v) {
        if (kind_ != Kind::prismatic) {
            d_.error(fields_.key_location("axis"),
                     v.path + ": only a prismatic joint has an axis");
            ok_ = false;
            return;
        }
        const auto axis = read_vec2(v, "[x, y]", d_);
        if (axis && axis->x == 0 && axis->y == 0) {
            d_.error(v.where, v.path + ": the axis must not be [0, 0]; give its direction");
            ok_ = false;
            return;
        }
        ok_ = ok_ && axis;
        if (axis) j_.axis = *axis;
    }

    void read_limits(const Value& v) {
        const auto items = read_tuple(v, 2, "[lower, upper]", d_);
        if (!items) {
            ok_ = false;
            return;
        }
        const auto lower = read_number((*items)[0], d_);
        const auto upper = read_number((*items)[1], d_);
        if (!lower || !upper) {
            ok_ = false;
            return;
        }
        if (*lower > *upper) {
            d_.error(v.where, v.path + ": limits are [lower, upper], but " +
                                  format_number(*lower) + " is above " + format_number(*upper));
            ok_ = false;
            return;
        }
        j_.limits = std::array<double, 2>{*lower, *upper};
    }

    void read_motor(const Value& v) {
        const bool turning = kind_ == Kind::revolute;
        const std::span<const std::string_view> keys =
            turning ? std::span<const std::string_view>(torque_motor_keys)
                    : std::span<const std::string_view>(force_motor_keys);
        const auto motor = Fields::open(v, keys, d_);
        if (!motor) {
            ok_ = false;
            return;
        }
        physics::JointDef::Motor m;
        const std::string_view limit_key = turning ? "max_torque" : "max_force";
        if (const auto s = motor->get("speed")) {
            const auto speed = read_number(*s, d_);
            ok_ = ok_ && speed;
            m.speed = speed.value_or(0);
        } else {
            d_.error(v.where, v.path + ": missing required key 'speed'");
            ok_ = false;
        }
        if (const auto f = motor->get(limit_key)) {
            const auto force = read_non_negative(*f, d_);
            ok_ = ok_ && force;
            m.max_force = force.value_or(0);
        } else {
            d_.error(v.where, v.path + ": missing required key '" + std::string(limit_key) + "'");
            ok_ = false;
        }
        j_.motor = m;
    }

    void read_spring(const Value& v) {
        const auto spring = Fields::open(v, spring_keys, d_);
        if (!spring) {
            ok_ = false;
            return;
        }
        physics::SpringDef s;
        if (const auto f = spring->get("frequency")) {
            const auto frequency = read_positive(*f, d_);
            ok_ = ok_ && frequency;
            s.frequency = frequency.value_or(1);
        } else {
            d_.error(v.where, v.path + ": missing required key 'frequency'");
            ok_ = false;
        }
        if (const auto z = spring->get("damping")) {
            const auto damping = read_non_negative(*z, d_);
            ok_ = ok_ && damping;
            s.damping = damping.value_or(0);
        }
        j_.spring = s;
    }

    Loader& loader_;
    Diagnostics& d_;
    const Fields& fields_;
    const DiscIds& ids_;
    Kind kind_;
    physics::JointDef& j_;
    bool ok_ = true;
};

}  // namespace

void read_joints(Loader& loader, const Value& value) {
    auto& d = loader.diagnostics;
    const auto items = read_list(value, d);
    if (!items) return;
    if (items->size() > max_joints) {
        d.error(value.where, value.path + ": too many joints (" + std::to_string(items->size()) +
                                 "); the limit is " + std::to_string(max_joints));
        return;
    }
    const DiscIds ids(loader.scene.bodies);
    std::set<std::string> named;   // the joints' ids so far
    for (const Value& item : *items) {
        if (d.full()) break;
        const std::size_t problems = d.count();
        const auto outer = Fields::open(item, kinds, d);
        if (!outer) continue;
        std::optional<Value> body;
        Kind kind = Kind::revolute;
        bool several = false;
        for (std::size_t k = 0; k < kinds.size() && !several; ++k) {
            const auto v = outer->get(kinds[k]);
            if (!v) continue;
            if (body) {
                d.error(outer->key_location(kinds[k]),
                        item.path + ": one joint per entry; start another entry with '- " +
                            std::string(kinds[k]) + ":'");
                several = true;
            }
            body = v;
            kind = static_cast<Kind>(k);
        }
        if (several) continue;
        if (!body) {
            // An unknown key is reported already, with its suggestion.
            if (d.count() == problems) {
                d.error(item.where, item.path + ": a joint is one of revolute:, distance:, "
                                                "prismatic: or weld:");
            }
            continue;
        }
        const auto fields = Fields::open(*body, keys_of(kind), d);
        if (!fields) continue;
        physics::JointDef j;
        j.kind = kind;
        if (!JointReader(loader, *fields, ids, kind, j).read()) continue;
        std::string id = std::to_string(loader.scene.joints.size());
        if (const auto v = fields->get("id")) {
            id = v->node.Scalar();
            if (!named.insert(id).second) {
                d.error(v->where, v->path + ": id '" + id + "' is already used by another joint");
                continue;
            }
        }
        loader.scene.joint_ids.push_back(std::move(id));
        loader.scene.joints.push_back(j);
    }
}

}  // namespace discreel::scene::detail
