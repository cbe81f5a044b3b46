#pragma once
// A render request's JSON body: checked field by field, turned into the render-job layer's
// request, and named by an id derived from discreel's version, the scene and the options.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "callbacks.hpp"
#include "discreel/render_plan.hpp"
#include "discreel/scene.hpp"

namespace discreel::serve {

// An answer other than success: the status code and the JSON body.
struct Refusal {
    int status = 400;
    nlohmann::json body;
};

Refusal refusal(int status, const std::string& message);   // {"error": {"message": ...}}

// nlohmann::json's move constructor is noexcept; the check follows the assertions inside it.
// NOLINTNEXTLINE(bugprone-exception-escape)
struct JobRequest {
    std::string scene;               // YAML text
    std::string format;              // "mp4", "webm", "mkv", "gif", "png"
    nlohmann::json options;          // every field but the scene, output included: canonical
    job::RenderRequest render;       // .output is a bare "render.<format>", set by the worker
    std::vector<scene::Override> overrides;   // `set`, in key order
    // `outputs` beside the main one: "trace", "events", "joints", "shapes", "camera", "masks",
    // "boxes", in the order given (side_outputs names them all).
    std::vector<std::string> extras;
    std::optional<CallbackUrl> callback;   // POSTed the job when it ends
    std::string id;                  // 32 hex digits
    std::string stored() const;      // the JSON kept in the store: options plus the scene
};

// Parses a request body (POST /v1/renders and /v1/validate). 400 for malformed JSON, unknown
// fields and wrong types; 413 for a scene over limits.file_bytes.
std::variant<JobRequest, Refusal> parse_job_request(std::string_view body,
                                                    const scene::Limits& limits,
                                                    const std::string& version);

// A job's scene loaded and its options planned: what the job will render, and its scene's
// warnings, [{"line", "column", "message"}, ...].
struct PlannedJob {
    job::RenderPlan plan;
    nlohmann::json warnings = nlohmann::json::array();
};

// The job planned, or 422 with {"errors": [{"line", "column", "message"}, ...]} (line and column
// null for the options).
std::variant<PlannedJob, Refusal> plan_job(const JobRequest& request,
                                           const scene::Limits& limits);

const char* content_type_of(const std::string& format);

// The outputs a job may ask for beside its video or image, each at /v1/renders/<id>/<name>.
inline constexpr std::array<const char*, 7> side_outputs{"trace",  "events", "joints", "shapes",
                                                         "camera", "masks",  "boxes"};
// A side output's file extension: "csv", "json", or "tar" for the masks.
const char* extension_of(const std::string& side_output);

}  // namespace discreel::serve
