#pragma once
// A fixed-capacity FIFO of slot indices between two pipeline stages. It never allocates after
// construction. close() ends the stream (pop drains what is left, then reports the end);
// cancel() abandons it (pop reports the end at once, push drops its item), which is how a
// failing or interrupted stage wakes the others.
#include <condition_variable>
#include <mutex>
#include <optional>
#include <vector>

namespace discreel::job {

class SlotQueue {
public:
    explicit SlotQueue(int capacity) : items_(static_cast<std::size_t>(capacity)) {}

    void push(int slot) {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return cancelled_ || size_ < items_.size(); });
        if (cancelled_) return;
        items_[(head_ + size_) % items_.size()] = slot;
        ++size_;
        changed_.notify_all();
    }

    // The next slot, or nullopt at the end of the stream.
    std::optional<int> pop() {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return cancelled_ || closed_ || size_ > 0; });
        if (cancelled_ || size_ == 0) return std::nullopt;
        const int slot = items_[head_];
        head_ = (head_ + 1) % items_.size();
        --size_;
        changed_.notify_all();
        return slot;
    }

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

private:
    std::mutex mutex_;
    std::condition_variable changed_;
    std::vector<int> items_;
    std::size_t head_ = 0;
    std::size_t size_ = 0;
    bool closed_ = false;
    bool cancelled_ = false;
};

}  // namespace discreel::job
