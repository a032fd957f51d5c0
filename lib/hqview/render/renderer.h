#pragma once
// Renderer: draws a Scene seen through a Camera into an Image. The one
// implementation that touches OpenGL is the OSMesa backend
// (osmesa_renderer.h); tests may substitute their own.

#include <memory>

#include "hqview/image/image.h"
#include "hqview/render/camera.h"
#include "hqview/render/id_image.h"
#include "hqview/render/scene.h"

namespace hq {

class Renderer {
 public:
  virtual ~Renderer() = default;

  // A width x height image (both > 0) of the scene; the camera's aspect is
  // width / height. Throws RenderError on failure (bad size, GL error).
  virtual Image render(const Scene& scene, const Camera& camera, int width, int height) = 0;

  // The id image of an id-coded scene (every colour id_color of an id):
  // drawn as render draws it (same camera, depth test, sphere order,
  // overlay after a depth clear) but unlit and without blending, the
  // translucent sets left out (they hide nothing); each pixel the id seen
  // at most of its samples (ties: the first). Scalars are ignored. Empty
  // when the renderer draws no id images (callers then do without).
  virtual IdImage render_ids(const Scene& scene, const Camera& camera, int width, int height) {
    (void)scene, (void)camera, (void)width, (void)height;
    return {};
  }

  // A second renderer that draws the same images, for another thread (each
  // renderer is used by one thread at a time); nullptr when there is none.
  virtual std::unique_ptr<Renderer> sibling() const { return nullptr; }
};

}  // namespace hq
