#include "vtkAccelVolumeDepthCopy.h"

#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

int vtkAccelVolumeReadDepthFormat()
{
  GLint sampleBuffers = 0;
  glGetIntegerv(GL_SAMPLE_BUFFERS, &sampleBuffers);
  if (sampleBuffers == 0)
  {
    return -1;
  }
  GLint readBinding = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readBinding);
  const GLenum depth = readBinding == 0 ? GL_DEPTH : GL_DEPTH_ATTACHMENT;
  const GLenum stencil = readBinding == 0 ? GL_STENCIL : GL_STENCIL_ATTACHMENT;
  GLint stencilObject = GL_NONE;
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, stencil, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &stencilObject);
  GLint stencilBits = 0;
  if (stencilObject != GL_NONE)
  {
    glGetFramebufferAttachmentParameteriv(
      GL_READ_FRAMEBUFFER, stencil, GL_FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE, &stencilBits);
  }
  GLint componentType = GL_NONE;
  GLint depthBits = 0;
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, depth, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &componentType);
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, depth, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &depthBits);
  while (glGetError() != GL_NO_ERROR)
  {
    // a query the framebuffer cannot answer leaves an error behind; the defaults stand
  }
  if (stencilBits > 0)
  {
    return vtkAccelVolumeDepthStencilFormat;
  }
  if (componentType == GL_FLOAT)
  {
    return vtkTextureObject::Float32;
  }
  return depthBits <= 16
    ? vtkTextureObject::Fixed16
    : (depthBits <= 24 ? vtkTextureObject::Fixed24 : vtkTextureObject::Fixed32);
}

bool vtkAccelVolumeAllocateDepth(vtkTextureObject* texture, int width, int height, int depthFormat)
{
  if (depthFormat == vtkAccelVolumeDepthStencilFormat)
  {
    return texture->AllocateDepthStencil(width, height);
  }
  return texture->AllocateDepth(
    width, height, depthFormat < 0 ? vtkTextureObject::Float32 : depthFormat);
}

void vtkAccelVolumeCopyReadDepth(vtkOpenGLRenderWindow* window, vtkTextureObject* texture,
  vtkOpenGLFramebufferObject* framebuffer, int depthFormat, int x, int y, int width, int height)
{
  if (depthFormat < 0)
  {
    texture->Activate();
    texture->CopyFromFrameBuffer(x, y, 0, 0, width, height);
    texture->Deactivate();
    return;
  }
  vtkOpenGLState* state = window->GetState();
  state->PushDrawFramebufferBinding();
  framebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  state->vtkglBlitFramebuffer(
    x, y, x + width, y + height, 0, 0, width, height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  state->PopDrawFramebufferBinding();
}

vtkAccelVolumeDepthReader::vtkAccelVolumeDepthReader() = default;
vtkAccelVolumeDepthReader::~vtkAccelVolumeDepthReader() = default;

bool vtkAccelVolumeDepthReader::Read(
  vtkOpenGLRenderWindow* window, const int lowerLeft[2], int width, int height, float* depth)
{
  vtkOpenGLState* state = window->GetState();
  state->vtkglPixelStorei(GL_PACK_ALIGNMENT, 1);
  const int format = vtkAccelVolumeReadDepthFormat();
  if (format < 0)
  {
    glReadPixels(lowerLeft[0], lowerLeft[1], width, height, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
    return glGetError() == GL_NO_ERROR;
  }
  if (!this->Resolved->GetHandle() || this->Format != format ||
    static_cast<int>(this->Resolved->GetWidth()) != width ||
    static_cast<int>(this->Resolved->GetHeight()) != height)
  {
    this->Resolved->SetContext(window);
    if (!vtkAccelVolumeAllocateDepth(this->Resolved, width, height, format))
    {
      return false;
    }
    this->Format = format;
    this->Framebuffer->SetContext(window);
    this->Framebuffer->SaveCurrentBindingsAndBuffers();
    this->Framebuffer->Bind();
    this->Framebuffer->AddDepthAttachment(this->Resolved);
    this->Framebuffer->RestorePreviousBindingsAndBuffers();
  }
  vtkAccelVolumeCopyReadDepth(
    window, this->Resolved, this->Framebuffer, format, lowerLeft[0], lowerLeft[1], width, height);
  state->PushReadFramebufferBinding();
  this->Framebuffer->Bind(GL_READ_FRAMEBUFFER);
  glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
  state->PopReadFramebufferBinding();
  return glGetError() == GL_NO_ERROR;
}

void vtkAccelVolumeDepthReader::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Framebuffer->ReleaseGraphicsResources(window);
  this->Resolved->ReleaseGraphicsResources(window);
  this->Format = -2;
}

vtkAccelVolumeWindowContext::vtkAccelVolumeWindowContext(vtkWindow* window)
{
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (gl && gl->GetGenericContext())
  {
    this->Window = gl;
    gl->PushContext();
  }
}

vtkAccelVolumeWindowContext::~vtkAccelVolumeWindowContext()
{
  if (this->Window)
  {
    this->Window->PopContext();
  }
}
