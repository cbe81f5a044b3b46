#pragma once
// The one place that includes the GL headers inside the render module.
// Debian's libOSMesa exports every GL entry point (glDrawArraysInstanced, glBlendFuncSeparate,
// ... ~1300 symbols) as a dispatch stub that forwards to the current context, so we link
// against them directly instead of loading pointers with OSMesaGetProcAddress. The binaries
// must not also link libGL, whose stubs would shadow these and dispatch to no context.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>   // includes GL/gl.h, which includes GL/glext.h
