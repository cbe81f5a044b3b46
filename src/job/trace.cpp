#include "trace.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace discreel::job {

Expected<TraceWriter> TraceWriter::create(const std::string& path, const scene::Scene& scene) {
    auto file = AtomicTextFile::create(path);
    if (!file) return file.error();
    return TraceWriter(std::move(*file), scene);
}

TraceWriter::TraceWriter(AtomicTextFile file, const scene::Scene& scene)
    : file_(std::move(file)), scene_(&scene) {
    file_.write("frame,t,id,x,y,angle,vx,vy,omega,radius,mass,inertia\n");
    for (const scene::Body& d : scene.bodies) bodies_.push_back(&d);
}

void TraceWriter::write_frame(int frame, double t, std::span<const physics::BodyState> discs,
                              std::size_t respawns) {
    for (; respawns_ < std::min(respawns, scene_->respawns.size()); ++respawns_) {
        const scene::Respawn& r = scene_->respawns[respawns_];
        for (std::size_t k = 0; k < r.bodies.size() && r.first + k < bodies_.size(); ++k) {
            bodies_[r.first + k] = &r.bodies[k];
        }
    }
    for (std::size_t i = 0; i < discs.size(); ++i) {
        const scene::Body& def = *bodies_[i];
        const physics::BodyState& s = discs[i];
        row_.clear();
        row_ += std::to_string(frame);
        row_ += ',';
        append_number(row_, t);
        row_ += ',';
        row_ += def.id;
        for (double v : {s.position.x, s.position.y, s.angle, s.velocity.x, s.velocity.y,
                         s.angular_velocity, def.radius, def.is_static ? 0.0 : def.mass,
                         def.is_static ? 0.0 : def.inertia}) {
            row_ += ',';
            append_number(row_, v);
        }
        row_ += '\n';
        file_.write(row_);
    }
}

Expected<JointWriter> JointWriter::create(const std::string& path, const scene::Scene& scene) {
    auto file = AtomicTextFile::create(path);
    if (!file) return file.error();
    return JointWriter(std::move(*file), scene);
}

JointWriter::JointWriter(AtomicTextFile file, const scene::Scene& scene)
    : file_(std::move(file)), scene_(&scene) {
    file_.write("frame,t,joint,ax,ay,bx,by,force,torque\n");
}

void JointWriter::write_frame(int frame, double t, std::span<const physics::JointState> joints) {
    for (std::size_t k = 0; k < joints.size(); ++k) {
        const physics::JointState& j = joints[k];
        row_.clear();
        row_ += std::to_string(frame);
        row_ += ',';
        append_number(row_, t);
        row_ += ',';
        row_ += k < scene_->joint_ids.size() ? scene_->joint_ids[k] : std::to_string(k);
        for (double v : {j.anchor_a.x, j.anchor_a.y, j.anchor_b.x, j.anchor_b.y,
                         std::hypot(j.force.x, j.force.y), j.torque}) {
            row_ += ',';
            append_number(row_, v);
        }
        row_ += '\n';
        file_.write(row_);
    }
}

Expected<EventWriter> EventWriter::create(const std::string& path, const scene::Scene& scene) {
    auto file = AtomicTextFile::create(path);
    if (!file) return file.error();
    return EventWriter(std::move(*file), scene);
}

EventWriter::EventWriter(AtomicTextFile file, const scene::Scene& scene)
    : file_(std::move(file)), scene_(&scene) {
    file_.write("t,a,b,impulse,kind\n");
}

void EventWriter::write(std::span<const physics::ContactEvent> events) {
    for (const physics::ContactEvent& e : events) {
        row_.clear();
        append_number(row_, e.t);
        row_ += ',';
        row_ += scene_->bodies[e.a].id;
        row_ += ',';
        if (e.other_kind == physics::ContactEvent::Other::wall) {
            row_ += "wall:" + std::to_string(e.other);
        } else {
            row_ += scene_->bodies[e.other].id;
        }
        row_ += ',';
        append_number(row_, e.impulse);
        row_ += e.kind == physics::ContactEvent::Kind::begin ? ",begin\n"
                : e.kind == physics::ContactEvent::Kind::end ? ",end\n"
                                                             : ",contact\n";
        file_.write(row_);
    }
}

}  // namespace discreel::job
