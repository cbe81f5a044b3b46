#pragma once
// The CSV trace, contact-event and joint files (docs/cli.md, "Trace, events and joints").
// Numbers are written in the shortest form that reads back to the same double, so a trace can
// be compared bit for bit.
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "discreel/atomic_text_file.hpp"
#include "discreel/expected.hpp"
#include "discreel/physics.hpp"
#include "discreel/printable.hpp"
#include "discreel/scene.hpp"

namespace discreel::job {

class TraceWriter {
public:
    // frame,t,id,x,y,angle,vx,vy,omega,radius,mass,inertia — one row per body per frame;
    // radius is a shape's bounding radius.
    static Expected<TraceWriter> create(const std::string& path, const scene::Scene& scene);
    // `respawns`: how many of the scene's respawns the world has carried out (their bodies'
    // radius, mass and inertia are the ones written from then on).
    void write_frame(int frame, double t, std::span<const physics::BodyState> discs,
                     std::size_t respawns = 0);
    AtomicTextFile& file() { return file_; }

private:
    TraceWriter(AtomicTextFile file, const scene::Scene& scene);
    AtomicTextFile file_;
    const scene::Scene* scene_;
    std::vector<const scene::Body*> bodies_;   // each body's current definition
    std::size_t respawns_ = 0;
    std::string row_;
};

class JointWriter {
public:
    // frame,t,joint,ax,ay,bx,by,force,torque — one row per joint per frame: its anchors in
    // the world (m), the size of its reaction force (N) and its torque (N m) in the last step;
    // joint is the joint's id, or its index.
    static Expected<JointWriter> create(const std::string& path, const scene::Scene& scene);
    void write_frame(int frame, double t, std::span<const physics::JointState> joints);
    AtomicTextFile& file() { return file_; }

private:
    JointWriter(AtomicTextFile file, const scene::Scene& scene);
    AtomicTextFile file_;
    const scene::Scene* scene_;
    std::string row_;
};

class EventWriter {
public:
    // t,a,b,impulse,kind — one row per new contact (kind `contact`) and per overlap of a sensor
    // that began or ended (`begin`, `end`, impulse 0); b is a body id or wall:<index>.
    static Expected<EventWriter> create(const std::string& path, const scene::Scene& scene);
    void write(std::span<const physics::ContactEvent> events);
    AtomicTextFile& file() { return file_; }

private:
    EventWriter(AtomicTextFile file, const scene::Scene& scene);
    AtomicTextFile file_;
    const scene::Scene* scene_;
    std::string row_;
};

}  // namespace discreel::job
