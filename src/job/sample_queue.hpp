#pragma once
// Sound samples handed from the thread that synthesizes them to the one that encodes them, in
// a bounded buffer: the producer waits when it is full, so memory stays flat however long the
// clip; either side can close it (the end, or a cancellation) and wake the other.
#include <algorithm>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <span>
#include <vector>

namespace discreel::job {

class SampleQueue {
public:
    explicit SampleQueue(std::size_t capacity) : capacity_(capacity) {}

    // False once the queue is cancelled: the producer should stop.
    bool push(std::span<const std::int16_t> samples) {
        std::unique_lock lock(mutex_);
        for (std::size_t i = 0; i < samples.size();) {
            changed_.wait(lock, [&] { return cancelled_ || samples_.size() < capacity_; });
            if (cancelled_) return false;
            const std::size_t n = std::min(samples.size() - i, capacity_ - samples_.size());
            samples_.insert(samples_.end(), samples.begin() + static_cast<std::ptrdiff_t>(i),
                            samples.begin() + static_cast<std::ptrdiff_t>(i + n));
            i += n;
            changed_.notify_all();
        }
        return true;
    }
    // No more samples will come.
    void close() {
        std::lock_guard lock(mutex_);
        closed_ = true;
        changed_.notify_all();
    }
    void cancel() {
        std::lock_guard lock(mutex_);
        cancelled_ = true;
        changed_.notify_all();
    }
    // Up to `count` samples, waiting until that many are there or the queue is closed; fewer
    // only at the end.
    std::vector<std::int16_t> take(std::size_t count) {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] {
            return cancelled_ || closed_ || samples_.size() >= std::min(count, capacity_);
        });
        const std::size_t n = std::min(count, samples_.size());
        std::vector<std::int16_t> out(samples_.begin(),
                                      samples_.begin() + static_cast<std::ptrdiff_t>(n));
        samples_.erase(samples_.begin(), samples_.begin() + static_cast<std::ptrdiff_t>(n));
        changed_.notify_all();
        return out;
    }

private:
    const std::size_t capacity_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<std::int16_t> samples_;
    bool closed_ = false;
    bool cancelled_ = false;
};

}  // namespace discreel::job
