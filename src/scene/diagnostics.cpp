#include "diagnostics.hpp"

#include "discreel/printable.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <utility>

namespace discreel::scene {

std::string Diagnostic::to_string() const {
    // File names, keys and ids come from users: their control bytes are shown escaped.
    const std::string text = (warning ? "warning: " : "") + message;
    if (line <= 0) return printable(file + ": " + text);  // about the file as a whole
    return printable(file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " +
                     text);
}

namespace detail {

void Diagnostics::error(Location where, std::string message) {
    if (full()) return;
    entries_.push_back({where, std::move(message)});
}

void Diagnostics::warn(Location where, std::string message) {
    if (warnings_.size() >= shown) return;
    warnings_.push_back({where, std::move(message)});
}

void Diagnostics::sort_by_position(std::vector<Entry>& entries) {
    std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
        if (a.where.line != b.where.line) return a.where.line < b.where.line;
        return a.where.column < b.where.column;
    });
}

void Diagnostics::add_source(int first_line, std::string label) {
    sources_.push_back({first_line, std::move(label)});
}

Diagnostic Diagnostics::report(std::string_view file, Entry& entry, bool warning) const {
    for (auto it = sources_.rbegin(); it != sources_.rend(); ++it) {
        if (entry.where.line >= it->first_line)
            return {it->label, 0, 0, std::move(entry.message), warning};
    }
    return {std::string(file), entry.where.line, entry.where.column, std::move(entry.message),
            warning};
}

std::vector<Diagnostic> Diagnostics::take_warnings(std::string_view file) {
    sort_by_position(warnings_);
    std::vector<Diagnostic> out;
    for (Entry& e : warnings_) out.push_back(report(file, e, true));
    warnings_.clear();
    return out;
}

std::vector<Diagnostic> Diagnostics::finish(std::string_view file) && {
    sort_by_position(entries_);
    std::vector<Diagnostic> out;
    const std::size_t n = std::min(entries_.size(), shown);
    out.reserve(n + 1);
    for (std::size_t i = 0; i < n; ++i) out.push_back(report(file, entries_[i], false));
    if (entries_.size() > shown) {
        const std::string more = entries_.size() >= stop_after
                                     ? "at least " + std::to_string(entries_.size() - shown)
                                     : std::to_string(entries_.size() - shown);
        Entry closing{entries_[shown].where, "too many problems; " + more + " more not shown"};
        out.push_back(report(file, closing, false));
    }
    return out;
}

std::string format_number(double value) {
    // Whole numbers as people write them: 100000, not the shorter 1e+05.
    if (value == std::trunc(value) && std::fabs(value) < 1e15)
        return std::to_string(static_cast<long long>(value));
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

std::string format_short(double value) {
    char buffer[64];
    const auto result =
        std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 4);
    return std::string(buffer, result.ptr);
}

}  // namespace detail
}  // namespace discreel::scene
