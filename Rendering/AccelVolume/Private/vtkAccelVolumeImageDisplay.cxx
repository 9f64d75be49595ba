// vtkAccelVolumeImageDisplay: shows the CPU ray caster's image in the OpenGL scene.
#include "vtkAccelVolumeImageDisplay.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "common/Unorm16.h"

#include <algorithm>
#include <cmath>

#include "AccelVolumeImageFS.h"
#include "AccelVolumeResolveVS.h"

vtkAccelVolumeImageDisplay::vtkAccelVolumeImageDisplay() = default;

vtkAccelVolumeImageDisplay::~vtkAccelVolumeImageDisplay() = default;

bool vtkAccelVolumeImageDisplay::Draw(vtkOpenGLRenderWindow* window, const int lowerLeft[2],
  int width, int height, int imageWidth, int imageHeight, const float* rgba, const int rectangle[4],
  float colourScale, float colourBias, int selectionMode, const float selectionColour[3],
  bool clearSecondTarget)
{
  const int x0 = std::max(rectangle[0], 0), x1 = std::min(rectangle[1], imageWidth - 1);
  const int y0 = std::max(rectangle[2], 0), y1 = std::min(rectangle[3], imageHeight - 1);
  if (x1 < x0 || y1 < y0)
  {
    return true; // nothing visible
  }
  const int rectangleWidth = x1 - x0 + 1, rectangleHeight = y1 - y0 + 1;
  // 16-bit normalised channels (as VTK's CPU mapper uses): a quarter of the float upload, in
  // 1/65535 steps, far below the 8-bit framebuffer's; only the rectangle the rays covered.
  const std::size_t rowValues = 4 * static_cast<std::size_t>(rectangleWidth);
  this->Pixels.resize(rowValues * rectangleHeight);
  for (int y = y0; y <= y1; ++y)
  {
    accelvolume::ConvertToUnorm16(rgba + 4 * (static_cast<std::size_t>(y) * imageWidth + x0),
      rowValues, this->Pixels.data() + rowValues * (y - y0));
  }
  vtkOpenGLState* state = window->GetState();
  state->Push();
  this->Image->SetContext(window);
  state->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, 2);
  // With one ray per pixel the shader fetches texels by index, so a texture of the whole image
  // serves every rectangle: it is made once, not anew whenever the rectangle's size changes
  // (every frame of a turning camera). Filtered lookups (fewer rays than pixels) clamp at the
  // rectangle's edges and need a texture of its exact size.
  const bool texelPerPixel = imageWidth == width && imageHeight == height;
  const unsigned textureWidth = static_cast<unsigned>(texelPerPixel ? imageWidth : rectangleWidth);
  const unsigned textureHeight =
    static_cast<unsigned>(texelPerPixel ? imageHeight : rectangleHeight);
  bool ok = (this->Image->GetHandle() && this->Image->GetWidth() == textureWidth &&
              this->Image->GetHeight() == textureHeight) ||
    this->Image->Create2D(textureWidth, textureHeight, 4, VTK_UNSIGNED_SHORT, false);
  if (ok)
  {
    this->Image->Activate();
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, rectangleWidth, rectangleHeight, GL_RGBA,
      GL_UNSIGNED_SHORT, this->Pixels.data());
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
      // Only fragments over the rectangle (one image pixel of margin for the magnification).
      const double scaleX = static_cast<double>(width) / imageWidth;
      const double scaleY = static_cast<double>(height) / imageHeight;
      const int left = lowerLeft[0] + static_cast<int>(std::floor((x0 - 1) * scaleX));
      const int bottom = lowerLeft[1] + static_cast<int>(std::floor((y0 - 1) * scaleY));
      const int right = lowerLeft[0] + static_cast<int>(std::ceil((x1 + 2) * scaleX));
      const int top = lowerLeft[1] + static_cast<int>(std::ceil((y1 + 2) * scaleY));
      state->vtkglEnable(GL_SCISSOR_TEST);
      state->vtkglScissor(left, bottom, right - left, top - bottom);
      state->vtkglDisable(GL_DEPTH_TEST);
      state->vtkglDepthMask(GL_FALSE);
      state->vtkglEnable(GL_BLEND);
      state->vtkglBlendEquation(GL_FUNC_ADD);
      state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
      program->SetUniformi("image", this->Image->GetTextureUnit());
      const float origin[2] = { static_cast<float>(lowerLeft[0]),
        static_cast<float>(lowerLeft[1]) };
      const float size[2] = { static_cast<float>(width), static_cast<float>(height) };
      const float image[2] = { static_cast<float>(imageWidth), static_cast<float>(imageHeight) };
      const float rectangleOrigin[2] = { static_cast<float>(x0), static_cast<float>(y0) };
      const float rectangleSize[2] = { static_cast<float>(rectangleWidth),
        static_cast<float>(rectangleHeight) };
      program->SetUniform2f("viewportOrigin", origin);
      program->SetUniform2f("viewportSize", size);
      program->SetUniform2f("imageSize", image);
      program->SetUniform2f("rectangleOrigin", rectangleOrigin);
      program->SetUniform2f("rectangleSize", rectangleSize);
      program->SetUniformf("colourScale", colourScale);
      program->SetUniformf("colourBias", colourBias);
      const float noColour[3] = { 0, 0, 0 };
      program->SetUniformi("selectionMode", selectionMode);
      program->SetUniformi("clearSecondTarget", clearSecondTarget ? 1 : 0);
      program->SetUniform3f("selectionColour", selectionColour ? selectionColour : noColour);
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
  return this->DepthReader.Read(window, lowerLeft, width, height, depth);
}

void vtkAccelVolumeImageDisplay::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Image->ReleaseGraphicsResources(window);
  this->Array->ReleaseGraphicsResources();
  this->DepthReader.ReleaseGraphicsResources(window);
}
