#pragma once
// The service's counters, in Prometheus' text exposition format (version 0.0.4).
#include <array>
#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>

namespace discreel::serve {

class Metrics {
public:
    void accepted() { ++accepted_; }
    void cache_hit() { ++cache_hits_; }
    void rejected_busy() { ++rejected_busy_; }
    void ended(const char* status, double render_seconds);   // a job reached a final status
    void served(std::uint64_t bytes) { bytes_served_ += bytes; }
    void answered(int status);                               // an HTTP response
    void swept(std::uint64_t jobs, std::uint64_t bytes) {    // the sweeper forgot them
        swept_jobs_ += jobs;
        swept_bytes_ += bytes;
    }

    // The gauges come from the job table at the time of the scrape.
    std::string text(std::size_t queued, std::size_t running, int workers,
                     std::size_t studio_timelines) const;

private:
    // Render time buckets, seconds: from a small still (tens of ms) to long clips.
    static constexpr std::array<double, 12> bounds{0.025, 0.05, 0.1, 0.25, 0.5, 1,
                                                   2.5,   5,    10,  30,   120, 600};
    std::atomic<std::uint64_t> accepted_{0}, cache_hits_{0}, rejected_busy_{0}, bytes_served_{0},
        swept_jobs_{0}, swept_bytes_{0};
    mutable std::mutex mutex_;   // guards what follows
    std::map<std::string, std::uint64_t> ended_;     // by final status
    std::array<std::uint64_t, bounds.size()> buckets_{};   // not cumulative; summed when written
    std::uint64_t render_count_ = 0;
    double render_sum_ = 0;
    std::map<int, std::uint64_t> responses_;          // by status code
};

}  // namespace discreel::serve
