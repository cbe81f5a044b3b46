// discreel serve end to end: a real server process on 127.0.0.1 with a temporary --data,
// driven over HTTP. Every wait is bounded in time and every loop in count; every server is
// stopped by pid. GL: the server renders.
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <gtest/gtest.h>
#include <httplib.h>

#include <atomic>
#include <map>
#include <mutex>
#include <chrono>
#include <nlohmann/json.hpp>
#include <thread>

#include "serve_client.hpp"
#include "serve_process.hpp"
#include "test_support.hpp"

namespace discreel {
namespace {

using nlohmann::json;
using testing::client_for;
using testing::connect_to;
using testing::exchange;
using testing::metric;
using testing::post;
using testing::read_file;
using testing::scene_text;
using testing::wait_final;
using testing::run_command;
using testing::ServeProcess;
using testing::TempDir;
using Clock = std::chrono::steady_clock;

const std::string bin = DISCREEL_BIN;

// What `discreel render` writes for the same scene and options.
std::string cli_render(const TempDir& dir, const std::string& scene,
                       const std::vector<std::string>& options, const std::string& name) {
    testing::write_file(dir / "cli.yaml", scene);
    std::vector<std::string> argv{bin, "render", dir / "cli.yaml", "-o", dir / name, "-q"};
    argv.insert(argv.end(), options.begin(), options.end());
    const auto run = run_command(argv);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return read_file(dir / name);
}

class ServeGLTest : public ::testing::Test {
protected:
    TempDir dir;
    std::string log = dir / "serve.log";
};

TEST_F(ServeGLTest, AStillIsTheCliBytesAndTheSameRequestIsACacheHit) {
    ServeProcess server(bin, {"--data", dir / "data"}, log);
    auto client = client_for(server.port());
    const json request{{"scene", scene_text()}, {"output", "png"}, {"frame", 3},
                       {"size", "160x90"}};
    auto accepted = post(client, "/v1/renders", request);
    ASSERT_TRUE(accepted);
    ASSERT_EQ(accepted->status, 202) << accepted->body;
    const json job = json::parse(accepted->body);
    const std::string id = job["id"];
    EXPECT_EQ(accepted->get_header_value("Location"), "/v1/renders/" + id);
    EXPECT_EQ(job["status"], "queued");
    EXPECT_EQ(job["progress"]["frames_total"], 1);

    const json done = wait_final(client, id);
    ASSERT_EQ(done["status"], "succeeded") << done.dump();
    EXPECT_EQ(done["error"], nullptr);
    EXPECT_EQ(done["output"]["content_type"], "image/png");
    EXPECT_EQ(done["output"]["url"], "/v1/renders/" + id + "/output");

    auto output = client.Get("/v1/renders/" + id + "/output");
    ASSERT_TRUE(output);
    ASSERT_EQ(output->status, 200);
    EXPECT_EQ(output->get_header_value("Content-Type"), "image/png");
    const std::string cli = cli_render(dir, scene_text(), {"--frame", "3", "--size", "160x90"},
                                       "cli.png");
    EXPECT_EQ(output->body, cli) << "the service's still differs from discreel render's";
    EXPECT_EQ(done["output"]["bytes"], cli.size());
    const std::string etag = output->get_header_value("ETag");
    std::string quoted_sha = done["output"]["sha256"].get<std::string>();
    quoted_sha.insert(quoted_sha.begin(), '"');
    quoted_sha.push_back('"');
    EXPECT_EQ(etag, quoted_sha);

    // The same request: answered from the store at once, no new job.
    auto again = post(client, "/v1/renders", request);
    ASSERT_TRUE(again);
    EXPECT_EQ(again->status, 200);
    EXPECT_EQ(json::parse(again->body)["status"], "succeeded");
    // Key order and spacing are not part of the request's identity.
    std::string reordered_body =
        "{ \"size\": \"160x90\", \"frame\": 3, \"output\": \"png\", \"scene\": ";
    reordered_body += json(scene_text()).dump();
    reordered_body += " }";
    auto reordered = client.Post("/v1/renders", reordered_body, "application/json");
    ASSERT_TRUE(reordered);
    EXPECT_EQ(reordered->status, 200);
    EXPECT_EQ(json::parse(reordered->body)["id"], id);

    // Conditional and partial requests.
    auto unchanged = client.Get("/v1/renders/" + id + "/output", {{"If-None-Match", etag}});
    ASSERT_TRUE(unchanged);
    EXPECT_EQ(unchanged->status, 304);
    EXPECT_TRUE(unchanged->body.empty());
    auto part = client.Get("/v1/renders/" + id + "/output", {{"Range", "bytes=8-23"}});
    ASSERT_TRUE(part);
    EXPECT_EQ(part->status, 206);
    EXPECT_EQ(part->body, cli.substr(8, 16));
    EXPECT_EQ(part->get_header_value("Content-Range"),
              "bytes 8-23/" + std::to_string(cli.size()));

    auto metrics = client.Get("/metrics");
    ASSERT_TRUE(metrics);
    EXPECT_EQ(metrics->status, 200);
    EXPECT_EQ(metric(metrics->body, "discreel_jobs_accepted_total"), "1");
    EXPECT_EQ(metric(metrics->body, "discreel_jobs_cache_hits_total"), "2");
    EXPECT_EQ(metric(metrics->body, "discreel_jobs_finished_total{status=\"succeeded\"}"), "1");
    EXPECT_EQ(metric(metrics->body, "discreel_render_seconds_count"), "1");
    EXPECT_EQ(metric(metrics->body, "discreel_output_bytes_served_total"),
              std::to_string(cli.size() + 16));   // the whole file and the range
    // A range past the end is cut at the end; one that starts past it is 416.
    auto tail = client.Get("/v1/renders/" + id + "/output", {{"Range", "bytes=-16"}});
    ASSERT_TRUE(tail);
    EXPECT_EQ(tail->status, 206);
    EXPECT_EQ(tail->body, cli.substr(cli.size() - 16));
    auto cut = client.Get("/v1/renders/" + id + "/output", {{"Range", "bytes=100-99999999"}});
    ASSERT_TRUE(cut);
    EXPECT_EQ(cut->status, 206);
    EXPECT_EQ(cut->body, cli.substr(100));
    auto outside = client.Get("/v1/renders/" + id + "/output", {{"Range", "bytes=99999999-"}});
    ASSERT_TRUE(outside);
    EXPECT_EQ(outside->status, 416);
    EXPECT_EQ(outside->get_header_value("Content-Range"), "bytes */" + std::to_string(cli.size()));
    // Finished: nothing to cancel.
    auto cancel = client.Delete("/v1/renders/" + id);
    ASSERT_TRUE(cancel);
    EXPECT_EQ(cancel->status, 409);

    // Another still on the same worker, whose context is now warm: still the CLI's bytes.
    auto second = post(client, "/v1/renders",
                       json{{"scene", scene_text(9)}, {"output", "png"}, {"size", "160x90"}});
    ASSERT_TRUE(second);
    ASSERT_EQ(second->status, 202);
    const std::string second_id = json::parse(second->body)["id"];
    ASSERT_EQ(wait_final(client, second_id)["status"], "succeeded");
    auto second_output = client.Get("/v1/renders/" + second_id + "/output");
    ASSERT_TRUE(second_output);
    EXPECT_EQ(second_output->body, cli_render(dir, scene_text(9), {"--size", "160x90"}, "2.png"));
    // SIGTERM: a clean stop.
    EXPECT_EQ(server.stop(SIGTERM), 0);
}

TEST_F(ServeGLTest, AClipIsTheCliBytesWithProgressEventsToTheEnd) {
    ServeProcess server(bin, {"--data", dir / "data"}, log);
    auto client = client_for(server.port());
    // With the contacts' sound: the CLI's bytes with --audio.
    const json request{{"scene", scene_text(2)}, {"output", "mp4"}, {"crf", 30},
                       {"preset", "ultrafast"}, {"fps", 25}, {"audio", true}};
    auto accepted = post(client, "/v1/renders", request);
    ASSERT_TRUE(accepted);
    ASSERT_EQ(accepted->status, 202) << accepted->body;
    const std::string id = json::parse(accepted->body)["id"];

    std::string stream;
    auto events = client.Get("/v1/renders/" + id + "/events",
                             [&](const char* data, std::size_t size) {
                                 stream.append(data, size);
                                 return stream.size() < (1 << 20);
                             });
    ASSERT_TRUE(events);
    EXPECT_EQ(events->status, 200);
    EXPECT_EQ(events->get_header_value("Content-Type"), "text/event-stream");
    std::vector<json> jobs;
    for (std::size_t at = 0; (at = stream.find("data: ", at)) != std::string::npos;) {
        const auto end = stream.find('\n', at);
        jobs.push_back(json::parse(stream.substr(at + 6, end - at - 6)));
        at = end;
    }
    ASSERT_FALSE(jobs.empty());
    EXPECT_EQ(jobs.back()["status"], "succeeded");
    EXPECT_EQ(jobs.back()["progress"]["frames_done"], 25);
    for (std::size_t i = 1; i < jobs.size(); ++i) {
        EXPECT_LE(jobs[i - 1]["progress"]["frames_done"], jobs[i]["progress"]["frames_done"]);
    }

    auto output = client.Get("/v1/renders/" + id + "/output");
    ASSERT_TRUE(output);
    EXPECT_EQ(output->get_header_value("Content-Type"), "video/mp4");
    EXPECT_EQ(output->body, cli_render(dir, scene_text(2),
                                       {"--crf", "30", "--preset", "ultrafast", "--fps", "25",
                                        "--audio"},
                                       "cli.mp4"));
}

// A scene beyond the speeds a crowd holds (a fast disc among eight resting ones): it loads with
// one warning, at line 4, column 48.
const std::string fast_scene =
    "version: 1\nvideo: {duration: 0.1, fps: 10}\ndiscs:\n"
    "  - {position: [0, 0], radius: 0.05, velocity: [1000, 0]}\n"
    "  - grid: {origin: [0, 5], count: [8, 1], spacing: [0.5, 1], radius: 0.05}\n";

TEST_F(ServeGLTest, RequestsAreCheckedWithExactAnswers) {
    ServeProcess server(bin, {"--data", dir / "data", "--max-scene-bytes", "2000"}, log);
    auto client = client_for(server.port());
    const auto answer = [&](const std::string& path, const std::string& body) {
        auto got = client.Post(path, body, "application/json");
        EXPECT_TRUE(got);
        return got ? std::pair{got->status, got->body} : std::pair{0, std::string()};
    };
    EXPECT_EQ(answer("/v1/validate", json{{"scene", scene_text()}}.dump()),
              (std::pair{200, std::string("{\"ok\":true,\"warnings\":[]}\n")}));
    // A scene beyond what a crowd holds: accepted, its warnings at their line and column, as
    // validate prints them, in the answer and in the job.
    const std::string fast = fast_scene;
    const json warnings = json::parse(R"json([{"line": 4, "column": 48, "message":
        "discs[0].velocity: 1000 m/s: crowds of this scene's bodies are measured to stay apart up to 240 m/s at 480 Hz (10 radii of the smallest moving body, '0', 0.05 m, per physics step); where several bodies this fast meet at once they may overlap; physics.rate 2000 or more keeps them apart (docs/physics.md, Limits)"}])json");
    const auto validated = answer("/v1/validate", json{{"scene", fast}}.dump());
    EXPECT_EQ(validated.first, 200);
    EXPECT_EQ(json::parse(validated.second), (json{{"ok", true}, {"warnings", warnings}}));
    const auto accepted = answer("/v1/renders", json{{"scene", fast}, {"output", "png"}}.dump());
    EXPECT_EQ(accepted.first, 202) << accepted.second;
    EXPECT_EQ(json::parse(accepted.second)["warnings"], warnings);
    // A scene problem: line and column of the value, the message validate prints.
    const std::string bad = "version: 1\ndiscs:\n  - position: [0, 0]\n    radius: -1\n";
    for (const char* path : {"/v1/validate", "/v1/renders"}) {
        const auto [status, body] = answer(path, json{{"scene", bad}}.dump());
        EXPECT_EQ(status, 422) << path;
        EXPECT_EQ(json::parse(body),
                  json::parse(R"({"errors": [{"line": 4, "column": 13, "message":
                                 "discs[0].radius: must be greater than 0, got -1"}]})"));
    }
    // An option problem: no place in the scene.
    EXPECT_EQ(json::parse(answer("/v1/validate",
                                 json{{"scene", scene_text()}, {"fps", 500}}.dump()).second),
              json::parse(R"({"errors": [{"line": null, "column": null,
                             "message": "'fps' must be between 1 and 240"}]})"));
    // Advice names the request's fields, never an option the service does not take.
    const auto advice = [&](const json& body) {
        return json::parse(answer("/v1/validate", body.dump()).second)["errors"][0]["message"]
            .get<std::string>();
    };
    EXPECT_EQ(advice(json{{"scene", scene_text()}, {"output", "mp4"}, {"size", "161x91"}}),
              "'size' 161x91: mp4 video (yuv420p) stores colour at half resolution, so its "
              "width and height must be even; PNG and GIF take any size");
    EXPECT_EQ(advice(json{{"scene", scene_text()}, {"output", "png"}, {"frame", 2}, {"at", 0.5}}),
              "give either 'frame' or 'at', not both");
    EXPECT_EQ(advice(json{{"scene", scene_text()}, {"output", "mp4"}, {"frames", "5-2"}}),
              "'frames' 5-2 ends before it starts; give the first frame first");
    EXPECT_EQ(answer("/v1/renders", "{\"scene\": ").first, 400);
    EXPECT_EQ(answer("/v1/renders", "[1, 2]"),
              (std::pair{400, std::string("{\"error\":{\"message\":\"the body must be a "
                                          "JSON object\"}}\n")}));
    EXPECT_EQ(answer("/v1/renders", json{{"scene", scene_text()}, {"colour", "red"}}.dump()).second,
              "{\"error\":{\"message\":\"unknown field 'colour'; the fields are scene, output, "
              "outputs, frame, frames, at, size, fps, duration, crf, preset, audio, set and "
              "callback\"}}\n");
    // `set` as --set: its problems name the key, with no place in the scene.
    EXPECT_EQ(json::parse(answer("/v1/validate", json{{"scene", scene_text()},
                                                      {"set", {{"physics.sede", 3}}}}
                                                     .dump())
                              .second),
              json::parse(R"({"errors": [{"line": null, "column": null, "message":
                  "set 'physics.sede': physics: unknown key 'sede'; did you mean 'seed'?"}]})"));
    EXPECT_EQ(answer("/v1/renders",
                     json{{"scene", scene_text()}, {"set", {{"video", {{"fps", 2}}}}}}.dump()),
              (std::pair{400, std::string("{\"error\":{\"message\":\"field 'set': the value of "
                                          "'video' is an object; set its keys one by one "
                                          "('video.KEY')\"}}\n")}));
    EXPECT_EQ(answer("/v1/renders", json{{"scene", scene_text()}, {"fps", "30"}}.dump()).second,
              "{\"error\":{\"message\":\"field 'fps' must be an integer\"}}\n");
    EXPECT_EQ(answer("/v1/renders", json{{"scene", scene_text()}, {"output", "avi"}}.dump()).first,
              400);
    EXPECT_EQ(answer("/v1/renders", "{\"scene\": [[[[[[1]]]]]]}").first, 400);
    // Over the scene limit: 413, from the parsed scene and, far over, before the body is read.
    EXPECT_EQ(answer("/v1/renders", json{{"scene", std::string(3000, '#')}}.dump()),
              (std::pair{413, std::string("{\"error\":{\"message\":\"the scene is 3000 bytes, "
                                          "over the limit of 2000\"}}\n")}));
    EXPECT_EQ(answer("/v1/renders", json{{"scene", std::string(200000, '#')}}.dump()).first,
              413);
    auto unknown = client.Get("/v1/renders/0123456789abcdef0123456789abcdef");
    ASSERT_TRUE(unknown);
    EXPECT_EQ(unknown->status, 404);
    auto not_an_id = client.Get("/v1/renders/..%2F..%2Fjobs.sqlite3/output");
    ASSERT_TRUE(not_an_id);
    EXPECT_EQ(not_an_id->status, 404);
    auto health = client.Get("/healthz");
    ASSERT_TRUE(health);
    EXPECT_EQ(health->status, 200);
    auto page = client.Get("/");
    ASSERT_TRUE(page);
    EXPECT_EQ(page->status, 200);
    EXPECT_NE(page->body.find("<textarea id=\"scene\""), std::string::npos);
}

// What the command line takes, the service takes: `set` as --set, `frames` as --frames; the
// bytes are the command line's.
TEST_F(ServeGLTest, SetAndFramesAreTheCommandLines) {
    ServeProcess server(bin, {"--data", dir / "data"}, log);
    auto client = client_for(server.port());
    const json request{{"scene", scene_text()}, {"output", "mkv"}, {"frames", "2-5"},
                       {"set", {{"physics.seed", 7}, {"video.size", {96, 54}}}}};
    auto accepted = post(client, "/v1/renders", request);
    ASSERT_TRUE(accepted);
    ASSERT_EQ(accepted->status, 202) << accepted->body;
    const json done = wait_final(client, json::parse(accepted->body)["id"]);
    ASSERT_EQ(done["status"], "succeeded") << done.dump();
    EXPECT_EQ(done["progress"]["frames_total"], 4);
    auto output = client.Get(done["output"]["url"].get<std::string>());
    ASSERT_TRUE(output);
    const std::string cli =
        cli_render(dir, scene_text(),
                   {"--frames", "2-5", "--set", "physics.seed=7", "--set", "video.size=[96,54]"},
                   "cli.mkv");
    EXPECT_EQ(output->body, cli) << "the service's clip differs from discreel render's";
    EXPECT_NE(cli_render(dir, scene_text(), {"--frames", "2-5", "--set", "video.size=[96,54]"},
                         "seed1.mkv"),
              cli);   // the seed took effect
}

// The files of a tar archive, by name.
std::map<std::string, std::string> untar(const std::string& archive) {
    std::map<std::string, std::string> files;
    for (std::size_t at = 0; at + 512 <= archive.size();) {
        const std::string name = archive.substr(at, archive.find('\0', at) - at).substr(0, 100);
        if (name.empty()) break;   // the zero blocks at the end
        const std::size_t size = std::stoul(archive.substr(at + 124, 11), nullptr, 8);
        files[name] = archive.substr(at + 512, size);
        at += 512 + (size + 511) / 512 * 512;
    }
    return files;
}

// A dataset's job: the clip and its ground truth as outputs of one job, each the bytes the
// command line writes with the same options.
TEST_F(ServeGLTest, SideOutputsAreTheCommandLinesFiles) {
    ServeProcess server(bin, {"--data", dir / "data"}, log);
    auto client = client_for(server.port());
    const json request{{"scene", scene_text()}, {"frames", "0-3"}, {"size", "64x36"},
                       {"outputs", {"mkv", "trace", "events", "shapes", "camera", "masks",
                                    "boxes"}}};
    auto accepted = post(client, "/v1/renders", request);
    ASSERT_TRUE(accepted);
    ASSERT_EQ(accepted->status, 202) << accepted->body;
    const json done = wait_final(client, json::parse(accepted->body)["id"]);
    ASSERT_EQ(done["status"], "succeeded") << done.dump();
    EXPECT_EQ(done["output"]["content_type"], "video/x-matroska");
    ASSERT_EQ(done["outputs"].size(), 6u) << done.dump();
    EXPECT_EQ(done["outputs"]["masks"]["content_type"], "application/x-tar");
    EXPECT_EQ(done["outputs"]["shapes"]["content_type"], "application/json");

    testing::write_file(dir / "cli.yaml", scene_text());
    const auto cli = run_command({bin, "render", dir / "cli.yaml", "-o", dir / "cli.mkv",
                                  "--frames", "0-3", "--size", "64x36", "--trace",
                                  dir / "t.csv", "--events", dir / "e.csv", "--shapes",
                                  dir / "s.json", "--camera", dir / "c.csv", "--masks",
                                  dir / "masks", "--boxes", dir / "b.csv", "-q"});
    ASSERT_EQ(cli.exit_code, 0) << cli.err;
    const auto fetch = [&](const std::string& name) {
        auto got = client.Get(done["outputs"][name]["url"].get<std::string>());
        EXPECT_TRUE(got && got->status == 200) << name;
        return got ? got->body : std::string();
    };
    EXPECT_EQ(fetch("trace"), read_file(dir / "t.csv"));
    EXPECT_EQ(fetch("events"), read_file(dir / "e.csv"));
    // The same path with EventSource's Accept is the job's progress stream, as for any job.
    auto stream = client.Get(done["outputs"]["events"]["url"].get<std::string>(),
                             {{"Accept", "text/event-stream"}});
    ASSERT_TRUE(stream);
    EXPECT_EQ(stream->get_header_value("Content-Type"), "text/event-stream");
    EXPECT_EQ(stream->body.rfind("event: job\n", 0), 0u) << stream->body;
    EXPECT_EQ(fetch("shapes"), read_file(dir / "s.json"));
    EXPECT_EQ(fetch("camera"), read_file(dir / "c.csv"));
    EXPECT_EQ(fetch("boxes"), read_file(dir / "b.csv"));
    const auto masks = untar(fetch("masks"));
    ASSERT_EQ(masks.size(), 4u);
    for (int frame = 0; frame < 4; ++frame) {
        const std::string name = "mask_0000" + std::to_string(frame) + ".png";
        EXPECT_EQ(masks.at("masks/" + name), read_file(dir / ("masks/" + name))) << name;
    }
    auto video = client.Get("/v1/renders/" + done["id"].get<std::string>() + "/output");
    ASSERT_TRUE(video);
    EXPECT_EQ(video->body, read_file(dir / "cli.mkv"));
    // A side output not asked for, and names that are none.
    auto absent = client.Get("/v1/renders/" + done["id"].get<std::string>() + "/joints");
    ASSERT_TRUE(absent);
    EXPECT_EQ(absent->status, 404);
    auto wav = post(client, "/v1/renders",
                    json{{"scene", scene_text()}, {"outputs", {"wav", "trace"}}});
    ASSERT_TRUE(wav);
    EXPECT_EQ(wav->status, 400);
    auto refused = post(client, "/v1/renders",
                        json{{"scene", scene_text()}, {"outputs", {"mp4", "depth"}}});
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 400);
    EXPECT_EQ(json::parse(refused->body)["error"]["message"],
              "field 'outputs': unknown output 'depth'; the outputs are mp4, webm, mkv, gif, png, "
              "wav (one of them) and trace, events, joints, shapes, camera, masks, boxes");
}

// "callback": the job's final state POSTed once to the app's server, retried after a failure,
// to allowed hosts only.
TEST_F(ServeGLTest, ACallbackIsReceivedOnceAndRetriedAfterAFailure) {
    httplib::Server receiver;
    std::mutex mutex;
    std::vector<std::pair<std::string, json>> received;   // path, body
    int answered = 0;
    receiver.Post(R"(/hooks/.*)", [&](const httplib::Request& req, httplib::Response& res) {
        std::lock_guard lock(mutex);
        received.emplace_back(req.path, json::parse(req.body, nullptr, false));
        // The first delivery of the second job fails: it must come again.
        res.status = req.path == "/hooks/flaky" && ++answered == 1 ? 500 : 204;
    });
    const int port = receiver.bind_to_any_port("127.0.0.1");
    std::thread serving([&] { receiver.listen_after_bind(); });
    struct Stop {
        httplib::Server& server;
        std::thread& thread;
        ~Stop() {
            server.stop();
            thread.join();
        }
    } stop{receiver, serving};

    ServeProcess server(bin, {"--data", dir / "data", "--callback-allow", "127.0.0.1"}, log);
    auto client = client_for(server.port());
    const std::string base = "http://127.0.0.1:" + std::to_string(port);
    std::vector<std::string> ids;
    for (const char* hook : {"/hooks/steady", "/hooks/flaky"}) {
        auto accepted = post(client, "/v1/renders",
                             json{{"scene", scene_text()}, {"output", "png"}, {"size", "64x36"},
                                  {"callback", base + hook}});
        ASSERT_TRUE(accepted);
        ASSERT_EQ(accepted->status, 202) << accepted->body;
        ids.push_back(json::parse(accepted->body)["id"]);
        ASSERT_EQ(wait_final(client, ids.back())["status"], "succeeded");
    }
    // The flaky hook's second try comes a second after its first.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    for (;;) {
        {
            std::lock_guard lock(mutex);
            if (received.size() >= 3 || std::chrono::steady_clock::now() > deadline) break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(500));   // nothing more may come
    std::lock_guard lock(mutex);
    ASSERT_EQ(received.size(), 3u);
    EXPECT_EQ(std::count_if(received.begin(), received.end(),
                            [](const auto& r) { return r.first == "/hooks/steady"; }),
              1);
    for (const auto& [path, body] : received) {
        EXPECT_EQ(body["status"], "succeeded") << path;
        EXPECT_EQ(body["id"], path == "/hooks/steady" ? ids[0] : ids[1]);
        EXPECT_EQ(body["output"]["url"], "/v1/renders/" + body["id"].get<std::string>() + "/output");
    }
    // Another host is refused before anything is stored.
    auto refused = post(client, "/v1/renders",
                        json{{"scene", scene_text()}, {"callback", "http://10.1.2.3/hook"}});
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 400);
    EXPECT_EQ(json::parse(refused->body)["error"]["message"],
              "field 'callback': the host '10.1.2.3' is not one this server calls back (serve "
              "--callback-allow)");
    refused = post(client, "/v1/renders",
                   json{{"scene", scene_text()}, {"callback", "https://127.0.0.1/hook"}});
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 400);
}

// An app's view of its jobs: newest first, a page at a time, by state.
TEST_F(ServeGLTest, JobsAreListedNewestFirstAPageAtATime) {
    ServeProcess server(bin, {"--data", dir / "data"}, log);
    auto client = client_for(server.port());
    std::vector<std::string> ids;
    for (int seed = 1; seed <= 3; ++seed) {
        auto accepted = post(client, "/v1/renders",
                             json{{"scene", scene_text(seed)}, {"output", "png"}, {"size", "64x36"}});
        ASSERT_TRUE(accepted);
        ASSERT_EQ(accepted->status, 202) << accepted->body;
        ids.push_back(json::parse(accepted->body)["id"]);
        ASSERT_EQ(wait_final(client, ids.back())["status"], "succeeded");
    }
    auto first = client.Get("/v1/renders?limit=2");
    ASSERT_TRUE(first);
    ASSERT_EQ(first->status, 200) << first->body;
    const json page = json::parse(first->body);
    ASSERT_EQ(page["jobs"].size(), 2u);
    EXPECT_EQ(page["jobs"][0]["id"], ids[2]);
    EXPECT_EQ(page["jobs"][1]["id"], ids[1]);
    EXPECT_EQ(page["jobs"][0]["status"], "succeeded");
    EXPECT_TRUE(page["jobs"][0]["created"].is_number_integer());
    EXPECT_EQ(page["next"], ids[1]);
    auto second = client.Get("/v1/renders?limit=2&before=" + ids[1]);
    ASSERT_TRUE(second);
    const json rest = json::parse(second->body);
    ASSERT_EQ(rest["jobs"].size(), 1u);
    EXPECT_EQ(rest["jobs"][0]["id"], ids[0]);
    EXPECT_EQ(rest["next"], nullptr);
    auto failed = client.Get("/v1/renders?state=failed");
    ASSERT_TRUE(failed);
    EXPECT_EQ(json::parse(failed->body), (json{{"jobs", json::array()}, {"next", nullptr}}));
    auto bad = client.Get("/v1/renders?state=done");
    ASSERT_TRUE(bad);
    EXPECT_EQ(bad->status, 400);
    EXPECT_EQ(json::parse(bad->body)["error"]["message"],
              "state must be queued, running, succeeded, failed or cancelled, not 'done'");
    bad = client.Get("/v1/renders?limit=0");
    ASSERT_TRUE(bad);
    EXPECT_EQ(bad->status, 400);
    bad = client.Get("/v1/renders?before=0123456789abcdef0123456789abcdef");
    ASSERT_TRUE(bad);
    EXPECT_EQ(bad->status, 400);
}

// --cors: a page of an allowed origin may call the API (its preflight answered, its answers
// marked readable); another origin's is refused and gets no CORS header. Without --cors, as
// before: OPTIONS is no method of the API.
TEST_F(ServeGLTest, CorsAllowsTheOriginsGivenAndNoOther) {
    {
        ServeProcess server(bin, {"--data", dir / "plain"}, log);
        auto client = client_for(server.port());
        auto options = client.Options("/v1/renders", {{"Origin", "http://app.example"},
                                                      {"Access-Control-Request-Method", "POST"}});
        ASSERT_TRUE(options);
        EXPECT_EQ(options->status, 405);
        EXPECT_FALSE(options->has_header("Access-Control-Allow-Origin"));
    }
    ServeProcess server(bin, {"--data", dir / "data", "--cors", "http://app.example", "--cors",
                              "https://studio.example:8443"},
                        log);
    auto client = client_for(server.port());
    auto allowed = client.Options("/v1/renders",
                                  {{"Origin", "https://studio.example:8443"},
                                   {"Access-Control-Request-Method", "POST"},
                                   {"Access-Control-Request-Headers", "content-type"}});
    ASSERT_TRUE(allowed);
    EXPECT_EQ(allowed->status, 204);
    EXPECT_EQ(allowed->get_header_value("Access-Control-Allow-Origin"),
              "https://studio.example:8443");
    EXPECT_NE(allowed->get_header_value("Access-Control-Allow-Methods").find("POST"),
              std::string::npos);
    EXPECT_NE(allowed->get_header_value("Access-Control-Allow-Headers").find("Content-Type"),
              std::string::npos);
    auto refused = client.Options("/v1/renders", {{"Origin", "http://evil.example"},
                                                  {"Access-Control-Request-Method", "POST"}});
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 403);
    EXPECT_FALSE(refused->has_header("Access-Control-Allow-Origin"));
    // The actual requests: marked for the allowed origin only.
    auto ok = post(client, "/v1/validate", json{{"scene", scene_text()}},
                   {{"Origin", "http://app.example"}});
    ASSERT_TRUE(ok);
    EXPECT_EQ(ok->status, 200);
    EXPECT_EQ(ok->get_header_value("Access-Control-Allow-Origin"), "http://app.example");
    EXPECT_EQ(ok->get_header_value("Vary"), "Origin");
    auto other = post(client, "/v1/validate", json{{"scene", scene_text()}},
                      {{"Origin", "http://evil.example"}});
    ASSERT_TRUE(other);
    EXPECT_FALSE(other->has_header("Access-Control-Allow-Origin"));
}

// --keep: a finished job older than that goes with its output, while it is being read over
// and over; a younger one stays; the metrics count what went.
TEST_F(ServeGLTest, TheSweeperDeletesWhatIsOldAndNothingElse) {
    ServeProcess server(bin, {"--data", dir / "data", "--keep", "3s"}, log);
    auto client = client_for(server.port());
    const auto render = [&](int seed) {
        auto accepted = post(client, "/v1/renders",
                             json{{"scene", scene_text(seed)}, {"output", "png"}, {"size", "64x36"},
                                  {"set", {{"physics.seed", seed}}}});
        EXPECT_TRUE(accepted && accepted->status == 202);
        const std::string id = json::parse(accepted->body)["id"];
        const json done = wait_final(client, id);
        EXPECT_EQ(done["status"], "succeeded");
        return std::pair{id, done["output"]["sha256"].get<std::string>()};
    };
    const auto [old_id, old_sha] = render(1);
    auto bytes = client.Get("/v1/renders/" + old_id + "/output");
    ASSERT_TRUE(bytes);
    ASSERT_EQ(bytes->status, 200);
    const std::string old_bytes = bytes->body;
    std::this_thread::sleep_for(std::chrono::seconds(2));
    const auto [young_id, young_sha] = render(2);
    ASSERT_NE(old_sha, young_sha);
    // Readers of the old output until it is gone: each gets all of it, or a 404 once the job
    // is forgotten; never a part, never a 500.
    std::atomic<bool> done{false};
    std::atomic<int> whole{0}, gone{0}, broken{0};
    std::thread reader([&] {
        auto mine = client_for(server.port());
        for (int i = 0; i < 2000 && !done; ++i) {
            auto got = mine.Get("/v1/renders/" + old_id + "/output");
            if (got && got->status == 200 && got->body == old_bytes) {
                ++whole;
            } else if (got && got->status == 404) {
                ++gone;
            } else {
                ++broken;
            }
        }
    });
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(8);
    bool swept = false;
    while (!swept && std::chrono::steady_clock::now() < deadline) {
        auto job = client.Get("/v1/renders/" + old_id);
        swept = job && job->status == 404;
        if (!swept) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    EXPECT_TRUE(swept) << "the old job is still there";
    // The young one, accepted two seconds later, is within its time.
    auto young = client.Get("/v1/renders/" + young_id);
    ASSERT_TRUE(young);
    EXPECT_EQ(young->status, 200);
    done = true;
    reader.join();
    EXPECT_GT(whole.load(), 0);
    EXPECT_EQ(broken.load(), 0);
    EXPECT_FALSE(std::filesystem::exists(dir / ("data/outputs/" + old_sha + ".png")));
    EXPECT_TRUE(std::filesystem::exists(dir / ("data/outputs/" + young_sha + ".png")));
    auto metrics = client.Get("/metrics");
    ASSERT_TRUE(metrics);
    EXPECT_NE(metrics->body.find("\ndiscreel_jobs_swept_total 1\n"), std::string::npos)
        << metrics->body;
}

TEST_F(ServeGLTest, ATokenGuardsEveryV1Route) {
    testing::write_file(dir / "token", "s3cret-token\n");
    ServeProcess server(bin, {"--data", dir / "data", "--token-file", dir / "token"}, log);
    auto client = client_for(server.port());
    const json body{{"scene", scene_text()}, {"output", "png"}};
    for (const httplib::Headers& headers :
         {httplib::Headers{}, httplib::Headers{{"Authorization", "Bearer s3cret-tokeN"}},
          httplib::Headers{{"Authorization", "Bearer s3cret-token2"}},
          httplib::Headers{{"Authorization", "s3cret-token"}}}) {
        auto refused = post(client, "/v1/validate", body, headers);
        ASSERT_TRUE(refused);
        EXPECT_EQ(refused->status, 401);
        EXPECT_EQ(refused->get_header_value("WWW-Authenticate"), "Bearer");
        auto get = client.Get("/v1/renders/0123456789abcdef0123456789abcdef", headers);
        ASSERT_TRUE(get);
        EXPECT_EQ(get->status, 401);
    }
    const httplib::Headers good{{"Authorization", "Bearer s3cret-token"}};
    auto ok = post(client, "/v1/validate", body, good);
    ASSERT_TRUE(ok);
    EXPECT_EQ(ok->status, 200);
    auto health = client.Get("/healthz");
    ASSERT_TRUE(health);
    EXPECT_EQ(health->status, 200);
}

TEST_F(ServeGLTest, AFloodOf40ClientsGets429WithRetryAfterAndLosesNothing) {
    ServeProcess server(bin, {"--data", dir / "data", "--workers", "2", "--max-queue", "4"}, log);
    std::vector<std::thread> clients;
    std::mutex mutex;
    std::vector<std::string> accepted;
    std::atomic<int> busy{0}, other{0};
    for (int c = 0; c < 40; ++c) {
        clients.emplace_back([&, c] {
            auto client = client_for(server.port());
            auto got = post(client, "/v1/renders",
                            json{{"scene", scene_text(100 + c)}, {"output", "png"}});
            if (got && got->status == 202) {
                std::lock_guard lock(mutex);
                accepted.push_back(json::parse(got->body)["id"]);
            } else if (got && got->status == 429 &&
                       std::stoi(got->get_header_value("Retry-After")) >= 1) {
                ++busy;
            } else {
                ++other;
                std::lock_guard lock(mutex);
                ADD_FAILURE() << (got ? std::to_string(got->status) + " " + got->body
                                      : httplib::to_string(got.error()));
            }
        });
    }
    for (auto& thread : clients) thread.join();
    EXPECT_EQ(other.load(), 0);
    EXPECT_GT(busy.load(), 0);
    EXPECT_EQ(accepted.size() + static_cast<std::size_t>(busy.load()), 40u);
    auto client = client_for(server.port());
    for (const std::string& id : accepted) {
        EXPECT_EQ(wait_final(client, id)["status"], "succeeded") << id;
    }
    auto metrics = client.Get("/metrics");
    ASSERT_TRUE(metrics);
    EXPECT_EQ(metric(metrics->body, "discreel_jobs_rejected_total"), std::to_string(busy.load()));
}

TEST_F(ServeGLTest, EveryAcceptedJobFinishesAfterSigkillAndRestart) {
    const std::string long_scene = scene_text(7, 6.0);
    const json clip{{"scene", long_scene}, {"output", "webm"}, {"size", "320x180"}};
    std::vector<std::string> ids;
    json warnings;   // of the last job, kept in the store
    {
        ServeProcess server(bin, {"--data", dir / "data"}, log);
        auto client = client_for(server.port());
        auto first = post(client, "/v1/renders", clip);
        ASSERT_TRUE(first);
        ASSERT_EQ(first->status, 202);
        ids.push_back(json::parse(first->body)["id"]);
        for (int i = 0; i < 2; ++i) {
            auto queued = post(client, "/v1/renders",
                               json{{"scene", scene_text(20 + i)}, {"output", "png"}});
            ASSERT_TRUE(queued);
            ASSERT_EQ(queued->status, 202);
            ids.push_back(json::parse(queued->body)["id"]);
        }
        auto warned = post(client, "/v1/renders", json{{"scene", fast_scene}, {"output", "png"}});
        ASSERT_TRUE(warned);
        ASSERT_EQ(warned->status, 202);
        ids.push_back(json::parse(warned->body)["id"]);
        warnings = json::parse(warned->body)["warnings"];
        ASSERT_EQ(warnings.size(), 1u);
        EXPECT_EQ(warnings[0]["line"], 4);
        // Killed while the clip is being rendered.
        const auto deadline = Clock::now() + std::chrono::seconds(30);
        while (Clock::now() < deadline) {
            auto got = client.Get("/v1/renders/" + ids[0]);
            if (got && json::parse(got->body)["progress"]["frames_done"] > 0) break;
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        const int status = server.stop(SIGKILL);
        ASSERT_TRUE(WIFSIGNALED(status));
    }
    ServeProcess server(bin, {"--data", dir / "data"}, log);
    auto client = client_for(server.port());
    for (const std::string& id : ids) {
        EXPECT_EQ(wait_final(client, id, 120)["status"], "succeeded") << id;
    }
    auto last = client.Get("/v1/renders/" + ids.back());
    ASSERT_TRUE(last);
    EXPECT_EQ(json::parse(last->body)["warnings"], warnings);
    auto output = client.Get("/v1/renders/" + ids[0] + "/output");
    ASSERT_TRUE(output);
    EXPECT_EQ(output->body, cli_render(dir, long_scene, {"--size", "320x180"}, "cli.webm"));
    // Nothing half-written is left beside the outputs.
    EXPECT_TRUE(testing::directory_entries(dir.path() / "data" / "tmp").empty());
}

TEST_F(ServeGLTest, ADiskFullFailsThatJobAndTheServerKeepsServing) {
    // Writes past 512 kB fail (EFBIG, as ENOSPC on a full disk): the job store's small writes
    // fit, a 1280x720 clip of 4 s does not.
    ServeProcess server(bin, {"--data", dir / "data"}, log, {"prlimit", "--fsize=524288"});
    auto client = client_for(server.port());
    auto big = post(client, "/v1/renders",
                    json{{"scene", scene_text(3, 4.0)}, {"output", "mkv"}, {"size", "1280x720"},
                         {"crf", 0}});
    ASSERT_TRUE(big);
    ASSERT_EQ(big->status, 202) << big->body;
    const json failed = wait_final(client, json::parse(big->body)["id"], 120);
    EXPECT_EQ(failed["status"], "failed");
    EXPECT_EQ(failed["output"], nullptr);
    const std::string message = failed["error"]["message"];
    EXPECT_NE(message.find("File too large"), std::string::npos) << message;
    EXPECT_EQ(message.find(dir.path().string()), std::string::npos) << "leaks a path: " << message;

    auto small = post(client, "/v1/renders", json{{"scene", scene_text(4)}, {"output", "png"}});
    ASSERT_TRUE(small);
    ASSERT_EQ(small->status, 202);
    EXPECT_EQ(wait_final(client, json::parse(small->body)["id"])["status"], "succeeded");
}

TEST_F(ServeGLTest, CancelAndTimeLimitEndJobsWithTheirReason) {
    ServeProcess server(bin, {"--data", dir / "data", "--job-timeout", "3"}, log);
    auto client = client_for(server.port());
    // A long clip runs; a still waits behind it.
    auto running = post(client, "/v1/renders",
                        json{{"scene", scene_text(5, 600.0)}, {"output", "mp4"}});
    auto queued = post(client, "/v1/renders", json{{"scene", scene_text(6)}, {"output", "png"}});
    ASSERT_TRUE(running && queued);
    ASSERT_EQ(running->status, 202);
    ASSERT_EQ(queued->status, 202);
    const std::string running_id = json::parse(running->body)["id"];
    const std::string queued_id = json::parse(queued->body)["id"];
    auto cancelled = client.Delete("/v1/renders/" + queued_id);
    ASSERT_TRUE(cancelled);
    EXPECT_EQ(cancelled->status, 200);
    EXPECT_EQ(json::parse(cancelled->body)["status"], "cancelled");
    const json timed_out = wait_final(client, running_id, 30);
    EXPECT_EQ(timed_out["status"], "failed");
    EXPECT_EQ(timed_out["error"]["message"],
              "the render took longer than the limit of 3 s (--job-timeout); nothing was kept");

    // A running job cancelled.
    auto again = post(client, "/v1/renders",
                      json{{"scene", scene_text(8, 600.0)}, {"output", "mp4"}});
    ASSERT_TRUE(again);
    const std::string again_id = json::parse(again->body)["id"];
    const auto deadline = Clock::now() + std::chrono::seconds(20);
    while (Clock::now() < deadline &&
           json::parse(client.Get("/v1/renders/" + again_id)->body)["status"] != "running") {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    auto stop = client.Delete("/v1/renders/" + again_id);
    ASSERT_TRUE(stop);
    EXPECT_EQ(stop->status, 200);
    EXPECT_EQ(json::parse(stop->body)["status"], "cancelled");
    EXPECT_TRUE(testing::directory_entries(dir.path() / "data" / "tmp").empty());
}

TEST_F(ServeGLTest, MalformedAndSlowRequestsDoNotHoldTheServer) {
    ServeProcess server(bin, {"--data", dir / "data"}, log);
    EXPECT_EQ(exchange(connect_to(server.port()), "HELLO THERE\r\n\r\n").rfind("HTTP/1.1 400", 0),
              0u);
    EXPECT_EQ(exchange(connect_to(server.port()),
                       "GET /" + std::string(10000, 'a') + " HTTP/1.1\r\n\r\n")
                  .rfind("HTTP/1.1 414", 0),
              0u);
    EXPECT_EQ(exchange(connect_to(server.port()),
                       "POST /v1/validate HTTP/1.1\r\nContent-Length: 99999999999\r\n\r\n")
                  .rfind("HTTP/1.1 413", 0),
              0u);
    // A client that stops half-way through its headers: others are served meanwhile, and the
    // server answers 408 when the head's time (5 s) is up.
    const int slow = connect_to(server.port());
    const auto started = Clock::now();
    const std::string partial = "GET /healthz HTTP/1.1\r\nHost: x\r\n";
    (void)send(slow, partial.data(), partial.size(), MSG_NOSIGNAL);
    auto client = client_for(server.port());
    auto health = client.Get("/healthz");
    ASSERT_TRUE(health);
    EXPECT_EQ(health->status, 200);
    char buffer[256];
    const ssize_t n = recv(slow, buffer, sizeof buffer, 0);
    const double waited = std::chrono::duration<double>(Clock::now() - started).count();
    close(slow);
    ASSERT_GT(n, 0);
    EXPECT_EQ(std::string(buffer, static_cast<std::size_t>(n)).rfind("HTTP/1.1 408", 0), 0u);
    EXPECT_GT(waited, 4.0);
    EXPECT_LT(waited, 9.0);
}

}  // namespace
}  // namespace discreel
