// Lists of timed points — a grab's waypoints [t, x, y], a kinematic path's poses
// [t, x, y, angle] — read by one reader, so that both say the same of the same mistakes.
#include <string>

#include "loader.hpp"

namespace discreel::scene::detail {

std::optional<std::vector<TimedPoint>> read_timed_points(const Value& value,
                                                         const TimedPointsForm& form,
                                                         Diagnostics& d) {
    const auto items = read_list(value, d);
    if (!items) return std::nullopt;
    const std::string noun(form.noun), nouns = noun + "s";
    if (items->size() < form.least) {
        d.error(value.where, value.path + ": " + std::string(form.owner) + " needs at least " +
                                 std::to_string(form.least) + " " +
                                 (form.least == 1 ? noun : nouns) + " " +
                                 std::string(form.shape) + ", got " +
                                 std::to_string(items->size()));
        return std::nullopt;
    }
    if (items->size() > max_waypoints) {
        d.error(value.where, value.path + ": too many " + nouns + " (" +
                                 std::to_string(items->size()) + "); the limit is " +
                                 std::to_string(max_waypoints));
        return std::nullopt;
    }
    std::vector<TimedPoint> points;
    bool ok = true;
    for (const Value& item : *items) {
        const auto numbers = read_tuple(item, form.width, form.shape, d);
        if (!numbers) {
            ok = false;
            continue;
        }
        TimedPoint point{item, {}};
        bool read = true;
        for (std::size_t k = 0; k < form.width; ++k) {
            const auto v = read_number((*numbers)[k], d);
            read = read && v;
            point.numbers[k] = v.value_or(0);
        }
        if (!read) {
            ok = false;
            continue;
        }
        // Each time against the last point that read fine.
        const double t = point.numbers[0];
        if (t < 0 || (!points.empty() && t <= points.back().numbers[0])) {
            d.error((*numbers)[0].where,
                    item.path + ": " + noun + " times must be at least 0 and increase strictly, but " +
                        format_number(t) +
                        (points.empty() ? std::string(" is below 0")
                                        : " comes after " + format_number(points.back().numbers[0])));
            ok = false;
            continue;
        }
        points.push_back(std::move(point));
    }
    if (!ok) return std::nullopt;
    return points;
}

}  // namespace discreel::scene::detail
