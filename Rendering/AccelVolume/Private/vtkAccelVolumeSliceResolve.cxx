// The slice mapper's last passes: the resolve of the accumulated values to colour (into the
// scene or the RenderToImage target) and the copy of the scene depth the accumulation tests.
#include "vtkAccelVolumeSliceResolve.h"

#include "vtkAccelVolumeDepthCopy.h"
#include "vtkAccelVolumeSlicePasses.h"
#include "vtkAccelVolumeSliceResources.h"
#include "vtkImageData.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "AccelVolumeDepthDownsampleFS.h"
#include "AccelVolumeResolveFS.h"
#include "AccelVolumeResolveVS.h"

#include <string>

// Pass 2: colour the accumulated value as VTK's GPU ray caster does and blend it
// (premultiplied) over the scene.
bool vtkAccelVolumeSliceResolve(vtkOpenGLRenderWindow* window,
  vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame,
  const int lowerLeft[2])
{
  vtkOpenGLState* state = window->GetState();
  state->vtkglViewport(lowerLeft[0], lowerLeft[1], frame.ViewportWidth, frame.ViewportHeight);
  state->vtkglDisable(GL_DEPTH_TEST);
  // Whatever the passes before left (compute slices draw nothing, the depth copy of a reduced
  // target blends nothing): blend premultiplied colour over the scene.
  state->vtkglEnable(GL_BLEND);
  state->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  state->vtkglBlendEquation(GL_FUNC_ADD);
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  vtkShaderProgram* program = resources.ReadyProgram(window, AccelVolumeResolveVS,
    AccelVolumeResolveFS, vtkAccelVolumeSliceShaderPrelude(frame, 1, false));
  if (!program)
  {
    return false;
  }
  resources.Accumulation->Activate();
  resources.TransferTable->Activate();
  if (frame.Components > 1)
  {
    resources.ComponentTables->Activate();
    program->SetUniformi("componentTables", resources.ComponentTables->GetTextureUnit());
    program->SetUniform4f("componentWeights", frame.ComponentWeights);
  }
  if (vtkAccelVolumeSliceSecondAccumulation(frame))
  {
    resources.AccumulationSecond->Activate();
    program->SetUniformi("accumulationSecond", resources.AccumulationSecond->GetTextureUnit());
  }
  program->SetUniformi("accumulation", resources.Accumulation->GetTextureUnit());
  program->SetUniformi("transferTable", resources.TransferTable->GetTextureUnit());
  program->SetUniformf("tableSize", static_cast<float>(vtkAccelVolumeSliceResources::TableSize));
  const float origin[2] = { static_cast<float>(lowerLeft[0]), static_cast<float>(lowerLeft[1]) };
  program->SetUniform2f("viewportOrigin", origin);
  const float viewport[2] = { static_cast<float>(frame.ViewportWidth),
    static_cast<float>(frame.ViewportHeight) };
  const float target[2] = { static_cast<float>(frame.Width), static_cast<float>(frame.Height) };
  program->SetUniform2f("viewportSize", viewport);
  program->SetUniform2f("targetSize", target);
  program->SetUniformf("colourScale", frame.ColourScale);
  program->SetUniformf("colourBias", frame.ColourBias);
  program->SetUniformi("selectionMode", frame.SelectionMode);
  program->SetUniform3f("selectionColour", frame.SelectionColour);
  program->SetUniformi("clearSecondTarget", frame.ClearSecondTarget ? 1 : 0);
  resources.ResolveArray->Bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  resources.ResolveArray->Release();
  resources.Accumulation->Deactivate();
  resources.TransferTable->Deactivate();
  if (frame.Components > 1)
  {
    resources.ComponentTables->Deactivate();
  }
  if (vtkAccelVolumeSliceSecondAccumulation(frame))
  {
    resources.AccumulationSecond->Deactivate();
  }
  return true;
}

// RenderToImage: the resolve into the image framebuffer (cleared to transparent), read back.
bool vtkAccelVolumeSliceResolveToImage(vtkOpenGLRenderWindow* window,
  vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame)
{
  vtkOpenGLState* state = window->GetState();
  resources.ImageFramebuffer->SaveCurrentBindingsAndBuffers();
  resources.ImageFramebuffer->Bind();
  resources.ImageFramebuffer->ActivateDrawBuffer(0);
  state->vtkglViewport(0, 0, frame.ViewportWidth, frame.ViewportHeight);
  state->vtkglDisable(GL_SCISSOR_TEST);
  state->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  state->vtkglClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  state->vtkglClear(GL_COLOR_BUFFER_BIT);
  state->vtkglEnable(GL_BLEND);
  const int origin[2] = { 0, 0 };
  bool ok = vtkAccelVolumeSliceResolve(window, resources, frame, origin);
  if (ok && frame.ColourImage)
  {
    frame.ColourImage->SetDimensions(frame.ViewportWidth, frame.ViewportHeight, 1);
    frame.ColourImage->AllocateScalars(VTK_UNSIGNED_CHAR, 4);
    resources.ImageFramebuffer->ActivateReadBuffer(0);
    state->vtkglPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, frame.ViewportWidth, frame.ViewportHeight, GL_RGBA, GL_UNSIGNED_BYTE,
      frame.ColourImage->GetScalarPointer());
  }
  resources.ImageFramebuffer->RestorePreviousBindingsAndBuffers();
  return ok;
}

// The scene's depth at the target's size: copied, or (reduced target) copied at the viewport's
// size and sampled down by a pass that writes the target's depth buffer.
bool vtkAccelVolumeSliceCopySceneDepth(vtkOpenGLRenderWindow* window,
  vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame, int depthFormat)
{
  if (!vtkAccelVolumeSliceReducedTarget(frame))
  {
    vtkAccelVolumeCopyReadDepth(window, resources.SceneDepth, resources.Framebuffer, depthFormat,
      frame.LowerLeft[0], frame.LowerLeft[1], frame.Width, frame.Height);
    return true;
  }
  if (!resources.PrepareFullDepth(window, frame.ViewportWidth, frame.ViewportHeight, depthFormat))
  {
    return false;
  }
  vtkAccelVolumeCopyReadDepth(window, resources.SceneDepthFull, resources.DepthFramebuffer,
    depthFormat, frame.LowerLeft[0], frame.LowerLeft[1], frame.ViewportWidth, frame.ViewportHeight);
  resources.SceneDepthFull->Activate();
  vtkShaderProgram* program =
    resources.ReadyProgram(window, AccelVolumeResolveVS, AccelVolumeDepthDownsampleFS, "");
  if (!program)
  {
    resources.SceneDepthFull->Deactivate();
    return false;
  }
  vtkOpenGLState* state = window->GetState();
  resources.Framebuffer->SaveCurrentBindingsAndBuffers();
  resources.Framebuffer->Bind();
  state->vtkglViewport(0, 0, frame.Width, frame.Height);
  state->vtkglDisable(GL_SCISSOR_TEST);
  state->vtkglDisable(GL_BLEND);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDepthFunc(GL_ALWAYS);
  state->vtkglDepthMask(GL_TRUE);
  state->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  program->SetUniformi("fullDepth", resources.SceneDepthFull->GetTextureUnit());
  const float scale[2] = { static_cast<float>(frame.ViewportWidth) / frame.Width,
    static_cast<float>(frame.ViewportHeight) / frame.Height };
  const float size[2] = { static_cast<float>(frame.ViewportWidth),
    static_cast<float>(frame.ViewportHeight) };
  program->SetUniform2f("scale", scale);
  program->SetUniform2f("fullSize", size);
  resources.ResolveArray->Bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  resources.ResolveArray->Release();
  state->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  state->vtkglDepthMask(GL_FALSE);
  state->vtkglDepthFunc(GL_LESS);
  resources.Framebuffer->RestorePreviousBindingsAndBuffers();
  resources.SceneDepthFull->Deactivate();
  return true;
}
