#include "metrics.hpp"

#include <sstream>

namespace discreel::serve {

void Metrics::ended(const char* status, double render_seconds) {
    std::lock_guard lock(mutex_);
    ++ended_[status];
    if (std::string_view(status) != "succeeded") return;
    ++render_count_;
    render_sum_ += render_seconds;
    for (std::size_t i = 0; i < bounds.size(); ++i) {
        if (render_seconds <= bounds[i]) {
            ++buckets_[i];
            break;
        }
    }
}

void Metrics::answered(int status) {
    std::lock_guard lock(mutex_);
    ++responses_[status];
}

std::string Metrics::text(std::size_t queued, std::size_t running, int workers,
                          std::size_t studio_timelines) const {
    std::ostringstream out;
    const auto metric = [&](const char* name, const char* type, const char* help) {
        out << "# HELP " << name << ' ' << help << "\n# TYPE " << name << ' ' << type << '\n';
    };
    metric("discreel_jobs_accepted_total", "counter",
           "Jobs put in the queue (new requests, and failed or cancelled ones sent again).");
    out << "discreel_jobs_accepted_total " << accepted_.load() << '\n';
    metric("discreel_jobs_cache_hits_total", "counter",
           "Requests answered from a finished job without rendering.");
    out << "discreel_jobs_cache_hits_total " << cache_hits_.load() << '\n';
    metric("discreel_jobs_rejected_total", "counter", "Jobs refused with 429: the queue was full.");
    out << "discreel_jobs_rejected_total " << rejected_busy_.load() << '\n';
    metric("discreel_jobs_queued", "gauge", "Jobs waiting for a worker.");
    out << "discreel_jobs_queued " << queued << '\n';
    metric("discreel_jobs_running", "gauge", "Jobs being rendered.");
    out << "discreel_jobs_running " << running << '\n';
    metric("discreel_workers", "gauge", "Render workers.");
    out << "discreel_workers " << workers << '\n';
    metric("discreel_studio_timelines", "gauge", "Studio timelines being played.");
    out << "discreel_studio_timelines " << studio_timelines << '\n';
    metric("discreel_output_bytes_served_total", "counter", "Bytes of outputs sent to clients.");
    out << "discreel_output_bytes_served_total " << bytes_served_.load() << '\n';
    metric("discreel_jobs_swept_total", "counter",
           "Finished jobs the sweeper deleted (--keep, --keep-bytes).");
    out << "discreel_jobs_swept_total " << swept_jobs_.load() << '\n';
    metric("discreel_output_bytes_swept_total", "counter",
           "Bytes of outputs the sweeper deleted.");
    out << "discreel_output_bytes_swept_total " << swept_bytes_.load() << '\n';
    std::lock_guard lock(mutex_);
    metric("discreel_jobs_finished_total", "counter", "Jobs that reached a final status.");
    for (const char* status : {"succeeded", "failed", "cancelled"}) {
        const auto found = ended_.find(status);
        out << "discreel_jobs_finished_total{status=\"" << status << "\"} "
            << (found == ended_.end() ? 0 : found->second) << '\n';
    }
    metric("discreel_render_seconds", "histogram", "Wall time of successful renders.");
    std::uint64_t cumulative = 0;
    for (std::size_t i = 0; i < bounds.size(); ++i) {
        cumulative += buckets_[i];
        out << "discreel_render_seconds_bucket{le=\"" << bounds[i] << "\"} " << cumulative << '\n';
    }
    out << "discreel_render_seconds_bucket{le=\"+Inf\"} " << render_count_ << '\n';
    out << "discreel_render_seconds_sum " << render_sum_ << '\n';
    out << "discreel_render_seconds_count " << render_count_ << '\n';
    metric("discreel_http_responses_total", "counter", "HTTP responses by status code.");
    for (const auto& [code, count] : responses_) {
        out << "discreel_http_responses_total{code=\"" << code << "\"} " << count << '\n';
    }
    return out.str();
}

}  // namespace discreel::serve
