#include "osmesa_context.hpp"

#include "gl.hpp"

namespace discreel::render {

void OsmesaContext::Deleter::operator()(osmesa_context* context) const {
    // Not left current on this thread: its next context would be bound over a freed one.
    if (OSMesaGetCurrentContext() == context) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    OSMesaDestroyContext(context);
}

Expected<OsmesaContext> OsmesaContext::create() {
    // Core 3.3 is what the shaders need; Mesa hands back the newest core version it has.
    const int attribs[] = {
        OSMESA_FORMAT, OSMESA_RGBA,
        OSMESA_DEPTH_BITS, 0,
        OSMESA_STENCIL_BITS, 0,
        OSMESA_ACCUM_BITS, 0,
        OSMESA_PROFILE, OSMESA_CORE_PROFILE,
        OSMESA_CONTEXT_MAJOR_VERSION, 3,
        OSMESA_CONTEXT_MINOR_VERSION, 3,
        0,
    };
    osmesa_context* context = OSMesaCreateContextAttribs(attribs, nullptr);
    if (context == nullptr) {
        return Error{"cannot create an OSMesa GL 3.3 core-profile context"};
    }
    OsmesaContext result(context);
    if (Status current = result.make_current(); !current) {
        return current.error();
    }
    return result;
}

void OsmesaContext::release() {
    if (OSMesaGetCurrentContext() == context_.get()) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
}

Status OsmesaContext::make_current() {
    if (!OSMesaMakeCurrent(context_.get(), default_buffer_.get(), GL_UNSIGNED_BYTE, 1, 1)) {
        return Error{"cannot make the OSMesa context current"};
    }
    return {};
}

}  // namespace discreel::render
