// Picks the slice, ray cast or shear-warp mapper for the context and renders with it.
#include "vtkAccelVolumeSmartMapper.h"

#include "vtkAccelVolumeMapperSupport.h"
#include "vtkAccelVolumeRenderProgress.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPlaneCollection.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <sstream>
#include <string>

vtkStandardNewMacro(vtkAccelVolumeSmartMapper);

namespace
{
const char* BlendName(int blend)
{
  switch (blend)
  {
    case vtkVolumeMapper::COMPOSITE_BLEND:
      return "composite";
    case vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND:
      return "MIP";
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
      return "MinIP";
    case vtkVolumeMapper::AVERAGE_INTENSITY_BLEND:
      return "average";
    case vtkVolumeMapper::ADDITIVE_BLEND:
      return "additive";
    case vtkVolumeMapper::ISOSURFACE_BLEND:
      return "isosurface";
    case vtkVolumeMapper::SLICE_BLEND:
      return "slice";
    default:
      return "unknown";
  }
}

// Mesa's software rasterizers: the slice mapper's fragment work would run on the CPU.
bool IsSoftwareRenderer(const std::string& name)
{
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower.find("llvmpipe") != std::string::npos ||
    lower.find("softpipe") != std::string::npos || lower.find("swrast") != std::string::npos;
}
}

vtkAccelVolumeSmartMapper::vtkAccelVolumeSmartMapper()
{
  this->Relayer->SetCallback(&vtkAccelVolumeSmartMapper::Relay);
  this->Relayer->SetClientData(this);
  vtkVolumeMapper* mappers[3] = { this->SliceMapper, this->RayCastMapper, this->ShearWarpMapper };
  for (vtkVolumeMapper* mapper : mappers)
  {
    mapper->AddObserver(vtkCommand::ErrorEvent, this->Relayer);
    mapper->AddObserver(vtkCommand::WarningEvent, this->Relayer);
  }
}

vtkAccelVolumeSmartMapper::~vtkAccelVolumeSmartMapper()
{
  vtkVolumeMapper* mappers[3] = { this->SliceMapper, this->RayCastMapper, this->ShearWarpMapper };
  for (vtkVolumeMapper* mapper : mappers)
  {
    mapper->RemoveObserver(this->Relayer);
  }
}

const char* vtkAccelVolumeSmartMapper::GetRenderModeAsString(int mode)
{
  switch (mode)
  {
    case DEFAULT_RENDER:
      return "Default";
    case SLICE_RENDER:
      return "Slice";
    case RAYCAST_RENDER:
      return "RayCast";
    case SHEARWARP_RENDER:
      return "ShearWarp";
    case OSPRAY_RENDER:
      return "OSPRay";
    default:
      return "Undefined";
  }
}

void vtkAccelVolumeSmartMapper::SetRequestedRenderMode(int mode)
{
  if (mode != DEFAULT_RENDER && mode != RAYCAST_RENDER && mode != SLICE_RENDER &&
    mode != OSPRAY_RENDER && mode != SHEARWARP_RENDER)
  {
    vtkErrorMacro("Invalid render mode " << mode
                                         << " (use DefaultRenderMode, RayCastRenderMode, "
                                            "GPURenderMode or SHEARWARP_RENDER)");
    return;
  }
  if (mode != this->RequestedRenderMode)
  {
    this->RequestedRenderMode = mode;
    this->Modified();
  }
}

void vtkAccelVolumeSmartMapper::SetVectorMode(int mode)
{
  if (mode < DISABLED || mode > COMPONENT)
  {
    vtkErrorMacro("Invalid vector mode " << mode << " (use DISABLED, MAGNITUDE or COMPONENT)");
    return;
  }
  if (mode != this->VectorMode)
  {
    this->VectorMode = mode;
    this->Modified();
  }
}

void vtkAccelVolumeSmartMapper::ConnectInput(vtkAccelVolumeMapper* mapper)
{
  vtkDataSet* input = this->GetInput();
  int cellFlag = 0;
  vtkDataArray* scalars = input ? vtkAbstractMapper::GetScalars(input, this->ScalarMode,
                                    this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag)
                                : nullptr;
  if (this->VectorMode == DISABLED || !scalars || scalars->GetNumberOfComponents() < 2)
  {
    mapper->SetInputConnection(this->GetInputConnection(0, 0));
    return;
  }
  const int components = scalars->GetNumberOfComponents();
  const int component = std::min(this->VectorComponent, components - 1);
  const vtkMTimeType sourceTime = std::max(input->GetMTime(), scalars->GetMTime());
  if (!this->Reduced || sourceTime > this->ReducedTime || this->ReducedMode != this->VectorMode ||
    this->ReducedComponent != component)
  {
    this->Reduced.TakeReference(input->NewInstance());
    this->Reduced->CopyStructure(input);
    vtkNew<vtkFloatArray> reduced;
    reduced->SetName(this->VectorMode == MAGNITUDE ? "Magnitude" : scalars->GetName());
    const vtkIdType tuples = scalars->GetNumberOfTuples();
    reduced->SetNumberOfTuples(tuples);
    float* out = reduced->GetPointer(0);
    for (vtkIdType t = 0; t < tuples; ++t)
    {
      if (this->VectorMode == MAGNITUDE)
      {
        double sum = 0.0;
        for (int c = 0; c < components; ++c)
        {
          const double v = scalars->GetComponent(t, c);
          sum += v * v;
        }
        out[t] = static_cast<float>(std::sqrt(sum));
      }
      else
      {
        out[t] = static_cast<float>(scalars->GetComponent(t, component));
      }
    }
    (cellFlag ? static_cast<vtkDataSetAttributes*>(this->Reduced->GetCellData())
              : static_cast<vtkDataSetAttributes*>(this->Reduced->GetPointData()))
      ->SetScalars(reduced);
    this->ReducedTime = this->Reduced->GetMTime();
    this->ReducedMode = this->VectorMode;
    this->ReducedComponent = component;
  }
  mapper->SetInputData(this->Reduced);
  mapper->SetScalarMode(cellFlag ? VTK_SCALAR_MODE_USE_CELL_DATA : VTK_SCALAR_MODE_USE_POINT_DATA);
}

void vtkAccelVolumeSmartMapper::ForwardSampleDistances(
  vtkRenderer* renderer, vtkAccelVolumeMapper* mapper)
{
  if (this->MaxMemoryInBytes > 0)
  {
    this->SliceMapper->SetMaxMemoryFraction(this->MaxMemoryFraction);
    this->SliceMapper->SetMaxMemoryInBytes(this->MaxMemoryInBytes);
  }
  // Left at their defaults, the owned mappers keep their own sample distances (see the class
  // documentation for how that differs from vtkSmartVolumeMapper).
  if (this->SampleDistance <= 0 && this->InteractiveAdjustSampleDistances &&
    this->AutoAdjustSampleDistances)
  {
    return;
  }
  vtkRenderWindow* window = renderer->GetRenderWindow();
  const bool interactive = window && window->GetDesiredUpdateRate() >= this->InteractiveUpdateRate;
  const vtkTypeBool autoAdjust =
    this->InteractiveAdjustSampleDistances ? interactive : this->AutoAdjustSampleDistances;
  // An explicit distance is used as given; -1 locks the owned mappers to the input spacing.
  const bool lock = this->SampleDistance <= 0;
  const double distance = lock ? 1.0 : this->SampleDistance;
  if (mapper == this->SliceMapper.GetPointer())
  {
    this->SliceMapper->SetAutoAdjustSampleDistances(autoAdjust);
    this->SliceMapper->SetLockSampleDistanceToInputSpacing(lock);
    this->SliceMapper->SetSampleDistance(distance);
  }
  else if (mapper == this->RayCastMapper.GetPointer())
  {
    this->RayCastMapper->SetAutoAdjustSampleDistances(autoAdjust);
    this->RayCastMapper->SetLockSampleDistanceToInputSpacing(lock);
    this->RayCastMapper->SetSampleDistance(distance);
    this->RayCastMapper->SetInteractiveSampleDistance(2.0 * distance);
  }
}

void vtkAccelVolumeSmartMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->SliceMapper->ReleaseGraphicsResources(window);
  this->RayCastMapper->ReleaseGraphicsResources(window);
  this->ShearWarpMapper->ReleaseGraphicsResources(window);
}

void vtkAccelVolumeSmartMapper::Relay(
  vtkObject* caller, unsigned long event, void* client, void* data)
{
  auto* self = static_cast<vtkAccelVolumeSmartMapper*>(client);
  std::string message = data ? static_cast<const char*>(data) : "";
  // Keep the owned mapper's own text: drop its "vtkClass (0x...): " prefix and trailing blanks.
  const size_t start = message.find("): ");
  if (start != std::string::npos)
  {
    message = message.substr(start + 3);
  }
  while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back())))
  {
    message.pop_back();
  }
  const char* name = caller ? caller->GetClassName() : "mapper";
  if (event == vtkCommand::ErrorEvent)
  {
    vtkErrorWithObjectMacro(self, << name << ": " << message);
  }
  else
  {
    vtkWarningWithObjectMacro(self, << name << ": " << message);
  }
}

void vtkAccelVolumeSmartMapper::Forward(vtkAccelVolumeMapper* mapper)
{
  mapper->SetBlendMode(this->BlendMode);
  mapper->SetCropping(this->Cropping);
  mapper->SetCroppingRegionPlanes(this->CroppingRegionPlanes);
  mapper->SetCroppingRegionFlags(this->CroppingRegionFlags);
  mapper->SetClippingPlanes(this->ClippingPlanes);
  mapper->SetAverageIPScalarRange(this->AverageIPScalarRange);
  mapper->SetScalarMode(this->ScalarMode);
  if (this->ArrayAccessMode == VTK_GET_ARRAY_BY_ID)
  {
    mapper->SelectScalarArray(this->ArrayId);
  }
  else
  {
    mapper->SelectScalarArray(this->ArrayName);
  }
  mapper->SetArrayAccessMode(this->ArrayAccessMode);
  mapper->SetEarlyRayTermination(this->EarlyRayTermination);
  mapper->SetEarlyRayTerminationThreshold(this->EarlyRayTerminationThreshold);
  mapper->SetFinalColorWindow(this->FinalColorWindow);
  mapper->SetFinalColorLevel(this->FinalColorLevel);
  // The input last: a VectorMode reduction overrides the scalar mode.
  this->ConnectInput(mapper);
}

int vtkAccelVolumeSmartMapper::ChooseMode(
  vtkRenderer* renderer, vtkVolume* volume, const int dims[3])
{
  // Can the slice mapper render here, and is its GL hardware?
  std::string sliceBlocker;
  std::string glRenderer;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (!window)
  {
    sliceBlocker = "no OpenGL render window";
  }
  else
  {
    if (!window->IsCurrent())
    {
      window->MakeCurrent();
    }
    const int maximum = vtkTextureObject::GetMaximumTextureSize3D(window);
    const char* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    glRenderer = name ? name : "unknown";
    // Volumes beyond GL_MAX_3D_TEXTURE_SIZE are no blocker: the slice mapper bricks them.
    if (maximum <= 0)
    {
      sliceBlocker = "the OpenGL context has no 3D textures";
    }
  }
  const bool sliceUsable = sliceBlocker.empty();
  const bool hardware = sliceUsable && !IsSoftwareRenderer(glRenderer);

  // Can the shear-warp mapper render this scene?
  std::string shearWarpBlocker;
  vtkCamera* camera = renderer->GetActiveCamera();
  const int blend = this->BlendMode;
  if (blend != COMPOSITE_BLEND && blend != MAXIMUM_INTENSITY_BLEND &&
    blend != MINIMUM_INTENSITY_BLEND)
  {
    shearWarpBlocker = std::string(BlendName(blend)) +
      " blend: shear-warp cannot (composite, "
      "MIP, MinIP only)";
  }
  else if (!camera || !camera->GetParallelProjection())
  {
    shearWarpBlocker = "perspective camera: shear-warp is parallel only";
  }
  else if (this->Cropping)
  {
    shearWarpBlocker = "cropping: shear-warp ignores it";
  }
  else if (this->ClippingPlanes && this->ClippingPlanes->GetNumberOfItems() > 0)
  {
    shearWarpBlocker = "clipping planes: shear-warp ignores them";
  }
  const bool shearWarpUsable = shearWarpBlocker.empty();
  const double allocated = volume->GetAllocatedRenderTime();
  const bool interactive = allocated < 1.0 / this->InteractiveUpdateRate;

  // The automatic choice, optionally without one mapper (the refused requested one).
  auto automatic = [&](int excluded, std::string& reason) -> int
  {
    if (hardware && excluded != SLICE_RENDER)
    {
      reason += "hardware OpenGL (" + glRenderer +
        ") with 3D textures -> slice (fastest of the three where measured on a GPU: "
        "docs/benchmarks/mapper-choice.md)";
      return SLICE_RENDER;
    }
    if (sliceUsable)
    {
      reason += "software OpenGL (" + glRenderer +
        "): the CPU mappers were faster than the slice mapper in every measured case "
        "(docs/benchmarks/mapper-choice.md)";
    }
    else if (excluded != SLICE_RENDER)
    {
      reason += sliceBlocker;
    }
    else
    {
      reason += "no slice"; // the refused slice request already said why
    }
    if (shearWarpUsable && interactive && excluded != SHEARWARP_RENDER)
    {
      reason += std::string("; parallel ") + BlendName(blend) +
        ", no cropping or clipping, interactive frame -> shear-warp (fastest measured on "
        "parallel views)";
      return SHEARWARP_RENDER;
    }
    if (excluded == SHEARWARP_RENDER)
    {
      // The requested shear-warp's blocker already leads the reason.
    }
    else if (!shearWarpUsable)
    {
      reason += "; " + shearWarpBlocker;
    }
    else if (!interactive)
    {
      reason += "; still frame (allocated time >= 1 / InteractiveUpdateRate): exact ray casting "
                "rather than shear-warp's resampling";
    }
    reason += " -> ray cast (fastest measured on perspective views)";
    return RAYCAST_RENDER;
  };

  // A requested mapper that cannot render the scene falls back to the automatic choice.
  std::string reason;
  auto requested = [&](int wanted, const char* name, bool usable, const std::string& blocker)
  {
    if (usable)
    {
      reason = std::string("requested ") + name;
      return wanted;
    }
    reason = std::string("requested ") + name + ", but " + blocker + "; falling back: ";
    return automatic(wanted, reason);
  };
  int mode = RAYCAST_RENDER;
  // Multi-component scalars that VectorMode does not reduce: only the slice mapper renders them.
  int cellFlag = 0;
  vtkDataArray* scalars = this->GetInput()
    ? vtkAbstractMapper::GetScalars(this->GetInput(), this->ScalarMode, this->ArrayAccessMode,
        this->ArrayId, this->ArrayName, cellFlag)
    : nullptr;
  if (scalars && scalars->GetNumberOfComponents() > 1 && this->VectorMode == DISABLED &&
    sliceUsable)
  {
    this->LastChoiceReason = "multi-component scalars (VectorMode DISABLED): only the slice mapper "
                             "renders them -> slice";
    return SLICE_RENDER;
  }
  if (blend == ISOSURFACE_BLEND && sliceUsable)
  {
    this->LastChoiceReason = "isosurface blend: only the slice mapper renders it -> slice";
    return SLICE_RENDER;
  }
  switch (this->RequestedRenderMode)
  {
    case SLICE_RENDER:
      mode = requested(SLICE_RENDER, "slice", sliceUsable, sliceBlocker);
      break;
    case RAYCAST_RENDER:
      mode = requested(RAYCAST_RENDER, "ray cast", true, std::string());
      break;
    case SHEARWARP_RENDER:
      mode = requested(SHEARWARP_RENDER, "shear-warp", shearWarpUsable, shearWarpBlocker);
      break;
    case OSPRAY_RENDER:
      reason = "requested OSPRay, but OSPRay is not available; falling back: ";
      mode = automatic(DEFAULT_RENDER, reason);
      break;
    default:
      mode = automatic(DEFAULT_RENDER, reason);
      break;
  }
  const bool fellBack =
    this->RequestedRenderMode != DEFAULT_RENDER && mode != this->RequestedRenderMode;
  if (fellBack && reason != this->LastWarning)
  {
    this->LastWarning = reason;
    vtkWarningMacro(<< reason);
  }
  this->LastChoiceReason = reason;
  return mode;
}

void vtkAccelVolumeSmartMapper::Render(vtkRenderer* renderer, vtkVolume* volume)
{
  const auto start = std::chrono::steady_clock::now();
  // StartEvent now, the chosen mapper's progress as this mapper's, ProgressEvent 1 and EndEvent
  // on every return.
  vtkAccelVolumeRenderProgress progress(this);
  if (!renderer || !volume)
  {
    vtkErrorMacro("Render needs a renderer and a volume");
    return;
  }
  if (this->GetNumberOfInputConnections(0) == 0)
  {
    this->LastRenderMode = UNDEFINED_RENDER;
    this->LastChoiceReason = "no input: nothing rendered";
    vtkErrorMacro("No input: connect a vtkImageData to the mapper");
    return;
  }
  this->GetInputAlgorithm()->Update();
  int dims[3] = { 0, 0, 0 };
  if (auto* image = vtkImageData::SafeDownCast(this->GetInput()))
  {
    image->GetDimensions(dims);
  }
  const int mode = this->ChooseMode(renderer, volume, dims);
  vtkAccelVolumeMapper* mapper = this->RayCastMapper;
  if (mode == SLICE_RENDER)
  {
    mapper = this->SliceMapper;
  }
  else if (mode == SHEARWARP_RENDER)
  {
    mapper = this->ShearWarpMapper;
  }
  this->LastRenderMode = mode;
  this->Forward(mapper);
  this->ForwardSampleDistances(renderer, mapper);
  // Observed only while it renders for an observed smart mapper: an unobserved mapper keeps its
  // single parallel calls.
  vtkNew<vtkCallbackCommand> forward;
  unsigned long forwardTag = 0;
  if (progress.IsObserved())
  {
    forward->SetClientData(&progress);
    forward->SetCallback([](vtkObject*, unsigned long, void* client, void* data)
      { static_cast<vtkAccelVolumeRenderProgress*>(client)->Report(*static_cast<double*>(data)); });
    forwardTag = mapper->AddObserver(vtkCommand::ProgressEvent, forward);
  }
  // The owned mapper's errors come back through Relay as this mapper's errors.
  mapper->Render(renderer, volume);
  if (forwardTag)
  {
    mapper->RemoveObserver(forwardTag);
  }
  // Connected only while it renders: an owned mapper still connected to the shared producer
  // when this mapper is destroyed kept that producer and its image from being collected
  // (VTK's garbage collector meets this mapper mid-destruction). Its caches key on the scalars,
  // not on the connection, so the next frame reuses them.
  mapper->SetInputConnection(nullptr);
  this->LastRenderTime =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void vtkAccelVolumeSmartMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RequestedRenderMode: " << GetRenderModeAsString(this->RequestedRenderMode)
     << "\n";
  os << indent << "InteractiveUpdateRate: " << this->InteractiveUpdateRate << "\n";
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "AutoAdjustSampleDistances: " << this->AutoAdjustSampleDistances << "\n";
  os << indent << "InteractiveAdjustSampleDistances: " << this->InteractiveAdjustSampleDistances
     << "\n";
  os << indent << "VectorMode: " << this->VectorMode << "\n";
  os << indent << "VectorComponent: " << this->VectorComponent << "\n";
  os << indent << "MaxMemoryInBytes: " << this->MaxMemoryInBytes << "\n";
  os << indent << "MaxMemoryFraction: " << this->MaxMemoryFraction << "\n";
  os << indent << "InterpolationMode: " << this->InterpolationMode << "\n";
  os << indent << "LastRenderMode: " << GetRenderModeAsString(this->LastRenderMode) << "\n";
  os << indent << "LastChoiceReason: " << this->LastChoiceReason << "\n";
  os << indent << "SliceMapper: " << this->SliceMapper.GetPointer() << "\n";
  os << indent << "RayCastMapper: " << this->RayCastMapper.GetPointer() << "\n";
  os << indent << "ShearWarpMapper: " << this->ShearWarpMapper.GetPointer() << "\n";
}
