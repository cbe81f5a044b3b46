// `category:` and `collides:` on discs, bodies and walls: category names, each one bit.
#include "entries.hpp"
#include "loader.hpp"

namespace discreel::scene::detail {

std::optional<std::uint32_t> category_bit(Loader& loader, const Value& value) {
    auto& d = loader.diagnostics;
    if (!value.node.IsScalar() || value.is_null()) {
        d.error(value.where, value.path + ": expected a category name, got " + describe(value.node));
        return std::nullopt;
    }
    const auto id = read_id(value, d);
    if (!id) return std::nullopt;
    auto& bits = loader.category_bits;
    if (bits.empty()) {
        bits.emplace("default", physics::default_category);
        bits.emplace("walls", physics::walls_category);
    }
    if (const auto it = bits.find(*id); it != bits.end()) return it->second;
    if (bits.size() >= 32) {
        d.error(value.where, value.path + ": '" + *id +
                                 "' would be a 33rd category; a scene may name at most 32 "
                                 "(default and walls included)");
        return std::nullopt;
    }
    const std::uint32_t bit = 1u << bits.size();
    bits.emplace(*id, bit);
    return bit;
}

bool read_filter(Loader& loader, const Fields& fields, std::uint32_t& category,
                 std::uint32_t& collides) {
    bool ok = true;
    if (const auto v = fields.get("category")) {
        const auto bit = category_bit(loader, *v);
        ok = bit.has_value();
        if (bit) category = *bit;
    }
    if (const auto v = fields.get("collides")) {
        const auto items = read_list(*v, loader.diagnostics);
        if (!items) return false;
        std::uint32_t bits = 0;
        for (const Value& item : *items) {
            const auto bit = category_bit(loader, item);
            ok = ok && bit.has_value();
            bits |= bit.value_or(0);
        }
        collides = bits;
    }
    return ok;
}

}  // namespace discreel::scene::detail
