#pragma once
// Collects every problem found while loading a scene, then hands them back in file order.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "discreel/scene.hpp"

namespace discreel::scene::detail {

// 1-based, as editors count.
struct Location {
    int line = 1;
    int column = 1;

    bool operator==(const Location&) const = default;
};

class Diagnostics {
public:
    // Past this many problems the file is hopeless; the loader stops looking so that a
    // pathological file (a million overlapping discs) cannot take minutes to reject.
    static constexpr std::size_t stop_after = 10'000;
    // How many are shown; the rest are summarised in one closing line.
    static constexpr std::size_t shown = 100;

    void error(Location where, std::string message);
    // What loads but leaves the measured range (Diagnostic::warning); the first `shown` kept.
    void warn(Location where, std::string message);
    bool empty() const { return entries_.empty(); }
    std::size_t count() const { return entries_.size(); }
    bool full() const { return entries_.size() >= stop_after; }

    // Sorted by position (stable: problems at the same place keep the order they were found).
    std::vector<Diagnostic> finish(std::string_view file) &&;
    // The warnings, sorted the same way; they are dropped from here.
    std::vector<Diagnostic> take_warnings(std::string_view file);

    // Lines from `first_line` on (up to the next source's) hold what the command line added
    // (`--set KEY=VALUE`): their problems are reported as `label: message`, without a line.
    void add_source(int first_line, std::string label);

private:
    struct Entry {
        Location where;
        std::string message;
    };
    struct Source {
        int first_line;
        std::string label;
    };
    Diagnostic report(std::string_view file, Entry& entry, bool warning) const;
    // Stable: entries at the same place keep the order they were found.
    static void sort_by_position(std::vector<Entry>& entries);

    std::vector<Entry> entries_, warnings_;
    std::vector<Source> sources_;  // in order of first_line
};

// Shortest text that reads back as the same double ("0.1", "1e-05"), whole numbers in full.
std::string format_number(double value);
// Four significant digits, for measured quantities in messages ("0.1", "2.5e-05").
std::string format_short(double value);

}  // namespace discreel::scene::detail
