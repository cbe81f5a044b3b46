// Naming a disc from elsewhere in the file (throws, camera.follow): by index or by id.
#include "disc_ref.hpp"

#include <algorithm>

#include "discreel/did_you_mean.hpp"

namespace discreel::scene::detail {

DiscIds::DiscIds(const std::vector<Body>& discs) {
    names.reserve(discs.size());
    for (std::size_t i = 0; i < discs.size(); ++i) {
        by_id.emplace(discs[i].id, i);
        names.push_back(discs[i].id);
    }
}

std::optional<std::size_t> resolve_disc(Loader& loader, const Value& value, const DiscIds& ids) {
    auto& d = loader.diagnostics;
    const std::size_t count = loader.scene.bodies.size();
    // A scene of discs only speaks of discs; one with shapes, of bodies (a disc is one too).
    const bool shaped = std::any_of(loader.scene.bodies.begin(), loader.scene.bodies.end(),
                                    [](const Body& b) { return b.shape.has_value(); });
    const std::string one = shaped ? "body" : "disc", many = shaped ? "bodies" : "discs";
    if (!value.node.IsScalar()) {
        d.error(value.where, value.path + ": expected a " + one + " id or index, got " +
                                 describe(value.node));
        return std::nullopt;
    }
    const std::string& text = value.node.Scalar();
    const bool plain = value.node.Tag() != "!";
    const bool looks_whole = !text.empty() && text.find_first_not_of("0123456789", text[0] == '-' ? 1 : 0) == std::string::npos &&
                             text != "-";
    if (plain && looks_whole) {
        Diagnostics quiet;
        const auto index = read_integer(value, quiet);
        if (index && *index >= 0 && static_cast<unsigned long long>(*index) < count)
            return static_cast<std::size_t>(*index);
        if (!loader.discs_complete) return std::nullopt;  // the real cause is reported already
        const std::string numbered =
            count == 0   ? "the scene has no " + many
            : count == 1 ? "the scene has 1 " + one + ", numbered 0"
                         : "the scene has " + std::to_string(count) + " " + many +
                               ", numbered 0 to " + std::to_string(count - 1);
        d.error(value.where, value.path + ": there is no " + one + " " + text + "; " + numbered);
        return std::nullopt;
    }
    if (const auto it = ids.by_id.find(text); it != ids.by_id.end()) return it->second;
    if (!loader.discs_complete) return std::nullopt;
    std::string message = value.path + ": no " + one + " has id '" + text + "'";
    if (const auto suggestion = closest_match(text, ids.names))
        message += "; did you mean '" + *suggestion + "'?";
    d.error(value.where, std::move(message));
    return std::nullopt;
}

}  // namespace discreel::scene::detail
