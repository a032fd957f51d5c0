#pragma once
// Renderer: draws a Scene seen through a Camera into an Image. The one
// implementation that touches OpenGL is the OSMesa backend
// (osmesa_renderer.h); tests may substitute their own.

#include <memory>

#include "hqview/image/image.h"
#include "hqview/render/camera.h"
#include "hqview/render/scene.h"

namespace hq {

class Renderer {
 public:
  virtual ~Renderer() = default;

  // A width x height image (both > 0) of the scene; the camera's aspect is
  // width / height. Throws RenderError on failure (bad size, GL error).
  virtual Image render(const Scene& scene, const Camera& camera, int width, int height) = 0;

  // A second renderer that draws the same images, for another thread (each
  // renderer is used by one thread at a time); nullptr when there is none.
  virtual std::unique_ptr<Renderer> sibling() const { return nullptr; }
};

}  // namespace hq
