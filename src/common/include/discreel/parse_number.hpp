#pragma once
// Whole numbers and frame sizes read from text the user typed (options, environment variables,
// file names, request fields): all of the text or nothing, no spaces, no '+', within range.
#include <charconv>
#include <optional>
#include <string_view>
#include <utility>

namespace discreel {

// "42", "-3" -> the number; "", "4x", " 4", "99999999999" -> nullopt. T is an integer type.
template <class T = int>
std::optional<T> parse_whole(std::string_view text) {
    T value{};
    const auto [end, problem] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || problem != std::errc() || end != text.data() + text.size()) {
        return std::nullopt;
    }
    return value;
}

// "1280x720" -> {1280, 720}; anything else -> nullopt. The range is the caller's to check.
inline std::optional<std::pair<int, int>> parse_size(std::string_view text) {
    const auto x = text.find('x');
    if (x == std::string_view::npos) return std::nullopt;
    const auto width = parse_whole(text.substr(0, x));
    const auto height = parse_whole(text.substr(x + 1));
    if (!width || !height) return std::nullopt;
    return std::pair{*width, *height};
}

}  // namespace discreel
