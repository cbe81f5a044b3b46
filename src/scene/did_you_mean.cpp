#include "discreel/did_you_mean.hpp"

#include <algorithm>
#include <vector>

namespace discreel {
namespace {

char lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

bool plausible(std::size_t distance, std::size_t candidate_length) {
    return distance <= 2 && 2 * distance < candidate_length;
}

template <class Candidates>
std::optional<std::string> closest(std::string_view word, const Candidates& candidates) {
    std::optional<std::string> best;
    std::size_t best_distance = 0;
    for (const auto& candidate : candidates) {
        const std::string_view c = candidate;
        // Cheap bound first: the length difference alone is a lower bound on the distance.
        const std::size_t length_gap = c.size() > word.size() ? c.size() - word.size()
                                                              : word.size() - c.size();
        if (length_gap > 2) continue;
        const std::size_t d = edit_distance(word, c);
        if (!plausible(d, c.size())) continue;
        if (!best || d < best_distance) {
            best = std::string(c);
            best_distance = d;
        }
    }
    return best;
}

}  // namespace

std::size_t edit_distance(std::string_view a, std::string_view b) {
    const std::size_t n = a.size(), m = b.size();
    // Three rolling rows: the transposition step looks two rows back.
    std::vector<std::size_t> before(m + 1), previous(m + 1), current(m + 1);
    for (std::size_t j = 0; j <= m; ++j) previous[j] = j;
    for (std::size_t i = 1; i <= n; ++i) {
        current[0] = i;
        for (std::size_t j = 1; j <= m; ++j) {
            const std::size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
            current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost});
            if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) &&
                lower(a[i - 2]) == lower(b[j - 1]))
                current[j] = std::min(current[j], before[j - 2] + 1);
        }
        std::swap(before, previous);
        std::swap(previous, current);
    }
    return previous[m];
}

std::optional<std::string> closest_match(std::string_view word,
                                         std::span<const std::string_view> candidates) {
    return closest(word, candidates);
}

std::optional<std::string> closest_match(std::string_view word,
                                         std::span<const std::string> candidates) {
    return closest(word, candidates);
}

}  // namespace discreel
