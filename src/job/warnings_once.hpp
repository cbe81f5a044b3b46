#pragma once
// Hands Playback::take_warnings' messages to a RenderDef's or SimulateDef's on_warning, each
// message once however many playbacks (segments, the recorder) meet it, from any thread.
#include <functional>
#include <mutex>
#include <set>
#include <string>
#include <vector>

namespace discreel::job {

class WarningsOnce {
public:
    explicit WarningsOnce(const std::function<void(const std::string&)>& sink) : sink_(sink) {}

    void say(const std::vector<std::string>& messages) {
        if (messages.empty() || !sink_) return;
        std::lock_guard lock(mutex_);
        for (const std::string& message : messages) {
            if (said_.insert(message).second) sink_(message);
        }
    }

private:
    const std::function<void(const std::string&)>& sink_;
    std::mutex mutex_;
    std::set<std::string> said_;
};

}  // namespace discreel::job
