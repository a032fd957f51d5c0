#pragma once
// The OpenGL and OSMesa entry points of the OSMesa renderer, looked up in
// libOSMesa when the first renderer is made (hq::SharedLibrary), not linked:
// a run that draws nothing (--no-render, batch's parent, --version) never
// loads Mesa and LLVM. Private to osmesa_renderer.cpp.

#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>

namespace hq {

// X(name): the function gl<name> (OSMesa<name> for the OSMESA list).
#define HQ_GL_FUNCTIONS(X)                                                                                        \
  X(AttachShader) X(BindBuffer) X(BindFramebuffer) X(BindRenderbuffer) X(BindVertexArray) X(BlendFuncSeparate)   \
  X(BufferData) X(CheckFramebufferStatus) X(Clear) X(ClearColor) X(ClearDepth) X(CompileShader) X(CreateProgram) \
  X(CreateShader) X(DeleteBuffers) X(DeleteFramebuffers) X(DeleteProgram) X(DeleteRenderbuffers) X(DeleteShader) \
  X(DeleteVertexArrays) X(DepthFunc) X(DepthMask) X(Disable) X(DisableVertexAttribArray) X(DrawElements)         \
  X(Enable) X(EnableVertexAttribArray) X(FramebufferRenderbuffer) X(GenBuffers) X(GenFramebuffers)               \
  X(GenRenderbuffers) X(GenVertexArrays) X(GetError) X(GetFloatv) X(GetIntegerv) X(GetProgramInfoLog)            \
  X(GetProgramiv) X(GetShaderInfoLog) X(GetShaderiv) X(GetUniformLocation) X(LineWidth) X(LinkProgram)           \
  X(PixelStorei) X(PolygonOffset) X(ReadPixels) X(RenderbufferStorage) X(ShaderSource) X(StencilFunc)          \
  X(StencilOp) X(Uniform1f) X(Uniform1i) X(Uniform3f) X(Uniform3fv) X(UniformMatrix4fv) X(UseProgram)           \
  X(VertexAttribPointer) X(Viewport)
#define HQ_OSMESA_FUNCTIONS(X) X(CreateContextAttribs) X(DestroyContext) X(MakeCurrent)

// gl.Clear(...) calls glClear; gl.MakeCurrent(...) calls OSMesaMakeCurrent.
// decltype of the declared prototypes: the types without linking them.
struct GlApi {
#define HQ_GL_MEMBER(name) decltype(&::gl##name) name = nullptr;
#define HQ_OSMESA_MEMBER(name) decltype(&::OSMesa##name) name = nullptr;
  HQ_GL_FUNCTIONS(HQ_GL_MEMBER)
  HQ_OSMESA_FUNCTIONS(HQ_OSMESA_MEMBER)
#undef HQ_GL_MEMBER
#undef HQ_OSMESA_MEMBER
};

// The entry points, loaded once per process (thread-safe). Throws
// RenderError naming the library or the missing function when libOSMesa
// cannot be loaded or lacks one.
const GlApi& gl_api();

}  // namespace hq
