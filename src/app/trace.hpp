#pragma once
// The CSV trace and contact-event files of SCENE_FORMAT.md. Numbers are written in the shortest
// form that reads back to the same double, so a trace can be compared bit for bit.
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "discreel/expected.hpp"
#include "discreel/physics.hpp"
#include "discreel/scene.hpp"

namespace discreel::app {

// A text file written under a temporary name and renamed onto its path by commit(); dropped
// without commit(), it removes the temporary file and leaves any existing file untouched.
class AtomicTextFile {
public:
    static Expected<AtomicTextFile> create(const std::string& path);
    AtomicTextFile(AtomicTextFile&&) noexcept;
    AtomicTextFile& operator=(AtomicTextFile&&) = delete;
    ~AtomicTextFile();

    void write(std::string_view text);
    Status commit();

private:
    AtomicTextFile(std::string path, std::string temp_path, std::FILE* file);
    std::string path_;
    std::string temp_path_;
    std::FILE* file_ = nullptr;
    bool failed_ = false;
};

class TraceWriter {
public:
    // frame,t,id,x,y,angle,vx,vy,omega,radius,mass — one row per disc per frame.
    static Expected<TraceWriter> create(const std::string& path, const scene::Scene& scene);
    void write_frame(int frame, double t, std::span<const physics::DiscState> discs);
    Status commit() { return file_.commit(); }

private:
    TraceWriter(AtomicTextFile file, const scene::Scene& scene);
    AtomicTextFile file_;
    const scene::Scene* scene_;
    std::string row_;
};

class EventWriter {
public:
    // t,a,b,impulse — one row per new contact; b is a disc id or wall:<index>.
    static Expected<EventWriter> create(const std::string& path, const scene::Scene& scene);
    void write(std::span<const physics::ContactEvent> events);
    Status commit() { return file_.commit(); }

private:
    EventWriter(AtomicTextFile file, const scene::Scene& scene);
    AtomicTextFile file_;
    const scene::Scene* scene_;
    std::string row_;
};

// Shortest round-trip decimal form of v ("0.1", "1e-09", "-3").
void append_number(std::string& out, double v);

}  // namespace discreel::app
