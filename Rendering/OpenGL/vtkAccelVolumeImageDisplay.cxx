// vtkAccelVolumeImageDisplay: shows the CPU ray caster's image in the OpenGL scene.
#include "vtkAccelVolumeImageDisplay.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>

#include "AccelVolumeImageFS.h"
#include "AccelVolumeResolveVS.h"

vtkAccelVolumeImageDisplay::vtkAccelVolumeImageDisplay() = default;

vtkAccelVolumeImageDisplay::~vtkAccelVolumeImageDisplay() = default;

bool vtkAccelVolumeImageDisplay::Draw(vtkOpenGLRenderWindow* window, const int lowerLeft[2],
  int width, int height, int imageWidth, int imageHeight, const float* rgba)
{
  vtkOpenGLState* state = window->GetState();
  state->Push();
  this->Image->SetContext(window);
  state->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  bool ok = this->Image->GetHandle() &&
      this->Image->GetWidth() == static_cast<unsigned>(imageWidth) &&
      this->Image->GetHeight() == static_cast<unsigned>(imageHeight)
    ? true
    : this->Image->Create2D(imageWidth, imageHeight, 4, VTK_FLOAT, false);
  if (ok)
  {
    this->Image->Activate();
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, imageWidth, imageHeight, GL_RGBA, GL_FLOAT, rgba);
    this->Image->SetWrapS(vtkTextureObject::ClampToEdge);
    this->Image->SetWrapT(vtkTextureObject::ClampToEdge);
    this->Image->SetMinificationFilter(vtkTextureObject::Linear);
    this->Image->SetMagnificationFilter(vtkTextureObject::Linear);
    this->Image->SendParameters();
    vtkShaderProgram* program =
      window->GetShaderCache()->ReadyShaderProgram(AccelVolumeResolveVS, AccelVolumeImageFS, "");
    ok = program != nullptr;
    if (ok)
    {
      state->vtkglViewport(lowerLeft[0], lowerLeft[1], width, height);
      state->vtkglDisable(GL_DEPTH_TEST);
      state->vtkglDepthMask(GL_FALSE);
      state->vtkglEnable(GL_BLEND);
      state->vtkglBlendEquation(GL_FUNC_ADD);
      state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
      program->SetUniformi("image", this->Image->GetTextureUnit());
      const float origin[2] = { static_cast<float>(lowerLeft[0]),
        static_cast<float>(lowerLeft[1]) };
      const float size[2] = { static_cast<float>(width), static_cast<float>(height) };
      program->SetUniform2f("viewportOrigin", origin);
      program->SetUniform2f("viewportSize", size);
      this->Array->Bind();
      glDrawArrays(GL_TRIANGLES, 0, 3);
      this->Array->Release();
    }
    this->Image->Deactivate();
  }
  state->Pop();
  return ok;
}

bool vtkAccelVolumeImageDisplay::ReadDepth(
  vtkOpenGLRenderWindow* window, const int lowerLeft[2], int width, int height, float* depth)
{
  window->GetState()->vtkglPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(lowerLeft[0], lowerLeft[1], width, height, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
  return glGetError() == GL_NO_ERROR;
}

void vtkAccelVolumeImageDisplay::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Image->ReleaseGraphicsResources(window);
  this->Array->ReleaseGraphicsResources();
}
