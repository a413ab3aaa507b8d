// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiExactSurfaceMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkGarbageCollector.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderPass.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPiRayCaster.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkScalarsToColors.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkTimerLog.h"

#include "vtk_glew.h"

#include "PiTiming.h"
#include "RayCasting/PiRayViews.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkPiExactSurfaceMapper);

namespace
{
// The fragment shader of the full-viewport quad: the colour and the depth of the hit
// of each pixel; pixels without a hit (depth outside [0, 1]) are discarded.
const char* const QuadFragmentShader = R"(//VTK::System::Dec
in vec2 texCoord;
uniform sampler2D colourTexture;
uniform sampler2D depthTexture;
//VTK::Output::Dec
void main()
{
  float depth = texture(depthTexture, texCoord).r;
  if (depth < 0.0 || depth > 1.0)
  {
    discard;
  }
  gl_FragData[0] = texture(colourTexture, texCoord);
  gl_FragDepth = depth;
}
)";

void Normalize3(double v[3])
{
  const double n = vtkMath::Norm(v);
  if (n > 0.0)
  {
    v[0] /= n;
    v[1] /= n;
    v[2] /= n;
  }
}
}

vtkFieldData* vtkPiExactSurfaceMapper::FindModelFieldData(vtkDataObject* data)
{
  if (!data)
  {
    return nullptr;
  }
  // A molecule of any size or mode carries its atoms and settings (PiMoleculeSettings),
  // which the caster reads; a Global one of few atoms carries a PiSurfaceModel too.
  vtkFieldData* fd = data->GetFieldData();
  if (fd && (fd->GetAbstractArray("PiSurfaceModel") || fd->GetAbstractArray("PiMoleculeSettings")))
  {
    return fd;
  }
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(data))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      if (vtkFieldData* leaf = FindModelFieldData(it->GetCurrentDataObject()))
      {
        return leaf;
      }
    }
  }
  return nullptr;
}

struct vtkPiExactSurfaceMapper::Internals
{
  vtkNew<vtkPiRayCaster> Caster;
  vtkNew<vtkPolyData> Carrier;         // the model's field data, the caster's input
  vtkFieldData* CarriedFrom = nullptr; // the field data the carrier copied
  vtkMTimeType CarriedTime = 0;
  vtkDataObject* WarnedInput = nullptr; // the input last warned about
  bool WarnedMemory = false;
  bool WarnedTranslucent = false;
  vtkMTimeType RefusedTime = 0; // the carrier's time when the caster refused its model

  int W = 0, H = 0; // the image of the last cast (rays)
  std::vector<unsigned char> Colour;
  std::vector<float> Depth;
  std::vector<double> FactorColours; // RGBA per factor index from FactorBase on
  int FactorBase = 0;

  vtkSmartPointer<vtkTextureObject> ColourTexture;
  vtkSmartPointer<vtkTextureObject> DepthTexture;
  std::unique_ptr<vtkOpenGLQuadHelper> Quad;
};

vtkPiExactSurfaceMapper::vtkPiExactSurfaceMapper()
  : Internal(new Internals)
{
  this->Internal->Caster->SetViewMode(vtkPiRayCaster::CAMERA);
  this->Internal->Caster->SetAllHits(false);
  this->Internal->Caster->SetInputData(this->Internal->Carrier);
}

vtkPiExactSurfaceMapper::~vtkPiExactSurfaceMapper()
{
  this->SetModelData(nullptr);
}

void vtkPiExactSurfaceMapper::SetModelData(vtkDataObject* data)
{
  vtkSetObjectBodyMacro(ModelData, vtkDataObject, data);
}

vtkPiRayCaster* vtkPiExactSurfaceMapper::GetRayCaster()
{
  return this->Internal->Caster;
}

vtkMTimeType vtkPiExactSurfaceMapper::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->ModelData)
  {
    t = std::max(t, this->ModelData->GetMTime());
  }
  return t;
}

int vtkPiExactSurfaceMapper::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

void vtkPiExactSurfaceMapper::ReportReferences(vtkGarbageCollector* collector)
{
  this->Superclass::ReportReferences(collector);
  vtkGarbageCollectorReport(collector, this->ModelData, "ModelData");
}

void vtkPiExactSurfaceMapper::UpdateInput()
{
  // As VTK's mappers do, unless Static: a prop without bounds is culled before it renders.
  if (this->GetNumberOfInputConnections(0) > 0 && !this->Static)
  {
    this->Update();
  }
}

double* vtkPiExactSurfaceMapper::GetBounds()
{
  vtkMath::UninitializeBounds(this->Bounds);
  this->UpdateInput();
  vtkDataObject* data =
    this->GetNumberOfInputConnections(0) ? this->GetInputDataObject(0, 0) : this->ModelData;
  if (auto* ds = vtkDataSet::SafeDownCast(data))
  {
    if (ds->GetNumberOfPoints() > 0)
    {
      ds->GetBounds(this->Bounds);
    }
  }
  else if (auto* composite = vtkCompositeDataSet::SafeDownCast(data))
  {
    composite->GetBounds(this->Bounds);
  }
  return this->Bounds;
}

void vtkPiExactSurfaceMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  Internals& in = *this->Internal;
  if (in.Quad)
  {
    in.Quad->ReleaseGraphicsResources(window);
    in.Quad.reset();
  }
  if (in.ColourTexture)
  {
    in.ColourTexture->ReleaseGraphicsResources(window);
    in.ColourTexture = nullptr;
  }
  if (in.DepthTexture)
  {
    in.DepthTexture->ReleaseGraphicsResources(window);
    in.DepthTexture = nullptr;
  }
}

void vtkPiExactSurfaceMapper::Render(vtkRenderer* ren, vtkActor* actor)
{
  Internals& in = *this->Internal;
  this->Drawn = false;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!window || ren->GetSelector())
  {
    return;
  }
  // Depth peeling and order-independent translucency draw translucent props with shader
  // code of their own that the quad does not carry.
  vtkInformation* keys = actor->GetPropertyKeys();
  if (actor->HasTranslucentPolygonalGeometry() && keys &&
    keys->Length(vtkOpenGLRenderPass::RenderPasses()) > 0)
  {
    if (!in.WarnedTranslucent)
    {
      vtkWarningMacro("A translucent exact surface cannot be drawn by the renderer's depth "
                      "peeling or order-independent translucency: turn the actor's ForceOpaque "
                      "on (the surface then blends over what was drawn before it) or both off.");
      in.WarnedTranslucent = true;
    }
    return;
  }
  this->UpdateInput();
  vtkDataObject* source = this->ModelData
    ? this->ModelData
    : (this->GetNumberOfInputConnections(0) ? this->GetInputDataObject(0, 0) : nullptr);
  vtkFieldData* fd = FindModelFieldData(source);
  if (!fd)
  {
    if (this->WarnMissingModel && source && in.WarnedInput != source)
    {
      vtkWarningMacro("The input (" << source->GetClassName()
                                    << ") carries no PiSurfaceModel or PiMoleculeSettings field "
                                       "data: nothing to draw.");
      in.WarnedInput = source;
    }
    return;
  }
  in.WarnedInput = nullptr;
  if (fd != in.CarriedFrom || fd->GetMTime() != in.CarriedTime)
  {
    in.Carrier->GetFieldData()->ShallowCopy(fd);
    in.Carrier->Modified();
    in.CarriedFrom = fd;
    in.CarriedTime = fd->GetMTime();
  }

  int width, height, x0, y0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  if (width < 1 || height < 1)
  {
    return;
  }
  // The reduction: ReductionFactor, or InteractiveReductionFactor if larger in an
  // interactive render, raised until the cast fits the caster's cap.
  const bool interactive = window->GetDesiredUpdateRate() >= 1.0;
  const int requested =
    std::max(this->ReductionFactor, interactive ? this->InteractiveReductionFactor : 1);
  int r = requested;
  std::string error;
  while (!pisurf::RayViews::CheckMemory((width + r - 1) / r, (height + r - 1) / r, 1, error))
  {
    ++r;
  }
  if (r > requested && !in.WarnedMemory)
  {
    vtkWarningMacro("A full cast of " << width << " x " << height
                                      << " pixels exceeds the ray caster's memory cap; the exact "
                                         "view casts one ray per "
                                      << r << " x " << r << " pixels.");
    in.WarnedMemory = true;
  }
  const int w = (width + r - 1) / r;
  const int h = (height + r - 1) / r;

  vtkCamera* camera = ren->GetActiveCamera();
  vtkPiRayCaster* caster = in.Caster;
  caster->SetResolution(w, h);
  caster->SetCameraPosition(camera->GetPosition());
  caster->SetCameraFocalPoint(camera->GetFocalPoint());
  caster->SetCameraViewUp(camera->GetViewUp());
  double angle = camera->GetViewAngle();
  if (camera->GetUseHorizontalViewAngle())
  {
    angle = vtkMath::DegreesFromRadians(
      2.0 * std::atan(std::tan(vtkMath::RadiansFromDegrees(angle) / 2.0) * height / width));
  }
  caster->SetViewAngle(angle);
  caster->SetParallelProjection(camera->GetParallelProjection() != 0);
  caster->SetParallelScale(camera->GetParallelScale());
  // A model the caster refused (its error is in the output window) is not cast again
  // until it changes: the error is not repeated at every camera move.
  if (in.RefusedTime == in.Carrier->GetMTime())
  {
    return;
  }
  // PISURF_TIMING=1: the time of the cast, the shading, the upload and the drawing.
  pisurf::PassTimer lap("vtkPiExactSurfaceMapper");
  const vtkMTimeType before = caster->GetOutput()->GetMTime();
  vtkNew<vtkTimerLog> timer;
  timer->StartTimer();
  const bool cast = this->NumberOfPieces > 1
    ? caster->UpdatePiece(this->Piece, this->NumberOfPieces, 0) != 0
    : caster->GetExecutive()->Update() != 0;
  timer->StopTimer();
  lap("cast");
  if (!cast)
  {
    in.RefusedTime = in.Carrier->GetMTime();
    this->HitRows[0] = this->HitRows[1] = -1;
    return;
  }
  in.RefusedTime = 0;
  vtkPolyData* hits = caster->GetOutput();
  if (hits->GetMTime() != before)
  {
    ++this->CastCount;
    this->LastCastSeconds = timer->GetElapsedTime();
  }
  this->CastResolution[0] = w;
  this->CastResolution[1] = h;

  // Depth of each hit in the window's depth range, colour from the lights.
  in.W = w;
  in.H = h;
  in.Depth.assign(size_t(w) * h, 2.0f);
  in.Colour.assign(size_t(w) * h * 4, 0);
  vtkDataArray* pixels = hits->GetPointData()->GetArray("PixelIndex");
  vtkDataArray* normals = hits->GetPointData()->GetArray("Normals");
  vtkDataArray* factors = hits->GetPointData()->GetArray("Factor");
  vtkDataArray* singular = hits->GetPointData()->GetArray("Singular");
  const vtkIdType n = hits->GetNumberOfPoints();
  this->HitRows[0] = this->HitRows[1] = -1;
  if (n > 0 && pixels)
  {
    double rows[2];
    pixels->GetRange(rows, 1);
    this->HitRows[0] = static_cast<int>(rows[0]);
    this->HitRows[1] = static_cast<int>(rows[1]);
  }
  if (n > 0 && pixels && normals)
  {
    vtkMatrix4x4* projection =
      camera->GetCompositeProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1, 1);
    double m[16];
    vtkMatrix4x4::DeepCopy(m, projection);

    vtkProperty* property = actor->GetProperty();
    double ambientColour[3], diffuseColour[3], specularColour[3];
    property->GetAmbientColor(ambientColour);
    property->GetDiffuseColor(diffuseColour);
    property->GetSpecularColor(specularColour);
    const double ambient = property->GetAmbient();
    const double diffuse = property->GetDiffuse();
    const double specular = property->GetSpecular();
    const double power = property->GetSpecularPower();
    const double opacity = property->GetOpacity();

    // The lights, as directions towards the light (or positions) in world coordinates.
    struct Light
    {
      bool Positional;
      double L[3];
      double Diffuse[3];
      double Specular[3];
    };
    std::vector<Light> lights;
    vtkLightCollection* collection = ren->GetLights();
    vtkCollectionSimpleIterator lit;
    collection->InitTraversal(lit);
    while (vtkLight* light = collection->GetNextLight(lit))
    {
      if (!light->GetSwitch() || light->GetIntensity() <= 0.0)
      {
        continue;
      }
      Light l;
      double position[3], focal[3];
      light->GetTransformedPosition(position);
      light->GetTransformedFocalPoint(focal);
      l.Positional = light->GetPositional() != 0;
      for (int c = 0; c < 3; ++c)
      {
        l.L[c] = l.Positional ? position[c] : position[c] - focal[c];
        l.Diffuse[c] = light->GetDiffuseColor()[c] * light->GetIntensity();
        l.Specular[c] = light->GetSpecularColor()[c] * light->GetIntensity();
      }
      if (!l.Positional)
      {
        Normalize3(l.L);
      }
      lights.push_back(l);
    }
    double toCamera[3];
    camera->GetDirectionOfProjection(toCamera);
    for (double& c : toCamera)
    {
      c = -c;
    }

    // Colour by Factor through the lookup table, or the solid colour.
    vtkScalarsToColors* table = nullptr;
    if (factors && this->GetScalarVisibility() && this->GetArrayName() &&
      std::strcmp(this->GetArrayName(), "Factor") == 0)
    {
      table = this->GetLookupTable();
      if (!this->GetUseLookupTableScalarRange())
      {
        table->SetRange(this->ScalarRange);
      }
      table->Build();
      // The table's colour of each factor index present (the tables are not
      // reentrant, so they are asked here, once per index).
      double range[2];
      factors->GetRange(range, 0);
      if (range[0] > range[1] || range[1] - range[0] > 1e7)
      {
        table = nullptr;
      }
      else
      {
        in.FactorBase = static_cast<int>(std::floor(range[0]));
        const int count = static_cast<int>(std::floor(range[1])) - in.FactorBase + 1;
        in.FactorColours.resize(size_t(count) * 4);
        for (int f = 0; f < count; ++f)
        {
          double* rgba = &in.FactorColours[4 * size_t(f)];
          table->GetColor(in.FactorBase + f, rgba);
          rgba[3] = table->GetOpacity(in.FactorBase + f);
        }
      }
    }

    vtkSMPTools::For(0, n,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType k = begin; k < end; ++k)
        {
          const int i = static_cast<int>(pixels->GetComponent(k, 0));
          const int j = static_cast<int>(pixels->GetComponent(k, 1));
          if (i < 0 || i >= w || j < 0 || j >= h)
          {
            continue;
          }
          double p[3];
          hits->GetPoint(k, p);
          const double zc = m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11];
          const double wc = m[12] * p[0] + m[13] * p[1] + m[14] * p[2] + m[15];
          const double depth = 0.5 * zc / wc + 0.5;
          if (!(depth >= 0.0 && depth <= 1.0))
          {
            continue;
          }
          const size_t pixel = size_t(j) * w + i;
          in.Depth[pixel] = static_cast<float>(depth);

          double nrm[3];
          normals->GetTuple(k, nrm);
          double view[3] = { toCamera[0], toCamera[1], toCamera[2] };
          if (!camera->GetParallelProjection())
          {
            const double* eye = camera->GetPosition();
            for (int c = 0; c < 3; ++c)
            {
              view[c] = eye[c] - p[c];
            }
            Normalize3(view);
          }
          if (vtkMath::Dot(nrm, view) < 0.0)
          {
            nrm[0] = -nrm[0];
            nrm[1] = -nrm[1];
            nrm[2] = -nrm[2];
          }
          double base[3] = { diffuseColour[0], diffuseColour[1], diffuseColour[2] };
          double amb[3] = { ambientColour[0], ambientColour[1], ambientColour[2] };
          double alpha = opacity;
          if (table)
          {
            const int f = static_cast<int>(factors->GetComponent(k, 0)) - in.FactorBase;
            const double* rgba = &in.FactorColours[4 * size_t(f)];
            for (int q = 0; q < 3; ++q)
            {
              base[q] = rgba[q];
              amb[q] = rgba[q];
            }
            if (table->IsOpaque() == 0)
            {
              alpha *= rgba[3];
            }
          }
          double colour[3] = { ambient * amb[0], ambient * amb[1], ambient * amb[2] };
          for (const Light& l : lights)
          {
            double L[3] = { l.L[0], l.L[1], l.L[2] };
            if (l.Positional)
            {
              for (int c = 0; c < 3; ++c)
              {
                L[c] -= p[c];
              }
              Normalize3(L);
            }
            const double nl = vtkMath::Dot(nrm, L);
            if (nl <= 0.0)
            {
              continue;
            }
            double reflected[3];
            for (int c = 0; c < 3; ++c)
            {
              reflected[c] = 2.0 * nl * nrm[c] - L[c];
            }
            const double rv = std::max(1e-10, vtkMath::Dot(reflected, view));
            const double sf = std::pow(rv, power);
            for (int c = 0; c < 3; ++c)
            {
              colour[c] += diffuse * base[c] * l.Diffuse[c] * nl +
                specular * specularColour[c] * l.Specular[c] * sf;
            }
          }
          if (this->MarkSingular && singular && singular->GetComponent(k, 0) != 0.0)
          {
            colour[0] = 1.0;
            colour[1] = 0.0;
            colour[2] = 0.0;
          }
          unsigned char* out = &in.Colour[4 * pixel];
          for (int c = 0; c < 3; ++c)
          {
            out[c] = static_cast<unsigned char>(
              std::lround(255.0 * vtkMath::ClampValue(colour[c], 0.0, 1.0)));
          }
          out[3] =
            static_cast<unsigned char>(std::lround(255.0 * vtkMath::ClampValue(alpha, 0.0, 1.0)));
        }
      });
  }

  lap("shade");
  // Upload and draw.
  if (!in.ColourTexture)
  {
    in.ColourTexture = vtkSmartPointer<vtkTextureObject>::New();
    in.DepthTexture = vtkSmartPointer<vtkTextureObject>::New();
  }
  in.ColourTexture->SetContext(window);
  in.DepthTexture->SetContext(window);
  in.ColourTexture->Create2DFromRaw(w, h, 4, VTK_UNSIGNED_CHAR, in.Colour.data());
  in.DepthTexture->Create2DFromRaw(w, h, 1, VTK_FLOAT, in.Depth.data());
  for (vtkTextureObject* t : { in.ColourTexture.GetPointer(), in.DepthTexture.GetPointer() })
  {
    t->SetMinificationFilter(vtkTextureObject::Nearest);
    t->SetMagnificationFilter(vtkTextureObject::Nearest);
    t->SetWrapS(vtkTextureObject::ClampToEdge);
    t->SetWrapT(vtkTextureObject::ClampToEdge);
  }
  lap("upload");
  if (!in.Quad)
  {
    in.Quad.reset(new vtkOpenGLQuadHelper(window, nullptr, QuadFragmentShader, nullptr));
  }
  else
  {
    window->GetShaderCache()->ReadyShaderProgram(in.Quad->Program);
  }
  if (!in.Quad->Program || !in.Quad->Program->GetCompiled())
  {
    vtkErrorMacro("The exact view's shader did not compile.");
    return;
  }
  vtkOpenGLState* state = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_TRUE);
  in.ColourTexture->Activate();
  in.DepthTexture->Activate();
  in.Quad->Program->SetUniformi("colourTexture", in.ColourTexture->GetTextureUnit());
  in.Quad->Program->SetUniformi("depthTexture", in.DepthTexture->GetTextureUnit());
  in.Quad->Render();
  in.DepthTexture->Deactivate();
  in.ColourTexture->Deactivate();
  if (lap.IsEnabled())
  {
    glFinish(); // the drawing, not just its queueing
    lap("draw");
  }
  this->Drawn = true;
}

void vtkPiExactSurfaceMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ModelData: " << this->ModelData << "\n";
  os << indent << "ReductionFactor: " << this->ReductionFactor << "\n";
  os << indent << "InteractiveReductionFactor: " << this->InteractiveReductionFactor << "\n";
  os << indent << "MarkSingular: " << this->MarkSingular << "\n";
  os << indent << "WarnMissingModel: " << this->WarnMissingModel << "\n";
  os << indent << "Piece: " << this->Piece << " of " << this->NumberOfPieces << "\n";
  os << indent << "HitRows: " << this->HitRows[0] << " to " << this->HitRows[1] << "\n";
  os << indent << "CastCount: " << this->CastCount << "\n";
}
