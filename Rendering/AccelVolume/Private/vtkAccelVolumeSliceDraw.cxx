// The slice mapper's proxy geometry drawn into the accumulation target: bricks, their slices
// in early-termination batches and their cut faces.
#include "vtkAccelVolumeSliceDraw.h"

#include "vtkAccelVolumeSlicePasses.h"
#include "vtkAccelVolumeSliceResolve.h"
#include "vtkAccelVolumeSliceResources.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkVolumeMapper.h"
#include "vtk_glew.h"

#include "AccelVolumeResolveVS.h"
#include "AccelVolumeSliceFS.h"
#include "AccelVolumeSliceVS.h"
#include "AccelVolumeTerminationFS.h"

#include <algorithm>
#include <string>

namespace
{

// Marks pixels whose front-to-back alpha reached the threshold: depth 0 there, so the early
// depth test rejects the remaining slices' fragments before shading.
bool RunTerminationPass(vtkOpenGLRenderWindow* window, vtkAccelVolumeSliceResources& resources,
  const vtkAccelVolumeSliceFrame& frame)
{
  vtkShaderProgram* program =
    resources.ReadyProgram(window, AccelVolumeResolveVS, AccelVolumeTerminationFS, "");
  if (!program)
  {
    return false;
  }
  vtkOpenGLState* state = window->GetState();
  // The accumulation texture is the colour target: make earlier blends visible to the reads.
  if (glTextureBarrier)
  {
    glTextureBarrier();
  }
  state->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  state->vtkglDepthMask(GL_TRUE);
  state->vtkglDepthFunc(GL_ALWAYS);
  resources.Accumulation->Activate();
  program->SetUniformi("accumulation", resources.Accumulation->GetTextureUnit());
  program->SetUniformf("threshold", frame.TerminationThreshold);
  // A terminated pixel's depth fails every later slice: 0 for the usual LESS test, 1 for the
  // depth pass's GEQUAL test against the contour.
  const bool contourTest = frame.DepthPassStage == 2;
  program->SetUniformf("terminatedDepth", contourTest ? 1.0f : 0.0f);
  resources.ResolveArray->Bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  resources.ResolveArray->Release();
  resources.Accumulation->Deactivate();
  state->vtkglDepthFunc(contourTest ? GL_GEQUAL : GL_LESS);
  state->vtkglDepthMask(GL_FALSE);
  state->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  ++frame.TerminationPasses;
  return true;
}

// The vertex stage: CPU polygons, or (generated slices) the variant that builds them.
const char* SliceVertexSource(const vtkAccelVolumeSliceFrame& frame)
{
  static const std::string generated = []
  {
    std::string source = AccelVolumeSliceVS;
    const std::string marker = "//VTK::System::Dec";
    return source.replace(
      source.find(marker), marker.size(), marker + "\n#define ACCELVOLUME_GENERATED_SLICES 1");
  }();
  return frame.GeneratedSlices ? generated.c_str() : AccelVolumeSliceVS;
}

// Generated slices: instance n of the next draw reads slice record first + n.
void BindSliceRecords(vtkAccelVolumeSliceResources& resources, vtkShaderProgram* program, int first)
{
  using Frame = vtkAccelVolumeSliceFrame;
  constexpr int Stride = Frame::SliceRecordFloats * sizeof(float);
  const int base = first * Stride;
  vtkOpenGLVertexArrayObject* array = resources.GeneratedSliceArray;
  vtkOpenGLBufferObject* buffer = resources.SliceRecordBuffer;
  array->AddAttributeArrayWithDivisor(
    program, buffer, "sliceDepth", base, Stride, VTK_FLOAT, 1, false, 1, false);
  array->AddAttributeArrayWithDivisor(program, buffer, "sliceLower",
    base + static_cast<int>(sizeof(float)), Stride, VTK_FLOAT, 3, false, 1, false);
  array->AddAttributeArrayWithDivisor(program, buffer, "sliceUpper",
    base + static_cast<int>(4 * sizeof(float)), Stride, VTK_FLOAT, 3, false, 1, false);
}

// Makes `program` current with the proxy vertex layout (slices and faces use different
// variants, and the termination pass uses another program in between).
void UseProgram(vtkOpenGLRenderWindow* window, vtkAccelVolumeSliceResources& resources,
  const vtkAccelVolumeSliceFrame& frame, vtkShaderProgram* program, bool faces)
{
  window->GetShaderCache()->ReadyShaderProgram(program);
  if (frame.GeneratedSlices && !faces)
  {
    // Their own array: instanced attributes (divisor 1) must never meet the polygons' layout.
    resources.GeneratedSliceArray->ShaderProgramChanged();
    resources.GeneratedSliceArray->Bind();
    program->SetUniform3f("depthGradient", frame.DepthGradient);
    program->SetUniformf("depthOffset", frame.DepthOffset);
    BindSliceRecords(resources, program, 0);
    return;
  }
  resources.SliceArray->ShaderProgramChanged();
  resources.SliceArray->Bind();
  constexpr int Stride = vtkAccelVolumeSliceFrame::VertexFloats * sizeof(float);
  resources.SliceArray->AddAttributeArray(
    program, resources.VertexBuffer, "vertexIndex", 0, Stride, VTK_FLOAT, 3, false);
  if (!faces)
  {
    // Cut faces sample where they are and never read the slice depth (compiled out there).
    resources.SliceArray->AddAttributeArray(program, resources.VertexBuffer, "vertexDepth",
      3 * sizeof(float), Stride, VTK_FLOAT, 1, false);
  }
}

// Back to `program` after a termination pass: the vertex array keeps its attribute layout and
// the program its uniforms, so binding both again suffices.
void ResumeSlices(vtkOpenGLRenderWindow* window, vtkAccelVolumeSliceResources& resources,
  const vtkAccelVolumeSliceFrame& frame, vtkShaderProgram* program)
{
  window->GetShaderCache()->ReadyShaderProgram(program);
  (frame.GeneratedSlices ? resources.GeneratedSliceArray : resources.SliceArray)->Bind();
}

// Unbinds the array the slices were drawn with.
void ReleaseSliceArray(
  vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame)
{
  (frame.GeneratedSlices ? resources.GeneratedSliceArray : resources.SliceArray)->Release();
}

// Slices [first, first + count) of the frame's proxy geometry (vertices [first, first + count)
// for CPU polygons).
void DrawSlices(vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame,
  vtkShaderProgram* program, int first, int count)
{
  if (!frame.GeneratedSlices)
  {
    glDrawArrays(GL_TRIANGLES, first, count);
    return;
  }
  constexpr int vertices = vtkAccelVolumeSliceFrame::GeneratedSliceVertices;
  // A base instance offsets the instanced records without re-specifying the attributes (which
  // costs CPU per batch of early termination).
  if (glDrawArraysInstancedBaseInstance)
  {
    glDrawArraysInstancedBaseInstance(GL_TRIANGLES, 0, vertices, count, static_cast<GLuint>(first));
    return;
  }
  if (first != 0)
  {
    BindSliceRecords(resources, program, first);
  }
  glDrawArraysInstanced(GL_TRIANGLES, 0, vertices, count);
}

void SetBrickUniforms(vtkShaderProgram* program, vtkTextureObject* texture,
  const vtkAccelVolumeSliceFrame::BrickDraw& brick)
{
  program->SetUniformi("volumeTexture", texture->GetTextureUnit());
  program->SetUniform3f("volumeDimensions", brick.TextureSize);
  program->SetUniform3f("textureOrigin", brick.TextureOrigin);
  program->SetUniform3f("ownedLower", brick.OwnedLower);
  program->SetUniform3f("ownedUpper", brick.OwnedUpper);
}

// The slices (or cut faces) of one brick's cells, with `program` current.
void DrawBrickCells(vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame,
  vtkShaderProgram* program, const vtkAccelVolumeSliceFrame::BrickDraw& brick, bool faces)
{
  for (const vtkAccelVolumeSliceFrame::Cell& cell : brick.Cells)
  {
    const int first = faces ? cell.FaceFirst : cell.SliceFirst;
    const int count = faces ? cell.FaceCount : cell.SliceCount;
    if (count > 0)
    {
      program->SetUniform3f("regionLower", cell.Lower.data());
      program->SetUniform3f("regionUpper", cell.Upper.data());
      if (faces)
      {
        glDrawArrays(GL_TRIANGLES, first, count);
      }
      else
      {
        DrawSlices(resources, frame, program, first, count);
      }
    }
  }
}

// Proxy slices between termination passes: TerminationInterval sample planes, in whole slabs.
int TerminationBatch(const vtkAccelVolumeSliceFrame& frame)
{
  return std::max(1, frame.TerminationInterval / std::max(1, frame.SlabSamples));
}

// Composite with early ray termination: a brick's slices in batches, with a mark pass after
// every TerminationBatch slices (or slabs) of the frame (counted across bricks) but the last.
bool DrawCompositeBrick(vtkOpenGLRenderWindow* window, vtkAccelVolumeSliceResources& resources,
  const vtkAccelVolumeSliceFrame& frame, vtkShaderProgram* program,
  const vtkAccelVolumeSliceFrame::BrickDraw& brick, int& slicesSinceMark, int& slicesLeft)
{
  const int sliceCount = static_cast<int>(brick.SliceStarts.size()) - 1;
  const int batch = TerminationBatch(frame);
  if (!brick.Cells.empty())
  {
    // A composite brick is one cell; slabs bound their samples by its box.
    program->SetUniform3f("regionLower", brick.Cells.front().Lower.data());
    program->SetUniform3f("regionUpper", brick.Cells.front().Upper.data());
  }
  int first = 0;
  while (first < sliceCount)
  {
    const int last = std::min(sliceCount, first + batch - slicesSinceMark);
    DrawSlices(resources, frame, program, brick.SliceStarts[first],
      brick.SliceStarts[last] - brick.SliceStarts[first]);
    slicesSinceMark += last - first;
    slicesLeft -= last - first;
    first = last;
    if (slicesSinceMark == batch && slicesLeft > 0)
    {
      ReleaseSliceArray(resources, frame);
      if (!RunTerminationPass(window, resources, frame))
      {
        return false;
      }
      slicesSinceMark = 0;
      ResumeSlices(window, resources, frame, program);
    }
  }
  return true;
}

} // namespace

// Every brick in drawing order: acquire (upload) its texture, draw its slices, then its cut
// faces, so a streamed brick is uploaded once per frame.
bool vtkAccelVolumeSliceDrawBricks(vtkOpenGLRenderWindow* window,
  vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame,
  std::string& error)
{
  vtkShaderProgram* sliceProgram = resources.ReadyProgram(window, SliceVertexSource(frame),
    AccelVolumeSliceFS, vtkAccelVolumeSliceShaderPrelude(frame, frame.SlabSamples, false));
  if (!sliceProgram)
  {
    error = "the slice shader did not compile";
    return false;
  }
  vtkAccelVolumeSliceSetFrameUniforms(sliceProgram, resources, frame);
  vtkShaderProgram* faceProgram = nullptr;
  // Only frames with cut faces (composite has none) need the face program and its uniforms.
  const bool anyFaces = std::any_of(frame.Bricks.begin(), frame.Bricks.end(),
    [](const vtkAccelVolumeSliceFrame::BrickDraw& brick)
    {
      return std::any_of(brick.Cells.begin(), brick.Cells.end(),
        [](const vtkAccelVolumeSliceFrame::Cell& cell) { return cell.FaceCount > 0; });
    });
  if (frame.BoundaryRerendering && anyFaces)
  {
    faceProgram = resources.ReadyProgram(window, AccelVolumeSliceVS, AccelVolumeSliceFS,
      vtkAccelVolumeSliceShaderPrelude(frame, 1, true));
    if (!faceProgram)
    {
      error = "the cut-face shader did not compile";
      return false;
    }
    vtkAccelVolumeSliceSetFrameUniforms(faceProgram, resources, frame);
  }
  const bool terminate =
    frame.BlendMode == vtkVolumeMapper::COMPOSITE_BLEND && frame.EarlyTermination;
  int slicesLeft = 0;
  for (const auto& brick : frame.Bricks)
  {
    slicesLeft += static_cast<int>(brick.SliceStarts.size()) - 1;
  }
  int slicesSinceMark = 0;
  for (const vtkAccelVolumeSliceFrame::BrickDraw& brick : frame.Bricks)
  {
    vtkTextureObject* texture = frame.Components > 1
      ? resources.ComponentVolume.GetPointer()
      : resources.Bricks.Acquire(window, brick.Brick, frame.Linear, error);
    if (frame.Components > 1)
    {
      const int filter = frame.Linear ? vtkTextureObject::Linear : vtkTextureObject::Nearest;
      texture->SetMinificationFilter(filter);
      texture->SetMagnificationFilter(filter);
    }
    if (!texture)
    {
      return false;
    }
    texture->Activate();
    UseProgram(window, resources, frame, sliceProgram, false);
    SetBrickUniforms(sliceProgram, texture, brick);
    bool ok = true;
    if (terminate)
    {
      ok = DrawCompositeBrick(
        window, resources, frame, sliceProgram, brick, slicesSinceMark, slicesLeft);
    }
    else
    {
      DrawBrickCells(resources, frame, sliceProgram, brick, false);
    }
    ReleaseSliceArray(resources, frame);
    if (ok && faceProgram)
    {
      UseProgram(window, resources, frame, faceProgram, true);
      SetBrickUniforms(faceProgram, texture, brick);
      DrawBrickCells(resources, frame, faceProgram, brick, true);
      resources.SliceArray->Release();
    }
    texture->Deactivate();
    if (!ok)
    {
      error = "the early-termination shader did not compile";
      return false;
    }
  }
  return true;
}
