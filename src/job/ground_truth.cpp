#include "ground_truth.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "discreel/encode.hpp"
#include "discreel/printable.hpp"

namespace discreel::job {
namespace {

std::string hex_color(const scene::Color& c) {
    char text[10];
    std::snprintf(text, sizeof text, "#%02x%02x%02x%02x", c.r, c.g, c.b, c.a);
    return text;
}

// Ids are names the loader checked (letters, digits, '_', '-', '.'), but a JSON string stays
// one whatever it holds.
void append_string(std::string& out, const std::string& text) {
    out += '"';
    for (const char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
            out += escaped;
        } else {
            out += c;
        }
    }
    out += '"';
}

void append_point(std::string& out, Vec2 p) {
    out += '[';
    append_number(out, p.x);
    out += ", ";
    append_number(out, p.y);
    out += ']';
}

// "circle", "capsule", "box" (an axis-aligned rectangle about the centroid) or "polygon".
const char* kind_of(const scene::Body& body) {
    if (!body.shape || body.shape->vertices.size() == 1) return "circle";
    const auto& v = body.shape->vertices;
    if (v.size() == 2) return "capsule";
    if (v.size() == 4) {
        const bool rectangle = v[0].x == v[3].x && v[1].x == v[2].x && v[0].y == v[1].y &&
                               v[2].y == v[3].y && v[0].x == -v[1].x && v[0].y == -v[3].y;
        if (rectangle) return "box";
    }
    return "polygon";
}

void append_body(std::string& out, const scene::Body& body, std::size_t index, double from,
                 double to) {
    out += "    {\"id\": ";
    append_string(out, body.id);
    const std::string kind = kind_of(body);
    out += ", \"index\": " + std::to_string(index) + ", \"kind\": \"" + kind + "\"";
    if (kind == "circle") {
        out += ", \"radius\": ";
        append_number(out, body.shape ? body.shape->radius : body.radius);
    } else if (kind == "capsule") {
        const auto& v = body.shape->vertices;
        out += ", \"length\": ";
        append_number(out, std::hypot(v[1].x - v[0].x, v[1].y - v[0].y));
        out += ", \"radius\": ";
        append_number(out, body.shape->radius);
    }
    if (body.shape && kind != "circle") {
        out += ", \"vertices\": [";
        for (std::size_t k = 0; k < body.shape->vertices.size(); ++k) {
            if (k > 0) out += ", ";
            append_point(out, body.shape->vertices[k]);
        }
        out += "]";
    }
    out += ", \"rounding\": ";
    append_number(out, body.shape && kind != "capsule" && kind != "circle" ? body.shape->radius
                                                                           : 0.0);
    out += ", \"color\": \"" + hex_color(body.color) + "\", \"mass\": ";
    append_number(out, body.is_static ? 0.0 : body.mass);
    out += ", \"inertia\": ";
    append_number(out, body.is_static ? 0.0 : body.inertia);
    out += std::string(", \"static\": ") + (body.is_static ? "true" : "false") +
           ", \"kinematic\": " + (body.kinematic ? "true" : "false") + ", \"from\": ";
    append_number(out, from);
    out += ", \"to\": ";
    append_number(out, to);
    out += "}";
}

}  // namespace

std::string shapes_json(const scene::Scene& scene) {
    const double end = scene.video.duration;
    // Each body slot's sets: the scene's, then each respawn that replaces it, in time order.
    struct Set {
        const scene::Body* body;
        double from;
    };
    std::vector<std::vector<Set>> sets(scene.bodies.size());
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) sets[i].push_back({&scene.bodies[i], 0});
    for (const scene::Respawn& r : scene.respawns) {
        for (std::size_t k = 0; k < r.bodies.size() && r.first + k < sets.size(); ++k) {
            sets[r.first + k].push_back({&r.bodies[k], r.at});
        }
    }
    // Entries in the order they appear: by start, then index.
    struct Entry {
        double from, to;
        std::size_t index;
        const scene::Body* body;
    };
    std::vector<Entry> entries;
    for (std::size_t i = 0; i < sets.size(); ++i) {
        for (std::size_t k = 0; k < sets[i].size(); ++k) {
            const double to = k + 1 < sets[i].size() ? sets[i][k + 1].from : end;
            entries.push_back({sets[i][k].from, to, i, sets[i][k].body});
        }
    }
    std::stable_sort(entries.begin(), entries.end(),
                     [](const Entry& a, const Entry& b) { return a.from < b.from; });
    std::string out = "{\n  \"bodies\": [\n";
    for (std::size_t e = 0; e < entries.size(); ++e) {
        append_body(out, *entries[e].body, entries[e].index, entries[e].from, entries[e].to);
        out += e + 1 < entries.size() ? ",\n" : "\n";
    }
    out += "  ],\n  \"walls\": [\n";
    for (std::size_t w = 0; w < scene.walls.size(); ++w) {
        const scene::Wall& wall = scene.walls[w];
        out += "    {\"index\": " + std::to_string(w) + ", \"kind\": \"" +
               (wall.shape == scene::Wall::Shape::box ? "box" : "segment") + "\", \"a\": ";
        append_point(out, wall.a);
        out += ", \"b\": ";
        append_point(out, wall.b);
        out += ", \"thickness\": ";
        append_number(out, wall.thickness);
        out += ", \"color\": \"" + hex_color(wall.color) + "\"}";
        out += w + 1 < scene.walls.size() ? ",\n" : "\n";
    }
    out += "  ]\n}\n";
    return out;
}

ViewWriter::ViewWriter(const GroundTruthPaths& paths, const scene::Scene& scene)
    : scene_(&scene), masks_(paths.masks) {}

Expected<ViewWriter> ViewWriter::open(const GroundTruthPaths& paths, const scene::Scene& scene) {
    ViewWriter writer(paths, scene);
    if (paths.camera) {
        auto file = AtomicTextFile::create(*paths.camera);
        if (!file) return file.error();
        writer.camera_.emplace(std::move(*file));
        writer.camera_->write("frame,t,m00,m01,m02,m10,m11,m12,width,height,pixels_per_metre\n");
    }
    if (paths.boxes) {
        auto file = AtomicTextFile::create(*paths.boxes);
        if (!file) return file.error();
        writer.boxes_.emplace(std::move(*file));
        writer.boxes_->write("frame,id,x0,y0,x1,y1,pixels\n");
    }
    return writer;
}

Status ViewWriter::record(int frame, double t, const render::FrameScene& view) {
    const int width = scene_->video.width, height = scene_->video.height;
    if (camera_) {
        const render::PixelTransform m = render::pixel_transform(view.camera, width, height);
        row_ = std::to_string(frame);
        for (const double v : {t, m.m00, m.m01, m.m02, m.m10, m.m11, m.m12}) {
            row_ += ',';
            append_number(row_, v);
        }
        row_ += ',' + std::to_string(width) + ',' + std::to_string(height) + ',';
        append_number(row_, m.pixels_per_metre);
        row_ += '\n';
        camera_->write(row_);
    }
    if (!masks_ && !boxes_) return {};
    const std::vector<std::uint16_t> ids = render::draw_mask(view, width, height);
    if (masks_) {
        char name[32];
        std::snprintf(name, sizeof name, "/mask_%05d.png", frame);
        auto file = encode::prepare_png_gray16(*masks_ + name, {width, height, ids});
        if (!file) return file.error();
        mask_files_.push_back(std::move(*file));
    }
    if (boxes_) {
        struct Box {
            int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
            std::int64_t pixels = 0;
        };
        std::vector<Box> boxes(scene_->bodies.size());
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const std::uint16_t id =
                    ids[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                        static_cast<std::size_t>(x)];
                if (id == 0 || id == render::wall_mask_id || id > boxes.size()) continue;
                Box& b = boxes[id - 1];
                if (b.pixels++ == 0) {
                    b = {x, y, x, y, 1};
                    continue;
                }
                b.x0 = std::min(b.x0, x);
                b.x1 = std::max(b.x1, x);
                b.y1 = y;   // rows come in order
            }
        }
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            const Box& b = boxes[i];
            if (b.pixels == 0) continue;
            row_ = std::to_string(frame) + ',' + printable(scene_->bodies[i].id) + ',' +
                   std::to_string(b.x0) + ',' + std::to_string(b.y0) + ',' +
                   std::to_string(b.x1) + ',' + std::to_string(b.y1) + ',' +
                   std::to_string(b.pixels) + '\n';
            boxes_->write(row_);
        }
    }
    return {};
}

Status ViewWriter::seal() {
    if (camera_) {
        if (Status s = camera_->seal(); !s) return s;
    }
    if (boxes_) {
        if (Status s = boxes_->seal(); !s) return s;
    }
    return {};
}

std::vector<OutputFile*> ViewWriter::files() {
    std::vector<OutputFile*> files;
    if (camera_) files.push_back(&camera_->file());
    if (boxes_) files.push_back(&boxes_->file());
    for (OutputFile& mask : mask_files_) files.push_back(&mask);
    return files;
}

}  // namespace discreel::job
