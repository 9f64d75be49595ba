// vtkAccelVolumeImageDisplay: shows the CPU mappers' images in the OpenGL scene.
#include "vtkAccelVolumeImageDisplay.h"

#include "vtkOpenGLBufferObject.h"
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
#include <limits>

// Where and how a texture's pixels land: the image of imageWidth x imageHeight pixels stretched
// over the viewport, drawn over `rectangle` only; the texture holds uploadWidth x uploadHeight
// pixels (Pixels) from the rectangle's corner, or, with a warp, the intermediate image.
struct vtkAccelVolumeImageDisplay::Placement
{
  const int* lowerLeft;
  int width, height;
  int imageWidth, imageHeight;
  const int* rectangle;
  int uploadWidth, uploadHeight;
  float colourScale, colourBias;
  int selectionMode;
  const float* selectionColour;
  bool clearSecondTarget;
  const Warp* warp; // null: the texture holds the image itself
  const unsigned short* pixels; // uploadWidth x uploadHeight 16-bit RGBA
  int uploadRowBegin, uploadRowEnd; // the rows of them uploaded now
  // With a warp: each intermediate row's first and last visible pixel (first > last: none).
  const int* rowFirst;
  const int* rowLast;
  // The footprint bands drawn now, [bandBegin, bandEnd) (DrawFootprint): all of them unless the
  // frame is drawn in parts.
  int bandBegin = 0;
  int bandEnd = std::numeric_limits<int>::max();
};

namespace
{

// Intermediate rows per band of the drawn footprint: fewer rows cut the empty parts closer,
// more bands add vertices.
constexpr int FootprintBandRows = 16;

// Parts a frame is drawn in while it composites (DrawWarpedRows, then the rest): each one costs
// an upload and a draw call on the compositing thread, and the last one's fragments are left
// to the end of the frame.
constexpr int WarpedFrameParts = 3;

// Band k of the footprint lies between intermediate lines FootprintLine(k) and
// FootprintLine(k + 1) (pixel rows at integers, -1 and height the image's zero fringe).
int FootprintLine(int k, int height)
{
  return std::min(-1 + k * FootprintBandRows, height);
}

int FootprintBands(int height)
{
  return (height + 1 + FootprintBandRows - 1) / FootprintBandRows;
}

// The first row a part from band k on uploads: one below the rows its bands read, so that
// every lookup near its edges reads the image's rows, as in a frame drawn at once.
int PartFirstRow(int k, int height)
{
  return std::max(FootprintLine(k, height) - 1, 0);
}

}

#include "AccelVolumeImageFS.h"
#include "AccelVolumeResolveVS.h"
#include "AccelVolumeWarpFS.h"
#include "AccelVolumeWarpVS.h"

vtkAccelVolumeImageDisplay::vtkAccelVolumeImageDisplay() = default;

vtkAccelVolumeImageDisplay::~vtkAccelVolumeImageDisplay() = default;

bool vtkAccelVolumeImageDisplay::Draw(vtkOpenGLRenderWindow* window, const int lowerLeft[2],
  int width, int height, int imageWidth, int imageHeight, const float* rgba, const int rectangle[4],
  float colourScale, float colourBias, int selectionMode, const float selectionColour[3],
  bool clearSecondTarget)
{
  const int x0 = std::max(rectangle[0], 0), x1 = std::min(rectangle[1], imageWidth - 1);
  const int y0 = std::max(rectangle[2], 0), y1 = std::min(rectangle[3], imageHeight - 1);
  this->LastParts = 0;
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
  // With one ray per pixel the shader fetches texels by index, so a texture of the whole image
  // serves every rectangle: it is made once, not anew whenever the rectangle's size changes
  // (every frame of a turning camera). Filtered lookups (fewer rays than pixels) clamp at the
  // rectangle's edges and need a texture of its exact size.
  const bool texelPerPixel = imageWidth == width && imageHeight == height;
  const unsigned textureWidth = static_cast<unsigned>(texelPerPixel ? imageWidth : rectangleWidth);
  const unsigned textureHeight =
    static_cast<unsigned>(texelPerPixel ? imageHeight : rectangleHeight);
  this->Image->SetContext(window);
  if (!((this->Image->GetHandle() && this->Image->GetWidth() == textureWidth &&
          this->Image->GetHeight() == textureHeight) ||
        this->Image->Create2D(textureWidth, textureHeight, 4, VTK_UNSIGNED_SHORT, false)))
  {
    return false;
  }
  this->Image->SetWrapS(vtkTextureObject::ClampToEdge);
  this->Image->SetWrapT(vtkTextureObject::ClampToEdge);
  Placement placement{ lowerLeft, width, height, imageWidth, imageHeight, rectangle, rectangleWidth,
    rectangleHeight, colourScale, colourBias, selectionMode, selectionColour, clearSecondTarget,
    nullptr, this->Pixels.data(), 0, rectangleHeight, nullptr, nullptr };
  const bool shown = this->Show(window, this->Image, placement);
  this->LastParts = shown ? 1 : 0;
  return shown;
}

bool vtkAccelVolumeImageDisplay::DrawWarped(vtkOpenGLRenderWindow* window, const int lowerLeft[2],
  int width, int height, int imageWidth, int imageHeight, const Warp& warp, const int rectangle[4],
  float colourScale, float colourBias, int selectionMode, const float selectionColour[3],
  bool clearSecondTarget)
{
  const int intermediateWidth = warp.size[0];
  const int intermediateHeight = warp.size[1];
  const float* intermediate = warp.image;
  if (rectangle[1] < rectangle[0] || rectangle[3] < rectangle[2])
  {
    this->LastParts = this->DrawnParts; // nothing more visible
    this->BeginWarpedFrame();
    return true;
  }
  // One zero column and row past the image: a bilinear lookup between the last pixel and the
  // next reads zero there, as the CPU warp; lookups before the first read the zero border.
  const int uploadWidth = intermediateWidth + 1;
  const int uploadHeight = intermediateHeight + 1;
  // A frame drawn in parts (DrawWarpedRows, converted pixels) needs only its rest, in a texture
  // of its own.
  const bool rest = this->DrawnParts > 0 && warp.converted;
  const int firstRow = rest ? PartFirstRow(this->DrawnBands, intermediateHeight) : 0;
  vtkTextureObject* texture = rest ? this->PartTexture(this->DrawnParts) : this->Intermediate.Get();
  if (!this->PrepareWarpTexture(window, texture, uploadWidth, uploadHeight))
  {
    return false;
  }
  const unsigned short* pixels = warp.converted;
  const int* rowFirst = warp.rowFirst;
  const int* rowLast = warp.rowLast;
  if (!pixels)
  {
    const std::size_t rowValues = 4 * static_cast<std::size_t>(uploadWidth);
    this->Pixels.resize(rowValues * uploadHeight);
    this->RowFirst.resize(intermediateHeight);
    this->RowLast.resize(intermediateHeight);
    accelvolume::ConvertRowsPadded(intermediate, intermediateWidth, 0, intermediateHeight,
      this->Pixels.data(), this->RowFirst.data(), this->RowLast.data());
    std::fill(this->Pixels.end() - static_cast<std::ptrdiff_t>(rowValues), this->Pixels.end(), 0);
    pixels = this->Pixels.data();
    rowFirst = this->RowFirst.data();
    rowLast = this->RowLast.data();
  }
  Placement placement{ lowerLeft, width, height, imageWidth, imageHeight, rectangle, uploadWidth,
    uploadHeight, colourScale, colourBias, selectionMode, selectionColour, clearSecondTarget,
    &warp, pixels, firstRow, uploadHeight, rowFirst, rowLast };
  placement.bandBegin = rest ? this->DrawnBands : 0;
  const int parts = this->DrawnParts + 1;
  this->BeginWarpedFrame();
  const bool shown = this->Show(window, texture, placement);
  this->LastParts = shown ? parts : 0;
  return shown;
}

void vtkAccelVolumeImageDisplay::BeginWarpedFrame()
{
  this->DrawnParts = 0;
  this->DrawnBands = 0;
}

vtkTextureObject* vtkAccelVolumeImageDisplay::PartTexture(int part)
{
  while (static_cast<int>(this->PartTextures.size()) <= part)
  {
    this->PartTextures.push_back(vtkSmartPointer<vtkTextureObject>::New());
  }
  return this->PartTextures[part];
}

bool vtkAccelVolumeImageDisplay::DrawWarpedRows(vtkOpenGLRenderWindow* window,
  const int lowerLeft[2], int width, int height, const Warp& warp, int rowsReady,
  float colourScale, float colourBias)
{
  const int uploadWidth = warp.size[0] + 1;
  const int uploadHeight = warp.size[1] + 1;
  // Footprint band k reads intermediate rows FootprintLine(k) to FootprintLine(k + 1) + 1, and
  // its edge on line k + 1 spans band k + 1's columns too (DrawFootprint): it is drawn once the
  // rows of both are ready, with the very vertices of a frame drawn at once. The last band,
  // which reads the zero row past the image, waits for DrawWarped.
  const int intermediateHeight = warp.size[1];
  const int bands = FootprintBands(intermediateHeight);
  const int firstRow = PartFirstRow(this->DrawnBands, intermediateHeight);
  int bandEnd = this->DrawnBands;
  while (bandEnd + 1 < bands &&
    std::min(FootprintLine(bandEnd + 2, intermediateHeight), intermediateHeight - 1) < rowsReady &&
    FootprintLine(bandEnd + 1, intermediateHeight) + 1 < rowsReady)
  {
    ++bandEnd;
  }
  if (!warp.converted)
  {
    return false;
  }
  if (rowsReady - firstRow < intermediateHeight / WarpedFrameParts || bandEnd <= this->DrawnBands)
  {
    return true; // too few rows yet for a part of their own
  }
  // Each part has a texture of its own, of the whole image's size (the same texture
  // coordinates, so the same samples, as a frame drawn at once): writing into one that an
  // earlier draw of the frame reads would make the driver finish that draw first (llvmpipe
  // waits for it).
  vtkTextureObject* texture = this->PartTexture(this->DrawnParts);
  if (!this->PrepareWarpTexture(window, texture, uploadWidth, uploadHeight))
  {
    return false;
  }
  const int noRectangle[4] = { 0, width - 1, 0, height - 1 };
  Placement placement{ lowerLeft, width, height, width, height, noRectangle, uploadWidth,
    uploadHeight, colourScale, colourBias, 0, nullptr, false, &warp, warp.converted, firstRow,
    rowsReady, warp.rowFirst, warp.rowLast };
  placement.bandBegin = this->DrawnBands;
  placement.bandEnd = bandEnd;
  if (!this->Show(window, texture, placement))
  {
    return false;
  }
  ++this->DrawnParts;
  this->DrawnBands = bandEnd;
  glFlush(); // the driver draws these bands while the caller composites the next rows
  return true;
}

bool vtkAccelVolumeImageDisplay::PrepareWarpTexture(
  vtkOpenGLRenderWindow* window, vtkTextureObject* texture, int uploadWidth, int uploadHeight)
{
  const int limit = vtkTextureObject::GetMaximumTextureSize(window);
  if (uploadWidth > limit || uploadHeight > limit)
  {
    return false;
  }
  // The view turns the intermediate image's size a little every frame: every warp texture has
  // the largest size needed so far (in steps of 64 texels), so that none is made anew each
  // frame and all have the same size (the same texture coordinates, the same samples).
  texture->SetContext(window);
  const auto room = [limit](int size) { return std::min(limit, (size + 63) / 64 * 64); };
  this->WarpTextureSize[0] = std::max(this->WarpTextureSize[0], room(uploadWidth));
  this->WarpTextureSize[1] = std::max(this->WarpTextureSize[1], room(uploadHeight));
  const int textureWidth = this->WarpTextureSize[0], textureHeight = this->WarpTextureSize[1];
  if (!texture->GetHandle() || static_cast<int>(texture->GetWidth()) != textureWidth ||
    static_cast<int>(texture->GetHeight()) != textureHeight)
  {
    if (!texture->Create2D(static_cast<unsigned>(textureWidth),
          static_cast<unsigned>(textureHeight), 4, VTK_UNSIGNED_SHORT, false))
    {
      return false;
    }
  }
  texture->SetWrapS(vtkTextureObject::ClampToBorder);
  texture->SetWrapT(vtkTextureObject::ClampToBorder);
  texture->SetBorderColor(0.0f, 0.0f, 0.0f, 0.0f);
  return true;
}

bool vtkAccelVolumeImageDisplay::Show(
  vtkOpenGLRenderWindow* window, vtkTextureObject* texture, const Placement& p)
{
  const int x0 = std::max(p.rectangle[0], 0), x1 = std::min(p.rectangle[1], p.imageWidth - 1);
  const int y0 = std::max(p.rectangle[2], 0), y1 = std::min(p.rectangle[3], p.imageHeight - 1);
  vtkOpenGLState* state = window->GetState();
  state->Push();
  texture->Activate();
  state->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, 2);
  if (p.uploadRowEnd > p.uploadRowBegin)
  {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, p.uploadRowBegin, p.uploadWidth,
      p.uploadRowEnd - p.uploadRowBegin, GL_RGBA, GL_UNSIGNED_SHORT,
      p.pixels + 4 * static_cast<std::size_t>(p.uploadWidth) * p.uploadRowBegin);
  }
  texture->SetMinificationFilter(vtkTextureObject::Linear);
  texture->SetMagnificationFilter(vtkTextureObject::Linear);
  texture->SendParameters();
  // Plain warped frames take the lean shader over the warped parallelogram only; selection and
  // depth peeling the general one.
  const bool lean = p.warp && p.selectionMode == 0 && !p.clearSecondTarget;
  vtkShaderProgram* program = lean
    ? this->ReadyLeanProgram(window)
    : window->GetShaderCache()->ReadyShaderProgram(AccelVolumeResolveVS, AccelVolumeImageFS, "");
  if (program)
  {
    state->vtkglViewport(p.lowerLeft[0], p.lowerLeft[1], p.width, p.height);
    state->vtkglDisable(GL_DEPTH_TEST);
    state->vtkglDepthMask(GL_FALSE);
    state->vtkglEnable(GL_BLEND);
    state->vtkglBlendEquation(GL_FUNC_ADD);
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    program->SetUniformi("image", texture->GetTextureUnit());
    program->SetUniformf("colourScale", p.colourScale);
    program->SetUniformf("colourBias", p.colourBias);
    if (lean)
    {
      state->vtkglDisable(GL_SCISSOR_TEST); // the footprint is the parallelogram's, cut
      state->vtkglDisable(GL_CULL_FACE);    // a mirroring warp turns its triangles
      this->DrawFootprint(program, texture, p);
    }
    else
    {
      const float origin[2] = { static_cast<float>(p.lowerLeft[0]),
        static_cast<float>(p.lowerLeft[1]) };
      program->SetUniform2f("viewportOrigin", origin);
      if (p.warp)
      {
        this->SetWarpUniforms(program, texture, p);
      }
      this->Array->Bind();
      // Only fragments over the rectangle (one image pixel of margin for the magnification).
      const double scaleX = static_cast<double>(p.width) / p.imageWidth;
      const double scaleY = static_cast<double>(p.height) / p.imageHeight;
      const int left = p.lowerLeft[0] + static_cast<int>(std::floor((x0 - 1) * scaleX));
      const int bottom = p.lowerLeft[1] + static_cast<int>(std::floor((y0 - 1) * scaleY));
      const int right = p.lowerLeft[0] + static_cast<int>(std::ceil((x1 + 2) * scaleX));
      const int top = p.lowerLeft[1] + static_cast<int>(std::ceil((y1 + 2) * scaleY));
      state->vtkglEnable(GL_SCISSOR_TEST);
      state->vtkglScissor(left, bottom, right - left, top - bottom);
      const float size[2] = { static_cast<float>(p.width), static_cast<float>(p.height) };
      const float image[2] = { static_cast<float>(p.imageWidth),
        static_cast<float>(p.imageHeight) };
      const float rectangleOrigin[2] = { static_cast<float>(x0), static_cast<float>(y0) };
      const float rectangleSize[2] = { static_cast<float>(p.uploadWidth),
        static_cast<float>(p.uploadHeight) };
      program->SetUniform2f("viewportSize", size);
      program->SetUniform2f("imageSize", image);
      program->SetUniform2f("rectangleOrigin", rectangleOrigin);
      program->SetUniform2f("rectangleSize", rectangleSize);
      program->SetUniformi("warped", p.warp ? 1 : 0);
      const float noColour[3] = { 0, 0, 0 };
      program->SetUniformi("selectionMode", p.selectionMode);
      program->SetUniformi("clearSecondTarget", p.clearSecondTarget ? 1 : 0);
      program->SetUniform3f("selectionColour", p.selectionColour ? p.selectionColour : noColour);
      glDrawArrays(GL_TRIANGLES, 0, 3);
      this->Array->Release();
    }
  }
  texture->Deactivate();
  state->Pop();
  return program != nullptr;
}

vtkShaderProgram* vtkAccelVolumeImageDisplay::ReadyLeanProgram(vtkOpenGLRenderWindow* window)
{
  // Readying a program from its source substitutes and hashes the source on every call: several
  // draws a frame keep the program instead (the cache owns it; the weak pointers drop it with
  // the cache or the window).
  vtkOpenGLShaderCache* cache = window->GetShaderCache();
  if (this->LeanProgram && this->LeanProgramWindow == window)
  {
    return cache->ReadyShaderProgram(this->LeanProgram) ? this->LeanProgram.GetPointer() : nullptr;
  }
  this->LeanProgram = cache->ReadyShaderProgram(AccelVolumeWarpVS, AccelVolumeWarpFS, "");
  this->LeanProgramWindow = window;
  return this->LeanProgram;
}

void vtkAccelVolumeImageDisplay::SetWarpUniforms(
  vtkShaderProgram* program, vtkTextureObject* texture, const Placement& p)
{
  const double(*m)[3] = p.warp->inverse;
  const float warpU[3] = { static_cast<float>(m[0][0]), static_cast<float>(m[0][1]),
    static_cast<float>(m[0][2]) };
  const float warpV[3] = { static_cast<float>(m[1][0]), static_cast<float>(m[1][1]),
    static_cast<float>(m[1][2]) };
  const float limits[2] = { static_cast<float>(p.warp->size[0]),
    static_cast<float>(p.warp->size[1]) };
  const float extent[2] = { static_cast<float>(texture->GetWidth()),
    static_cast<float>(texture->GetHeight()) };
  program->SetUniform3f("warpU", warpU);
  program->SetUniform3f("warpV", warpV);
  program->SetUniform2f("warpLimit", limits);
  program->SetUniform2f("textureExtent", extent);
}

void vtkAccelVolumeImageDisplay::DrawFootprint(
  vtkShaderProgram* program, vtkTextureObject* texture, const Placement& p)
{
  // The parallelogram (intermediate coordinates (-1, size), pixel i at i) in bands of
  // FootprintBandRows rows: lines v = -1, -1 + rows, ..., size[1]. Band k's fragments read
  // intermediate rows line(k) .. line(k + 1) and, of those, columns [first - 1, last + 1] at
  // most; elsewhere they read zeros and blend to nothing. Each band is drawn as a trapezoid
  // whose edge on a line spans the columns of both bands beside it: neighbours share that edge
  // exactly (no T-junction: no pixel drawn twice or missed), and every band covers its
  // columns. Bands with no visible pixel are not drawn.
  // Drawn in parts (DrawWarpedRows), bands [bandBegin, bandEnd) are drawn now; their edges need
  // the columns of the bands beside them.
  const int width = p.warp->size[0], height = p.warp->size[1];
  const int bands = FootprintBands(height);
  const int bandBegin = std::max(p.bandBegin, 0);
  const int bandEnd = std::min(p.bandEnd, bands);
  const auto line = [height](int k) { return FootprintLine(k, height); };
  std::vector<int> bandFirst(bands, width), bandLast(bands, -1); // first > last: empty
  for (int k = std::max(bandBegin - 1, 0); k < std::min(bandEnd + 1, bands); ++k)
  {
    int first = width, last = -1;
    for (int v = std::max(line(k), 0); v <= std::min(line(k + 1), height - 1); ++v)
    {
      if (p.rowFirst[v] <= p.rowLast[v])
      {
        first = std::min(first, p.rowFirst[v] - 1);
        last = std::max(last, p.rowLast[v] + 1);
      }
    }
    bandFirst[k] = std::max(first, -1);
    bandLast[k] = std::min(last, width);
  }
  // The span of line k: both neighbouring bands' columns.
  const auto span = [&](int k, double& first, double& last)
  {
    int lo = width, hi = -1;
    for (int band : { k - 1, k })
    {
      if (band >= 0 && band < bands && bandFirst[band] <= bandLast[band])
      {
        lo = std::min(lo, bandFirst[band]);
        hi = std::max(hi, bandLast[band]);
      }
    }
    first = lo;
    last = hi;
  };
  const double(*m)[3] = p.warp->forward;
  const double extent[2] = { static_cast<double>(texture->GetWidth()),
    static_cast<double>(texture->GetHeight()) };
  std::vector<float>& vertices = this->FootprintVertices;
  vertices.clear();
  const auto add = [&](double u, double v)
  {
    const double x = m[0][0] * u + m[0][1] * v + m[0][2];
    const double y = m[1][0] * u + m[1][1] * v + m[1][2];
    vertices.push_back(static_cast<float>(2.0 * x / p.imageWidth - 1.0));
    vertices.push_back(static_cast<float>(2.0 * y / p.imageHeight - 1.0));
    vertices.push_back(static_cast<float>((u + 0.5) / extent[0]));
    vertices.push_back(static_cast<float>((v + 0.5) / extent[1]));
  };
  for (int k = bandBegin; k < bandEnd; ++k)
  {
    if (bandFirst[k] > bandLast[k])
    {
      continue;
    }
    double bottomFirst, bottomLast, topFirst, topLast;
    span(k, bottomFirst, bottomLast);
    span(k + 1, topFirst, topLast);
    const double bottom = line(k), top = line(k + 1);
    add(bottomFirst, bottom);
    add(bottomLast, bottom);
    add(topLast, top);
    add(bottomFirst, bottom);
    add(topLast, top);
    add(topFirst, top);
  }
  if (vertices.empty())
  {
    return;
  }
  this->FootprintBuffer->Upload(vertices, vtkOpenGLBufferObject::ArrayBuffer);
  vtkOpenGLVertexArrayObject* array = this->FootprintArray;
  array->Bind();
  constexpr int stride = 4 * sizeof(float);
  array->AddAttributeArray(
    program, this->FootprintBuffer, "vertexPosition", 0, stride, VTK_FLOAT, 2, false);
  array->AddAttributeArray(program, this->FootprintBuffer, "vertexCoordinate", 2 * sizeof(float),
    stride, VTK_FLOAT, 2, false);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices.size() / 4));
  array->Release();
}

bool vtkAccelVolumeImageDisplay::ReadDepth(
  vtkOpenGLRenderWindow* window, const int lowerLeft[2], int width, int height, float* depth)
{
  return this->DepthReader.Read(window, lowerLeft, width, height, depth);
}

void vtkAccelVolumeImageDisplay::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Image->ReleaseGraphicsResources(window);
  this->Intermediate->ReleaseGraphicsResources(window);
  for (vtkTextureObject* texture : this->PartTextures)
  {
    texture->ReleaseGraphicsResources(window);
  }
  this->WarpTextureSize[0] = this->WarpTextureSize[1] = 0;
  this->LeanProgram = nullptr;
  this->LeanProgramWindow = nullptr;
  this->Array->ReleaseGraphicsResources();
  this->FootprintArray->ReleaseGraphicsResources();
  this->FootprintBuffer->ReleaseGraphicsResources();
  this->DepthReader.ReleaseGraphicsResources(window);
}
