#pragma once
// Naming a disc from elsewhere in the file (throws, camera.follow): by index or by id.
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "loader.hpp"

namespace discreel::scene::detail {

// The scene's disc ids, looked up once for all references.
struct DiscIds {
    explicit DiscIds(const std::vector<Body>& discs);
    std::map<std::string, std::size_t> by_id;
    std::vector<std::string> names;   // in disc order, for "did you mean"
};

// A plain whole number names a disc by index; anything else (including a quoted "3") by id.
// Reports a missing disc (with a suggestion for a close id) unless the disc list itself had
// problems, which are reported already.
std::optional<std::size_t> resolve_disc(Loader& loader, const Value& value, const DiscIds& ids);

}  // namespace discreel::scene::detail
