#pragma once
// An off-screen core-profile GL context (OSMesa, llvmpipe). Several may live in one thread:
// make_current() before issuing GL calls for the objects that belong to a context.
#include <memory>

#include "discreel/expected.hpp"

struct osmesa_context;

namespace discreel::render {

class OsmesaContext {
public:
    static Expected<OsmesaContext> create();

    Status make_current();
    // Unbinds it from the calling thread if it is current there.
    void release();

private:
    struct Deleter {
        void operator()(osmesa_context* context) const;
    };
    explicit OsmesaContext(osmesa_context* context) : context_(context) {}

    std::unique_ptr<osmesa_context, Deleter> context_;
    // OSMesaMakeCurrent insists on a colour buffer for the default framebuffer; we draw into
    // our own framebuffer object, so a single pixel is enough. Boxed so its address survives
    // moves of the context.
    std::unique_ptr<unsigned char[]> default_buffer_ = std::make_unique<unsigned char[]>(4);
};

}  // namespace discreel::render
