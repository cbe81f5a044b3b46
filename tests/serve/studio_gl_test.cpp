// The studio's API end to end (docs/serve.md, "Studio"): previews that are `discreel render`'s
// stills byte for byte in any order of frames, going back from a checkpoint rather than from
// t = 0, the clip's contacts as `simulate --events` lists them, and the body under a pixel.
// A real server process on 127.0.0.1, stopped by pid; GL, as the server draws.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <future>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "serve_client.hpp"
#include "serve_process.hpp"
#include "test_support.hpp"

namespace discreel {
namespace {

using nlohmann::json;
using testing::client_for;
using testing::post;
using testing::read_file;
using testing::run_command;
using testing::ServeProcess;
using testing::TempDir;

const std::string bin = DISCREEL_BIN;

std::string config(const std::string& name) {
    return read_file(std::string(DISCREEL_SOURCE_DIR) + "/configs/" + name);
}

// POST /v1/studio/timeline on a thread and a connection of its own: the answer's status and
// body (-1 and nothing without an answer).
std::future<std::pair<int, std::string>> play_timeline(int port, json request) {
    return std::async(std::launch::async, [port, request = std::move(request)] {
        auto own = client_for(port);
        own.set_read_timeout(120, 0);
        auto answer = post(own, "/v1/studio/timeline", request);
        return answer ? std::pair{answer->status, answer->body} : std::pair{-1, std::string()};
    });
}

// Half an hour of the demo at `size`: half a minute of physics or more, far longer than a
// test's requests while its timeline plays.
json long_demo(const char* size = "160x90") {
    return {{"scene", config("demo.yaml")},
            {"size", size},
            {"set", {{"video.duration", 1800}}}};
}

// The timeline ends within 30 s, stopped: 409 with `message`.
void expect_stopped(std::future<std::pair<int, std::string>>& played,
                    const std::string& message) {
    ASSERT_EQ(played.wait_for(std::chrono::seconds(30)), std::future_status::ready);
    const auto [status, body] = played.get();
    EXPECT_EQ(status, 409) << body;
    EXPECT_EQ(json::parse(body)["error"]["message"], message);
}

// Frame `frame` of the request's scene previewed: 200.
void expect_preview(httplib::Client& client, json request, int frame) {
    request["frame"] = frame;
    auto shown = post(client, "/v1/studio/frame", request);
    ASSERT_TRUE(shown);
    ASSERT_EQ(shown->status, 200) << shown->body;
}

// Waits (10 s at most) until the server says `count` timelines are playing (/metrics).
void wait_for_timelines(httplib::Client& client, int count) {
    const std::string line = "\ndiscreel_studio_timelines " + std::to_string(count) + "\n";
    for (int tries = 0; tries < 400; ++tries) {
        auto metrics = client.Get("/metrics");
        if (metrics && metrics->body.find(line) != std::string::npos) return;
        std::this_thread::sleep_for(std::chrono::milliseconds(25));
    }
    FAIL() << "the studio never played " << count << " timelines at once";
}

class StudioGLTest : public ::testing::Test {
protected:
    TempDir dir;
    std::string log = dir / "serve.log";

    std::string cli(const std::string& scene, const std::vector<std::string>& options) {
        testing::write_file(dir / "cli.yaml", scene);
        std::vector<std::string> argv{bin, "render", dir / "cli.yaml", "-o", dir / "cli.png", "-q"};
        argv.insert(argv.end(), options.begin(), options.end());
        const auto run = run_command(argv);
        EXPECT_EQ(run.exit_code, 0) << run.err;
        return read_file(dir / "cli.png");
    }
};

TEST_F(StudioGLTest, APreviewIsTheCliStillInAnyOrderOfFrames) {
    ServeProcess server(bin, {"--data", dir / "data"}, log);
    auto client = client_for(server.port());
    const std::string scene = config("polygons.yaml");
    std::int64_t from_start = 0;
    // Forward, back past a checkpoint, the same frame again, and a time.
    for (const int frame : {40, 130, 100, 100, 7}) {
        SCOPED_TRACE(frame);
        auto answer = post(client, "/v1/studio/frame",
                           {{"scene", scene}, {"size", "320x180"}, {"frame", frame}});
        ASSERT_TRUE(answer);
        ASSERT_EQ(answer->status, 200) << answer->body;
        EXPECT_EQ(answer->get_header_value("Content-Type"), "image/png");
        EXPECT_EQ(answer->get_header_value("X-Discreel-Frame"), std::to_string(frame));
        EXPECT_EQ(answer->body,
                  cli(scene, {"--size", "320x180", "--frame", std::to_string(frame)}));
        const std::int64_t steps = std::stoll(answer->get_header_value("X-Discreel-Steps"));
        const int fps = std::stoi(answer->get_header_value("X-Discreel-Fps"));
        if (frame == 40) from_start = steps;
        // Going back steps on from the checkpoint a second (fps frames) before, at most.
        if (frame == 100 || frame == 7) {
            EXPECT_LE(steps, from_start * fps / 40);
        }
    }
    auto at = post(client, "/v1/studio/frame",
                   {{"scene", scene}, {"size", "320x180"}, {"at", 1.5}});
    ASSERT_TRUE(at);
    ASSERT_EQ(at->status, 200) << at->body;
    EXPECT_EQ(at->body, cli(scene, {"--size", "320x180", "--at", "1.5"}));
}

TEST_F(StudioGLTest, TheTimelineHasTheContactsSimulateLists) {
    ServeProcess server(bin, {"--data", dir / "data"}, log);
    auto client = client_for(server.port());
    const std::string scene = config("billiards.yaml");
    testing::write_file(dir / "s.yaml", scene);
    // The scene's 60 fps, and 25, at which its 960 Hz steps do not fall evenly on frames.
    for (const int fps : {60, 25}) {
        SCOPED_TRACE(fps);
        const json set = {{"video.fps", fps}, {"video.duration", 20}};
        const json request = {{"scene", scene}, {"size", "160x90"}, {"set", set}};
        // Previews first, forward and back: the timeline goes on from the session's
        // playback, and the frames played twice do not list their contacts twice.
        for (const int frame : {100, 7}) expect_preview(client, request, frame);
        // More previews, back and forth, while it plays: it goes on from what it recorded,
        // so each costs it at most a second of steps again (from the checkpoint before).
        auto played = play_timeline(server.port(), request);
        for (const int frame : {7, 15 * fps, 7, 6 * fps, 7}) {
            expect_preview(client, request, frame);
        }
        const auto [status, body] = played.get();
        ASSERT_EQ(status, 200) << body;
        const json timeline = json::parse(body);
        constexpr int rate = 960;
        EXPECT_LE(timeline["steps"].get<int>(), 20 * rate + 6 * rate);

        const auto run = run_command({bin, "simulate", dir / "s.yaml", "--set",
                                      "video.duration=20", "--events", dir / "e.csv"});
        ASSERT_EQ(run.exit_code, 0) << run.err;
        std::istringstream csv(read_file(dir / "e.csv"));
        std::string line;
        std::getline(csv, line);   // t,a,b,impulse,kind
        std::vector<std::pair<double, std::string>> contacts;
        while (std::getline(csv, line)) {
            if (line.size() < 8 || line.substr(line.size() - 8) != ",contact") continue;
            contacts.emplace_back(std::stod(line), line.substr(line.find(',') + 1));
        }
        ASSERT_FALSE(contacts.empty());
        const json& events = timeline["events"];
        ASSERT_EQ(events.size(), contacts.size());
        // Frame n shows step round(n rate / fps) (docs/scene-format.md, "Frames").
        const auto step_of_frame = [&](std::int64_t n) {
            return (2 * n * rate + fps) / (2 * fps);
        };
        for (std::size_t k = 0; k < contacts.size(); ++k) {
            EXPECT_NEAR(events[k]["t"].get<double>(), contacts[k].first, 1e-6) << k;
            EXPECT_EQ(contacts[k].second.rfind(events[k]["a"].get<std::string>() + ",", 0), 0U)
                << contacts[k].second;
            // The first frame that shows it.
            const std::int64_t frame = events[k]["frame"];
            const auto step = std::llround(contacts[k].first * rate);
            EXPECT_GE(step_of_frame(frame), step) << k;
            if (frame > 0) {
                EXPECT_LT(step_of_frame(frame - 1), step) << k;
            }
        }
    }
}

// Scrubbing back while the timeline plays: the timeline goes on from what it has recorded
// (from the checkpoint before it), not from where the preview left the playback.
TEST_F(StudioGLTest, APreviewWhileTheTimelinePlaysCostsItAtMostASecondAgain) {
    ServeProcess server(bin, {"--data", dir / "data"}, log);
    const int port = server.port();
    // Four minutes of the demo at 480 Hz: seconds of physics.
    const json request = {{"scene", config("demo.yaml")},
                          {"size", "160x90"},
                          {"set", {{"video.duration", 240}}}};
    auto played = play_timeline(port, request);
    auto client = client_for(port);
    wait_for_timelines(client, 1);
    for (const int frame : {3, 5}) {
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        expect_preview(client, request, frame);
    }
    const auto [status, body] = played.get();
    ASSERT_EQ(status, 200) << body;
    constexpr std::int64_t rate = 480;
    EXPECT_LE(json::parse(body)["steps"].get<std::int64_t>(), (240 + 2) * rate);
}

// A page being typed into asks for a timeline of each text it shows; once it shows another,
// the timeline of the text before stops rather than play its clip to the end, taking one of
// the studio's two places. Other tabs, the same scene and picks leave it playing.
TEST_F(StudioGLTest, ATabsTimelineStopsWhenTheTabGoesOnToAnotherScene) {
    ServeProcess server(bin, {"--data", dir / "data"}, log);
    const int port = server.port();
    json long_clip = long_demo();
    long_clip["tab"] = "page-a";
    auto played = play_timeline(port, long_clip);
    auto client = client_for(server.port());
    wait_for_timelines(client, 1);
    json same = long_clip;
    same["frame"] = 3;
    json other_tab = {{"scene", config("billiards.yaml")}, {"size", "160x90"}, {"tab", "page-b"}};
    for (const json& request : {same, other_tab}) {
        auto answer = post(client, "/v1/studio/frame", request);
        ASSERT_TRUE(answer);
        EXPECT_EQ(answer->status, 200) << answer->body;
    }
    // A pick is of the preview shown, which may be of an older text: it moves nothing on.
    json pick = other_tab;
    pick["tab"] = "page-a";
    pick["pick"] = {10, 10};
    auto picked = post(client, "/v1/studio/body", pick);
    ASSERT_TRUE(picked);
    EXPECT_EQ(picked->status, 200) << picked->body;
    // Half a second on, it still plays.
    ASSERT_EQ(played.wait_for(std::chrono::milliseconds(500)), std::future_status::timeout)
        << "the timeline ended before page-a went on";
    json moved = other_tab;
    moved["tab"] = "page-a";
    auto answer = post(client, "/v1/studio/frame", moved);
    ASSERT_TRUE(answer);
    EXPECT_EQ(answer->status, 200) << answer->body;
    expect_stopped(played, "stopped: the tab that asked for this timeline went on to another scene");
}

// Both of the studio's places taken by timelines: a tab's new text, even when it finds no
// place (429), stops that tab's timeline, which is what held one.
TEST_F(StudioGLTest, ABusyStudioStillStopsTheTabsOlderTimeline) {
    ServeProcess server(bin, {"--data", dir / "data"}, log);
    const int port = server.port();
    const auto timeline = [&](const char* tab, const char* size) {
        json request = long_demo(size);
        request["tab"] = tab;
        return play_timeline(port, request);
    };
    auto a = timeline("page-a", "160x90");
    auto b = timeline("page-b", "192x108");
    auto client = client_for(port);
    wait_for_timelines(client, 2);
    const auto new_text = [&](const char* tab) {
        auto answer = post(client, "/v1/studio/frame",
                           {{"scene", config("billiards.yaml")}, {"size", "160x90"}, {"tab", tab}});
        return answer ? answer->status : -1;
    };
    // Refused, or let in if the stopped timeline gave its place up first.
    const int first = new_text("page-a");
    EXPECT_TRUE(first == 429 || first == 200) << first;
    const std::string moved_on =
        "stopped: the tab that asked for this timeline went on to another scene";
    expect_stopped(a, moved_on);
    EXPECT_EQ(new_text("page-a"), 200);
    EXPECT_EQ(new_text("page-b"), 200);
    expect_stopped(b, moved_on);
}

// The studio keeps four sessions: one dropped for newer scenes stops its timeline.
TEST_F(StudioGLTest, ATimelineOfADroppedSessionStops) {
    ServeProcess server(bin, {"--data", dir / "data"}, log);
    const int port = server.port();
    auto played = play_timeline(port, long_demo());
    auto client = client_for(port);
    wait_for_timelines(client, 1);
    for (const char* size : {"96x54", "128x72", "192x108", "224x126"}) {
        auto answer = post(client, "/v1/studio/frame",
                           {{"scene", config("billiards.yaml")}, {"size", size}, {"frame", 0}});
        ASSERT_TRUE(answer);
        EXPECT_EQ(answer->status, 200) << answer->body;
    }
    expect_stopped(played, "stopped: the studio dropped this scene's session for newer scenes");
}

TEST_F(StudioGLTest, APickedPixelNamesTheBodyDrawnThere) {
    ServeProcess server(bin, {"--data", dir / "data"}, log);
    auto client = client_for(server.port());
    // Walls centred on (1.6, 0.9): the fitted camera puts that point at the frame's centre.
    const std::string scene =
        "version: 1\n"
        "video: {size: [320, 180], fps: 30, duration: 1}\n"
        "physics: {gravity: [0, 0]}\n"
        "walls:\n"
        "  - box: [[0, 0], [3.2, 1.8]]\n"
        "discs:\n"
        "  - id: cue\n"
        "    position: [1.6, 0.9]\n"
        "    velocity: [0.5, 0]\n"
        "    radius: 0.3\n"
        "    mass: 2\n";
    auto hit = post(client, "/v1/studio/body",
                    {{"scene", scene}, {"frame", 15}, {"pick", {175, 90}}});
    ASSERT_TRUE(hit);
    ASSERT_EQ(hit->status, 200) << hit->body;
    const json body = json::parse(hit->body)["body"];
    EXPECT_EQ(body["id"], "cue");
    EXPECT_EQ(body["index"], 0);
    EXPECT_EQ(body["line"], 7);   // "  - id: cue"
    EXPECT_EQ(body["kind"], "dynamic");
    EXPECT_DOUBLE_EQ(body["mass"].get<double>(), 2.0);
    EXPECT_NEAR(body["position"][0].get<double>(), 1.6 + 0.5 * 0.5, 1e-9);   // t = 15 / 30
    EXPECT_NEAR(body["velocity"][0].get<double>(), 0.5, 1e-12);
    EXPECT_DOUBLE_EQ(json::parse(hit->body)["t"].get<double>(), 0.5);

    auto miss = post(client, "/v1/studio/body",
                     {{"scene", scene}, {"frame", 15}, {"pick", {40, 90}}});
    ASSERT_TRUE(miss);
    ASSERT_EQ(miss->status, 200) << miss->body;
    EXPECT_EQ(json::parse(miss->body)["body"], nullptr);

    auto outside = post(client, "/v1/studio/body", {{"scene", scene}, {"pick", {320, 0}}});
    ASSERT_TRUE(outside);
    EXPECT_EQ(outside->status, 422);
    EXPECT_EQ(json::parse(outside->body)["error"]["message"],
              "the pixel (320, 0) is outside the 320x180 frame");
}

TEST_F(StudioGLTest, MistakesAreAnsweredAsTheRenderRoutesAnswerThem) {
    ServeProcess server(bin, {"--data", dir / "data"}, log);
    auto client = client_for(server.port());
    const auto message = [](const httplib::Result& r) {
        return json::parse(r->body)["error"]["message"].get<std::string>();
    };
    auto bad = post(client, "/v1/studio/frame", {{"scene", "video: {fps: 0}\n"}});
    ASSERT_TRUE(bad);
    EXPECT_EQ(bad->status, 422);
    EXPECT_EQ(json::parse(bad->body)["errors"][0]["line"], 1) << bad->body;
    auto output = post(client, "/v1/studio/frame",
                       {{"scene", config("demo.yaml")}, {"output", "mp4"}});
    ASSERT_TRUE(output);
    EXPECT_EQ(output->status, 400);
    EXPECT_EQ(message(output), "field 'output': the studio answers PNG previews; leave it out");
    auto pick = post(client, "/v1/studio/body", {{"scene", config("demo.yaml")}, {"pick", "here"}});
    ASSERT_TRUE(pick);
    EXPECT_EQ(pick->status, 400);
    EXPECT_EQ(message(pick), "field 'pick' must be [x, y], a pixel of the preview");
    auto tab = post(client, "/v1/studio/frame", {{"scene", config("demo.yaml")}, {"tab", "a b"}});
    ASSERT_TRUE(tab);
    EXPECT_EQ(tab->status, 400);
    EXPECT_EQ(message(tab),
              "field 'tab' must be 1 to 64 letters, digits, '-' or '_', the page's name for "
              "itself");
    auto past = post(client, "/v1/studio/frame",
                     {{"scene", config("demo.yaml")}, {"frame", 100000}});
    ASSERT_TRUE(past);
    EXPECT_EQ(past->status, 422) << past->body;
    auto get = client.Get("/v1/studio/frame");
    ASSERT_TRUE(get);
    EXPECT_EQ(get->status, 405);
    EXPECT_EQ(get->get_header_value("Allow"), "POST");
}

}  // namespace
}  // namespace discreel
