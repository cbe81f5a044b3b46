// discreel serve against a hostile client (docs/serve.md, "Limits and security"; docs/
// reliability.md): floods, slow and idle connections, runaway jobs, cross-site requests, range
// tricks, foreign --data directories, two servers on one store, a store that cannot be written.
// Real server processes on 127.0.0.1; every loop is bounded in count and time, every server
// stopped by pid. "GL": the servers render. Tests named PeakMemory... measure memory and are
// left out of the sanitizer run.
#include <signal.h>
#include <sqlite3.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <httplib.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "serve_client.hpp"
#include "serve_process.hpp"
#include "test_support.hpp"

namespace discreel {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::client_for;
using testing::connect_to;
using testing::exchange;
using testing::memory_kb;
using testing::post;
using testing::read_head;
using testing::readable;
using testing::run_command;
using testing::scene_text;
using testing::ServeProcess;
using testing::TempDir;
using testing::wait_final;
using Clock = std::chrono::steady_clock;

const std::string bin = DISCREEL_BIN;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string host_line(int port) { return "Host: 127.0.0.1:" + std::to_string(port) + "\r\n"; }

// Sends `head`, then `chunk` again and again until the server answers (or closes) or `limit`
// bytes have gone; the response's head.
std::string flood(int port, const std::string& head, const std::string& chunk,
                  std::size_t limit) {
    const int fd = connect_to(port);
    if (fd < 0) return "";
    (void)send(fd, head.data(), head.size(), MSG_NOSIGNAL);
    for (std::size_t sent = 0; sent < limit && !readable(fd); sent += chunk.size()) {
        if (send(fd, chunk.data(), chunk.size(), MSG_NOSIGNAL) < 0) break;
    }
    return read_head(fd);
}

class ServeHostileGLTest : public ::testing::Test {
protected:
    TempDir dir;
    std::string log = dir / "serve.log";
    std::string data = dir / "data";
};

TEST_F(ServeHostileGLTest, AHeaderFloodGets431AndCostsTheServerNoMemory) {
    testing::write_file(dir / "token", "s3cret\n");
    ServeProcess server(bin, {"--data", data, "--token-file", dir / "token"}, log);
    const long before = memory_kb(server.pid(), "VmHWM");
    // 3 million header lines were 550 MB before a 401; the head's limit (16 KiB) ends it.
    std::string lines;
    for (int i = 0; i < 4096; ++i) lines += "X-Flood: 1\r\n";
    const std::string refused =
        flood(server.port(),
              "GET /v1/renders/0123456789abcdef0123456789abcdef HTTP/1.1\r\n" +
                  host_line(server.port()),
              lines, std::size_t{48} << 20);
    EXPECT_EQ(refused.rfind("HTTP/1.1 431", 0), 0u) << refused;
    // Many short fields within the byte limit: the count limit (100).
    std::string many;
    for (int i = 0; i < 150; ++i) many.append("A").append(std::to_string(i)).append(": b\r\n");
    EXPECT_EQ(exchange(connect_to(server.port()),
                       "GET /healthz HTTP/1.1\r\n" + host_line(server.port()) + many + "\r\n")
                  .rfind("HTTP/1.1 431", 0),
              0u);
    const long after = memory_kb(server.pid(), "VmHWM");
    EXPECT_LT(after - before, 16 * 1024) << "peak grew from " << before << " to " << after
                                         << " kB";
    auto client = client_for(server.port());
    auto health = client.Get("/healthz");
    ASSERT_TRUE(health);
    EXPECT_EQ(health->status, 200);
}

TEST_F(ServeHostileGLTest, AChunkedBodyIsHeldToTheSizeLimit) {
    // --max-scene-bytes 1000: a body may be 2 x 1000 + 64 KiB = 67 536 bytes.
    ServeProcess server(bin, {"--data", data, "--max-scene-bytes", "1000"}, log);
    const long before = memory_kb(server.pid(), "VmHWM");
    std::string chunk = "1000\r\n" + std::string(4096, 'a') + "\r\n";
    const std::string refused = flood(
        server.port(),
        "POST /v1/validate HTTP/1.1\r\n" + host_line(server.port()) +
            "Content-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n",
        chunk, std::size_t{256} << 20);
    EXPECT_EQ(refused.rfind("HTTP/1.1 413", 0), 0u) << refused;
    // A chunk's size line that never ends (its extension grows without a CRLF): the bytes the
    // body limit does not count are held to the read buffer's room.
    const std::string endless = flood(
        server.port(),
        "POST /v1/validate HTTP/1.1\r\n" + host_line(server.port()) +
            "Content-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n1;x=",
        std::string(4096, 'a'), std::size_t{64} << 20);
    EXPECT_EQ(endless.rfind("HTTP/1.1 413", 0), 0u) << endless;
    const long after = memory_kb(server.pid(), "VmHWM");
    EXPECT_LT(after - before, 16 * 1024) << "peak grew from " << before << " to " << after
                                         << " kB";
    // Under the limit, chunked is read as any body is.
    const std::string scene = json{{"scene", scene_text()}}.dump();
    char size[16];
    std::snprintf(size, sizeof size, "%zx", scene.size());
    const std::string ok = exchange(
        connect_to(server.port()),
        "POST /v1/validate HTTP/1.1\r\n" + host_line(server.port()) +
            "Content-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n" + size +
            "\r\n" + scene + "\r\n0\r\n\r\n");
    EXPECT_EQ(ok.rfind("HTTP/1.1 200", 0), 0u) << ok;
}

TEST_F(ServeHostileGLTest, SlowAndIdleConnectionsDoNotStarveOthers) {
    ServeProcess server(bin, {"--data", data}, log);
    // 320 connections that never send a byte, 64 that send a header line a second.
    std::vector<int> idle, slow;
    for (int i = 0; i < 320; ++i) idle.push_back(connect_to(server.port(), 15));
    for (int i = 0; i < 64; ++i) {
        slow.push_back(connect_to(server.port(), 15));
        (void)send(slow.back(), "GET /healthz HTTP/1.1\r\n", 23, MSG_NOSIGNAL);
    }
    auto client = client_for(server.port());
    const auto started = Clock::now();
    for (int round = 0; round < 3; ++round) {
        for (const int fd : slow) (void)send(fd, "X-Slow: 1\r\n", 11, MSG_NOSIGNAL);
        const auto asked = Clock::now();
        auto health = client.Get("/healthz");
        ASSERT_TRUE(health) << httplib::to_string(health.error());
        EXPECT_EQ(health->status, 200);
        EXPECT_LT(seconds_since(asked), 0.5) << "round " << round;
        std::this_thread::sleep_for(std::chrono::seconds(1));
    }
    // The head's time (5 s from the connection) is up for the slow ones: 408, not a wait.
    int timed_out = 0;
    for (const int fd : slow) {
        timed_out += read_head(fd).rfind("HTTP/1.1 408", 0) == 0;
    }
    EXPECT_EQ(timed_out, 64);
    EXPECT_LT(seconds_since(started), 9.0);
    // The idle ones are closed without a word.
    int closed = 0;
    for (const int fd : idle) {
        char c = 0;
        closed += recv(fd, &c, 1, 0) == 0;
        close(fd);
    }
    EXPECT_EQ(closed, 320);
}

// 2 000 discs at 100 000 steps a second and 1 frame a second: one frame is 100 000 steps.
std::string heavy_scene(int seed) {
    return "# heavy " + std::to_string(seed) +
           "\nversion: 1\nvideo: {size: [64, 36], fps: 1, duration: 30}\n"
           "physics: {rate: 100000}\nwalls:\n  - box: [[0, 0], [64, 36]]\n"
           "discs:\n  - grid: {origin: [1, 1], count: [50, 40], spacing: [0.8, 0.8], "
           "radius: 0.3}\n";
}

TEST_F(ServeHostileGLTest, AJobStopsWithinAPhysicsStepOfItsDeadlineOrCancel) {
    std::string timed_out_id;
    {
        ServeProcess server(bin, {"--data", data, "--job-timeout", "2"}, log);
        auto client = client_for(server.port());
        const auto started = Clock::now();
        auto heavy = post(client, "/v1/renders", json{{"scene", heavy_scene(1)}, {"output", "mp4"}});
        ASSERT_TRUE(heavy);
        ASSERT_EQ(heavy->status, 202) << heavy->body;
        timed_out_id = json::parse(heavy->body)["id"];
        const json failed = wait_final(client, timed_out_id, 20);
        EXPECT_EQ(failed["status"], "failed");
        EXPECT_LT(seconds_since(started), 4.0);

        // A running job cancelled: within a second, as cancelled.
        auto second = post(client, "/v1/renders", json{{"scene", heavy_scene(2)}, {"output", "mp4"}});
        ASSERT_TRUE(second);
        const std::string id = json::parse(second->body)["id"];
        const auto deadline = Clock::now() + std::chrono::seconds(10);
        while (Clock::now() < deadline &&
               json::parse(client.Get("/v1/renders/" + id)->body)["status"] != "running") {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(300));   // inside its first frame
        const auto asked = Clock::now();
        auto cancelled = client.Delete("/v1/renders/" + id);
        ASSERT_TRUE(cancelled);
        EXPECT_EQ(cancelled->status, 200);
        EXPECT_EQ(json::parse(cancelled->body)["status"], "cancelled");
        EXPECT_LT(seconds_since(asked), 1.0);

        // SIGTERM while a heavy job runs: the server ends at once.
        auto third = post(client, "/v1/renders", json{{"scene", heavy_scene(3)}, {"output", "mp4"}});
        ASSERT_TRUE(third);
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
        const auto stopping = Clock::now();
        EXPECT_EQ(server.stop(SIGTERM), 0);
        EXPECT_LT(seconds_since(stopping), 2.0);
    }
    // The job that ran out of time stays failed: it is not rendered again after a restart.
    ServeProcess server(bin, {"--data", data, "--job-timeout", "2"}, log);
    auto client = client_for(server.port());
    auto job = client.Get("/v1/renders/" + timed_out_id);
    ASSERT_TRUE(job);
    EXPECT_EQ(json::parse(job->body)["status"], "failed");
    EXPECT_EQ(json::parse(job->body)["error"]["message"],
              "the render took longer than the limit of 2 s (--job-timeout); nothing was kept");
}

TEST_F(ServeHostileGLTest, AClosedEventStreamGivesItsSlotBackAtOnce) {
    ServeProcess server(bin, {"--data", data}, log);
    auto client = client_for(server.port());
    auto running = post(client, "/v1/renders", json{{"scene", heavy_scene(5)}, {"output", "mp4"}});
    ASSERT_TRUE(running);
    const std::string id = json::parse(running->body)["id"];
    const std::string ask = "GET /v1/renders/" + id + "/events HTTP/1.1\r\n" +
                            host_line(server.port()) + "\r\n";
    // Every slot (128) taken, then the clients go away.
    std::vector<int> streams;
    for (int i = 0; i < 128; ++i) {
        streams.push_back(connect_to(server.port()));
        (void)send(streams.back(), ask.data(), ask.size(), MSG_NOSIGNAL);
    }
    for (const int fd : streams) {
        char buffer[512];
        EXPECT_GT(recv(fd, buffer, sizeof buffer, 0), 0);   // the head and the first event
    }
    EXPECT_EQ(exchange(connect_to(server.port()), ask).rfind("HTTP/1.1 503", 0), 0u);
    for (const int fd : streams) close(fd);
    // Their slots are free within moments, not after the 15 s keep-alive comment.
    const auto started = Clock::now();
    std::string answer;
    while (seconds_since(started) < 2.0) {
        answer = exchange(connect_to(server.port()), ask);
        if (answer.rfind("HTTP/1.1 200", 0) == 0) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    EXPECT_EQ(answer.rfind("HTTP/1.1 200", 0), 0u) << answer;
    EXPECT_LT(seconds_since(started), 1.0);
}

TEST_F(ServeHostileGLTest, PeakMemoryOfConcurrentValidationIsBoundedAndGivenBack) {
    // 25 000 discs, 0.9 MB of YAML: a load takes about 90 MB at its peak.
    std::string scene = "version: 1\nvideo: {size: [320, 180], fps: 30, duration: 1}\n"
                        "walls:\n  - box: [[0, 0], [200, 200]]\ndiscs:\n";
    for (int i = 0; i < 158 && i * 158 < 25000; ++i) {
        for (int j = 0; j < 158 && i * 158 + j < 25000; ++j) {
            scene += "- {position: [" + std::to_string(1 + i) + ", " + std::to_string(1 + j) +
                     "], radius: 0.4}\n";
        }
    }
    ServeProcess server(bin, {"--data", data}, log);
    const long before = memory_kb(server.pid(), "VmRSS");
    const std::string body = json{{"scene", scene}}.dump();
    std::vector<std::thread> clients;
    std::atomic<int> ok{0};
    for (int c = 0; c < 8; ++c) {
        clients.emplace_back([&] {
            auto client = client_for(server.port());
            client.set_read_timeout(120);
            for (int r = 0; r < 2; ++r) {
                auto got = client.Post("/v1/validate", body, "application/json");
                ok += got && got->status == 200;
            }
        });
    }
    for (std::thread& t : clients) t.join();
    EXPECT_EQ(ok.load(), 16);
    // Two loads at a time (about 2 x 90 MB), not eight; and given back afterwards.
    const long peak = memory_kb(server.pid(), "VmHWM");
    const long after = memory_kb(server.pid(), "VmRSS");
    EXPECT_LT(peak - before, 300 * 1024) << "peak " << peak << " kB, from " << before;
    EXPECT_LT(after - before, 64 * 1024) << "kept " << after << " kB, from " << before;
}

TEST_F(ServeHostileGLTest, RangesAreOnePartOrTheWholeFile) {
    ServeProcess server(bin, {"--data", data}, log);
    auto client = client_for(server.port());
    auto accepted = post(client, "/v1/renders",
                         json{{"scene", scene_text()}, {"output", "png"}, {"size", "160x90"}});
    ASSERT_TRUE(accepted);
    const std::string id = json::parse(accepted->body)["id"];
    ASSERT_EQ(wait_final(client, id)["status"], "succeeded");
    const std::string path = "/v1/renders/" + id + "/output";
    auto whole = client.Get(path);
    ASSERT_TRUE(whole);
    const std::string file = whole->body;
    const std::string size = std::to_string(file.size());
    const auto ranged = [&](const std::string& range) {
        auto got = client.Get(path, {{"Range", range}});
        EXPECT_TRUE(got);
        return got ? std::tuple{got->status, got->get_header_value("Content-Range"), got->body}
                   : std::tuple{0, std::string(), std::string()};
    };
    // 1 100 ranges in one header: the whole file, once (they were 1 135 times its size).
    std::string many = "bytes=0-1";
    for (int i = 1; i < 1100; ++i) many += ",0-1";
    EXPECT_EQ(ranged(many), (std::tuple{200, std::string(), file}));
    // Overlapping and adjacent parts coalesce into one.
    EXPECT_EQ(ranged("bytes=0-9,5-19,20-29"),
              (std::tuple{206, "bytes 0-29/" + size, file.substr(0, 30)}));
    // Disjoint parts: the whole file, not a multipart body.
    EXPECT_EQ(ranged("bytes=0-1,100-101"), (std::tuple{200, std::string(), file}));
    // Bounds past the end are cut, a huge one included; past the end entirely: 416.
    EXPECT_EQ(ranged("bytes=5-18446744073709551615"), (std::tuple{200, std::string(), file}));
    EXPECT_EQ(ranged("bytes=5-999999999999"),
              (std::tuple{206, "bytes 5-" + std::to_string(file.size() - 1) + "/" + size,
                          file.substr(5)}));
    EXPECT_EQ(std::get<0>(ranged("bytes=" + size + "-")), 416);
    EXPECT_EQ(std::get<1>(ranged("bytes=" + size + "-")), "bytes */" + size);
    // Malformed: ignored, the whole file.
    EXPECT_EQ(ranged("bytes=9-3"), (std::tuple{200, std::string(), file}));
    EXPECT_EQ(ranged("lines=1-2"), (std::tuple{200, std::string(), file}));
}

TEST_F(ServeHostileGLTest, CrossSiteRequestsAreRefused) {
    ServeProcess server(bin, {"--data", data}, log);
    const int port = server.port();
    const std::string body = json{{"scene", scene_text()}, {"output", "png"}}.dump();
    const auto raw = [&](const std::string& host, const std::string& type) {
        return exchange(connect_to(port), "POST /v1/renders HTTP/1.1\r\nHost: " + host +
                                              "\r\nContent-Type: " + type +
                                              "\r\nContent-Length: " +
                                              std::to_string(body.size()) + "\r\n\r\n" + body);
    };
    const std::string self = "127.0.0.1:" + std::to_string(port);
    // A form a web page may send anywhere without asking: not JSON.
    EXPECT_EQ(raw(self, "text/plain").rfind("HTTP/1.1 415", 0), 0u);
    EXPECT_EQ(raw(self, "application/x-www-form-urlencoded").rfind("HTTP/1.1 415", 0), 0u);
    // DNS rebinding: a name that resolves here, but is not this server's.
    EXPECT_EQ(raw("evil.example:" + std::to_string(port), "application/json")
                  .rfind("HTTP/1.1 421", 0),
              0u);
    EXPECT_EQ(raw("127.0.0.1:1", "application/json").rfind("HTTP/1.1 421", 0), 0u);
    EXPECT_EQ(raw(self, "application/json; charset=utf-8").rfind("HTTP/1.1 202", 0), 0u);
    EXPECT_EQ(raw("localhost:" + std::to_string(port), "application/json")
                  .rfind("HTTP/1.1 202", 0),
              0u);
    // The page may not be framed by another site.
    auto client = client_for(port);
    auto page = client.Get("/");
    ASSERT_TRUE(page);
    EXPECT_EQ(page->get_header_value("X-Frame-Options"), "DENY");
    EXPECT_NE(page->get_header_value("Content-Security-Policy").find("frame-ancestors 'none'"),
              std::string::npos);
    // A name allowed on the command line.
    ServeProcess named(bin, {"--data", dir / "named", "--allow-host", "render.example"}, log);
    const std::string answer =
        exchange(connect_to(named.port()),
                 "GET /healthz HTTP/1.1\r\nHost: render.example:" + std::to_string(named.port()) +
                     "\r\n\r\n");
    EXPECT_EQ(answer.rfind("HTTP/1.1 200", 0), 0u) << answer;
}

// A run of `discreel serve` that must not start: its exit code and standard error.
testing::CommandResult refused_serve(const std::vector<std::string>& args) {
    std::vector<std::string> argv{bin, "serve"};
    if (std::find(args.begin(), args.end(), "--listen") == args.end()) {
        argv.insert(argv.end(), {"--listen", "127.0.0.1:0"});
    }
    argv.insert(argv.end(), args.begin(), args.end());
    return run_command(argv);
}

TEST_F(ServeHostileGLTest, ADataDirectoryOfOtherFilesIsRefusedAndKept) {
    const fs::path project = dir.path() / "project";
    fs::create_directories(project / "tmp" / "important");
    testing::write_file(project / "tmp" / "important" / "notes.txt", "mine\n");
    const auto foreign = refused_serve({"--data", project.string()});
    EXPECT_EQ(foreign.exit_code, 2);
    EXPECT_EQ(foreign.err, "discreel: --data '" + project.string() +
                               "' holds files but no job store (jobs.sqlite3): give serve a new "
                               "or empty directory, or the --data of an earlier server\n");
    EXPECT_EQ(testing::read_file(project / "tmp" / "important" / "notes.txt"), "mine\n");
    const auto empty = refused_serve({"--data", ""});
    EXPECT_EQ(empty.exit_code, 2);
    EXPECT_EQ(empty.err, "discreel: --data must name a directory; an empty one means none (use "
                         "--data . for this one)\n");
    // In a store of its own, the server cleans only what it left there itself.
    {
        ServeProcess server(bin, {"--data", data}, log);
    }
    fs::create_directories(fs::path(data) / "tmp" / "mine");
    testing::write_file(fs::path(data) / "tmp" / "mine" / "notes.txt", "mine\n");
    fs::create_directories(fs::path(data) / "tmp" / "0123456789abcdef0123456789abcdef");
    ServeProcess server(bin, {"--data", data}, log);
    EXPECT_EQ(testing::read_file(fs::path(data) / "tmp" / "mine" / "notes.txt"), "mine\n");
    EXPECT_FALSE(fs::exists(fs::path(data) / "tmp" / "0123456789abcdef0123456789abcdef"));
}

TEST_F(ServeHostileGLTest, ASecondServerOnOneStoreExits3AndTheFirstKeepsItsJobs) {
    ServeProcess first(bin, {"--data", data}, log);
    auto client = client_for(first.port());
    auto accepted = post(client, "/v1/renders",
                         json{{"scene", scene_text(3, 3.0)}, {"output", "webm"}});
    ASSERT_TRUE(accepted);
    const std::string id = json::parse(accepted->body)["id"];
    const auto second = refused_serve({"--data", data});
    EXPECT_EQ(second.exit_code, 3);
    EXPECT_EQ(second.err, "discreel: another discreel serve is using the store in '" + data +
                              "' (it holds serve.lock); stop it, or give this one another "
                              "--data\n");
    EXPECT_EQ(wait_final(client, id, 120)["status"], "succeeded");
}

TEST_F(ServeHostileGLTest, ACancelTheStoreRefusesLeavesTheJobQueued) {
    ServeProcess server(bin, {"--data", data}, log);
    auto client = client_for(server.port());
    // One long job holds the worker; the next one waits in the queue.
    auto running = post(client, "/v1/renders", json{{"scene", heavy_scene(4)}, {"output", "mp4"}});
    auto queued = post(client, "/v1/renders", json{{"scene", scene_text(5)}, {"output", "png"}});
    ASSERT_TRUE(running && queued);
    const std::string id = json::parse(queued->body)["id"];
    // Another writer holds the store (as a full disk would refuse the write).
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open((fs::path(data) / "jobs.sqlite3").c_str(), &db), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(db, "BEGIN EXCLUSIVE", nullptr, nullptr, nullptr), SQLITE_OK);
    auto refused = client.Delete("/v1/renders/" + id);
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 503);
    sqlite3_exec(db, "ROLLBACK", nullptr, nullptr, nullptr);
    sqlite3_close(db);
    // Still queued, in memory as in the store: cancelled by a second try.
    EXPECT_EQ(json::parse(client.Get("/v1/renders/" + id)->body)["status"], "queued");
    auto cancelled = client.Delete("/v1/renders/" + id);
    ASSERT_TRUE(cancelled);
    EXPECT_EQ(cancelled->status, 200);
    EXPECT_EQ(json::parse(cancelled->body)["status"], "cancelled");
    auto again = post(client, "/v1/renders", json{{"scene", scene_text(5)}, {"output", "png"}});
    ASSERT_TRUE(again);
    EXPECT_EQ(again->status, 202);
    EXPECT_EQ(json::parse(again->body)["status"], "queued");
}

TEST_F(ServeHostileGLTest, BadNumbersAndOptionsGetExactAnswers) {
    ServeProcess server(bin, {"--data", data}, log);
    auto client = client_for(server.port());
    auto huge = client.Post("/v1/validate",
                            "{\"scene\": \"version: 1\\n\", \"output\": \"png\", \"at\": 1e400}",
                            "application/json");
    ASSERT_TRUE(huge);
    EXPECT_EQ(huge->status, 400);
    EXPECT_NE(huge->body.find("a number in the body is out of range"), std::string::npos)
        << huge->body;
    // The documented curl example without a content type: told what to send.
    auto untyped = client.Post("/v1/validate", std::string(10000, ' '), "");
    ASSERT_TRUE(untyped);
    EXPECT_EQ(untyped->status, 415);
    EXPECT_EQ(untyped->body, "{\"error\":{\"message\":\"send the body as JSON, with "
                             "Content-Type: application/json\"}}\n");
    // Options: the listen address, the token file.
    EXPECT_EQ(refused_serve({"--listen", "::1:0"}).err,
              "discreel: --listen: write an IPv6 address in brackets, e.g. [::1]:0, got '::1:0'\n");
    // An IPv6 address in brackets: served, and printed in brackets (where the machine has ::1).
    try {
        ServeProcess v6(bin, {"--listen", "[::1]:0", "--data", dir / "v6"}, log);
        EXPECT_EQ(v6.first_line().rfind("listening on http://[::1]:", 0), 0u) << v6.first_line();
    } catch (const std::runtime_error& no_v6) {
        EXPECT_NE(std::string(no_v6.what()).find("cannot listen on [::1]:0"), std::string::npos)
            << no_v6.what();
    }
    testing::write_file(dir / "long", std::string(5000, 'a'));
    testing::write_file(dir / "nul", std::string("abc\0def", 7));
    for (const auto& [file, problem] :
         std::vector<std::pair<std::string, std::string>>{
             {dir / "long", "is over 4 KiB: it must hold one token"},
             {dir / "nul", "must hold one token of visible ASCII characters: no spaces, "
                           "control or NUL bytes"},
             {"/dev/zero", "is not a regular file"},
             {dir / "missing", "cannot be read: No such file or directory"}}) {
        const auto run = refused_serve({"--data", data + "2", "--token-file", file});
        EXPECT_EQ(run.exit_code, 2) << file;
        EXPECT_EQ(run.err, "discreel: the token file '" + file + "' " + problem + "\n");
    }
}

}  // namespace
}  // namespace discreel
