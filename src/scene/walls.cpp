// `walls:` — boxes and segments.
#include <algorithm>
#include <array>
#include <string_view>

#include "entries.hpp"
#include "loader.hpp"

namespace discreel::scene::detail {

void read_walls(Loader& loader, const Value& value) {
    static constexpr std::array<std::string_view, 8> known{
        "box", "segment", "thickness", "restitution", "friction", "color", "category", "collides"};
    auto& d = loader.diagnostics;
    const auto items = read_list(value, d);
    if (!items) return;
    if (items->size() > max_walls) {
        d.error(value.where, value.path + ": too many walls (" + std::to_string(items->size()) +
                                 "); the limit is " + std::to_string(max_walls));
        return;
    }
    for (const Value& item : *items) {
        const auto fields = Fields::open(item, known, d);
        if (!fields) continue;
        Wall wall;
        wall.restitution = loader.scene.physics.restitution;
        wall.friction = loader.scene.physics.friction;
        read_filter(loader, *fields, wall.category, wall.collides);
        const bool has_box = fields->has("box"), has_segment = fields->has("segment");
        if (has_box && has_segment) {
            d.error(fields->key_location(fields->later_of("box", "segment")),
                    item.path + ": a wall is either a 'box' or a 'segment', not both");
        } else if (!has_box && !has_segment) {
            d.error(item.where, item.path + ": a wall needs either 'box: [[x0, y0], [x1, y1]]' or "
                                            "'segment: [[x0, y0], [x1, y1]]'");
        } else if (has_box) {
            const Value box = *fields->get("box");
            wall.shape = Wall::Shape::box;
            if (const auto c = read_corners(box, "[[x0, y0], [x1, y1]]", d)) {
                // Corners may come in any order; the box is their bounding rectangle.
                wall.a = {std::min(c->a.x, c->b.x), std::min(c->a.y, c->b.y)};
                wall.b = {std::max(c->a.x, c->b.x), std::max(c->a.y, c->b.y)};
                if (wall.a.x == wall.b.x || wall.a.y == wall.b.y)
                    d.error(box.where, box.path + ": the box has no area; its two corners must "
                                                  "differ in both x and y");
            }
        } else {
            const Value segment = *fields->get("segment");
            wall.shape = Wall::Shape::segment;
            if (const auto c = read_corners(segment, "[[x0, y0], [x1, y1]]", d)) {
                wall.a = c->a;
                wall.b = c->b;
                if (wall.a == wall.b)
                    d.error(segment.where,
                            segment.path + ": both ends are the same point; a segment needs "
                                           "two different ends");
            }
        }
        if (const auto thickness = fields->get("thickness"))
            if (const auto v = read_positive(*thickness, d)) wall.thickness = *v;
        if (const auto restitution = fields->get("restitution"))
            if (const auto v = read_between(*restitution, 0, 1, d)) wall.restitution = *v;
        if (const auto friction = fields->get("friction"))
            if (const auto v = read_non_negative(*friction, d)) wall.friction = *v;
        if (const auto color = fields->get("color"))
            if (const auto c = read_color(*color, d)) wall.color = *c;
        loader.scene.walls.push_back(wall);
    }
}

}  // namespace discreel::scene::detail
