#include "trace.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "test_support.hpp"

namespace discreel::job {
namespace {

std::string number(double v) {
    std::string s;
    append_number(s, v);
    return s;
}

TEST(TraceNumberTest, ShortestForm) {
    EXPECT_EQ(number(0.1), "0.1");
    EXPECT_EQ(number(-3.0), "-3");
    EXPECT_EQ(number(0.0), "0");
    EXPECT_EQ(number(1e-9), "1e-09");
}

TEST(TraceNumberTest, ReadsBackBitForBit) {
    std::uint64_t state = 0x9e3779b97f4a7c15ULL;
    for (int i = 0; i < 10000; ++i) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        double v = 0;
        std::memcpy(&v, &state, sizeof v);
        if (!std::isfinite(v)) continue;
        const std::string text = number(v);
        const double back = std::strtod(text.c_str(), nullptr);
        EXPECT_EQ(std::memcmp(&v, &back, sizeof v), 0) << text;
    }
}

scene::Body body(const std::string& id, double radius, double mass, double inertia,
                 bool is_static) {
    scene::Body d;
    d.id = id;
    d.radius = radius;
    d.mass = mass;
    d.inertia = inertia;
    d.is_static = is_static;
    return d;
}

// Each row carries the body's inertia (0, like its mass, for a static body), and a respawned
// body's radius, mass and inertia from the frame its respawn has been carried out.
TEST(TraceWriterTest, InertiaColumnAndRespawnedDefinitions) {
    testing::TempDir dir;
    scene::Scene scene;
    scene.bodies.push_back(body("peg", 0.5, 2, 0, true));
    scene.bodies.push_back(body("rock.0", 0.25, 1.5, 0.125, false));
    scene::Respawn respawn;
    respawn.at = 1;
    respawn.first = 1;
    respawn.bodies.push_back(body("rock.0", 0.75, 3, 0.5, false));
    scene.respawns.push_back(respawn);

    auto trace = TraceWriter::create(dir / "t.csv", scene);
    ASSERT_TRUE(trace);
    std::vector<physics::BodyState> states(2);
    states[1].position = {1, 2};
    states[1].angle = 0.5;
    states[1].angular_velocity = -3;
    trace->write_frame(0, 0, states, 0);
    trace->write_frame(1, 0.5, states, 0);
    trace->write_frame(2, 1, states, 1);
    ASSERT_TRUE(trace->file().commit());
    EXPECT_EQ(testing::read_file(dir / "t.csv"),
              "frame,t,id,x,y,angle,vx,vy,omega,radius,mass,inertia\n"
              "0,0,peg,0,0,0,0,0,0,0.5,0,0\n"
              "0,0,rock.0,1,2,0.5,0,0,-3,0.25,1.5,0.125\n"
              "1,0.5,peg,0,0,0,0,0,0,0.5,0,0\n"
              "1,0.5,rock.0,1,2,0.5,0,0,-3,0.25,1.5,0.125\n"
              "2,1,peg,0,0,0,0,0,0,0.5,0,0\n"
              "2,1,rock.0,1,2,0.5,0,0,-3,0.75,3,0.5\n");
}

}  // namespace
}  // namespace discreel::job
