#pragma once
// The offscreen OpenGL renderer: OSMesa (llvmpipe), core profile 4.5,
// headless (no X, no GPU). ALGORITHMS.md §6.

#include <memory>

#include "hqview/render/renderer.h"

namespace hq {

// Creates an OSMesa core-profile 4.5 context and compiles the shaders.
// Each frame is drawn at 2x2 supersampling into an offscreen framebuffer and
// filtered down to the requested size. One renderer draws any number of
// frames, from one thread at a time (it makes its context current on the
// calling thread for each frame). Rasterizer threads follow LP_NUM_THREADS.
// Throws RenderError when the context cannot be created.
std::unique_ptr<Renderer> make_osmesa_renderer();

}  // namespace hq
