#pragma once
// Benchmark results as data: each bench appends one CSV row per measurement to
// <dir>/<bench>.csv, writing the header first when the file is new. Every row starts with the
// UTC date and time, the CPU model (/proc/cpuinfo "model name") and the logical core count, so
// figures from different machines and days can sit in one file and be told apart. <dir> is
// $DISCREEL_BENCH_RESULTS when set (empty: write nothing), else the source tree's
// bench/results (DISCREEL_BENCH_RESULTS_DIR, set by bench/CMakeLists.txt).
// Benches may read the clock; the simulation never does.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace discreel::bench {

// One CSV field: quoted when it holds a comma, a quote or a line break.
inline std::string csv_field(const std::string& text) {
    if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
    std::string quoted = "\"";
    for (const char c : text) {
        if (c == '"') quoted += '"';
        quoted += c;
    }
    return quoted + '"';
}

inline std::string csv_number(double value, int decimals) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

// The p-quantile (0..1) of `values`, the nearest rank; 0 for none.
inline double percentile(std::vector<double> values, double p) {
    if (values.empty()) return 0;
    std::sort(values.begin(), values.end());
    const auto index =
        static_cast<std::size_t>(std::lround(p * static_cast<double>(values.size() - 1)));
    return values[std::min(index, values.size() - 1)];
}

inline std::string cpu_model() {
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);) {
        if (line.rfind("model name", 0) != 0) continue;
        const auto colon = line.find(':');
        if (colon == std::string::npos) break;
        const auto start = line.find_first_not_of(" \t", colon + 1);
        return start == std::string::npos ? std::string() : line.substr(start);
    }
    return "unknown";
}

inline std::string utc_now() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

// Appends rows to <dir>/<bench>.csv. `columns` are the bench's own, after date_utc, cpu_model
// and cores; name them with their unit (cpu_ms_per_sim_s, peak_mib).
class ResultsFile {
public:
    ResultsFile(const std::string& bench, std::vector<std::string> columns)
        : columns_(std::move(columns)), cpu_(cpu_model()),
          cores_(std::to_string(std::thread::hardware_concurrency())) {
        const char* dir = std::getenv("DISCREEL_BENCH_RESULTS");
#ifdef DISCREEL_BENCH_RESULTS_DIR
        if (dir == nullptr) dir = DISCREEL_BENCH_RESULTS_DIR;
#endif
        if (dir == nullptr || *dir == '\0') return;
        path_ = std::filesystem::path(dir) / (bench + ".csv");
    }

    // One row: values in the order of `columns`. A file whose header differs (the bench's
    // columns changed) is left alone, with a warning: rename it and run again.
    void append(const std::vector<std::string>& values) {
        if (path_.empty()) return;
        if (values.size() != columns_.size()) {
            std::cerr << "bench: " << values.size() << " values for " << columns_.size()
                      << " columns; not appended\n";
            return;
        }
        std::string header = "date_utc,cpu_model,cores";
        for (const auto& c : columns_) header += "," + c;
        std::error_code ignored;
        std::filesystem::create_directories(path_.parent_path(), ignored);
        const bool fresh = !std::filesystem::exists(path_) || std::filesystem::is_empty(path_);
        if (!fresh) {
            std::ifstream in(path_);
            std::string first;
            std::getline(in, first);
            if (first != header) {
                std::cerr << "bench: " << path_.string() << " has other columns; not appended\n";
                return;
            }
        }
        std::ofstream out(path_, std::ios::app);
        if (fresh) out << header << '\n';
        out << csv_field(utc_now()) << ',' << csv_field(cpu_) << ',' << cores_;
        for (const auto& v : values) out << ',' << csv_field(v);
        out << '\n';
        if (!out) std::cerr << "bench: could not write " << path_.string() << '\n';
    }

    const std::filesystem::path& path() const { return path_; }

private:
    std::vector<std::string> columns_;
    std::string cpu_;
    std::string cores_;
    std::filesystem::path path_;
};

}  // namespace discreel::bench
