// SPDX-License-Identifier: BSD-3-Clause
// vtkPiRayCaster: exact hits and depths against closed forms, no missed thin features,
// singular classification (cylinder crease, cone apex), pipeline input, bad settings.
#include "PiTestUtilities.h"

#include "vtkPiPrimitive.h"
#include "vtkPiRayCaster.h"
#include "vtkPiSurface.h"
#include "vtkPiSurfaceSource.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkDirectory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <array>

#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <tuple>

namespace
{
vtkDataArray* Array(vtkPolyData* p, const char* name)
{
  return p->GetPointData()->GetArray(name);
}

// Six axis views with every hit (or the first hits: then the octree also stops each
// leaf column where its rays have provably met a root), empty-space skipping on and
// off: the same hits (per view, pixel and hit index), depths within 1e-9 of the model
// size (both are roots to 1e-10 of it), the same Tangent and Singular flags. Returns
// the number of hits, or −1 (with a message) on a difference.
long SameHitsWithAndWithoutSkipping(vtkPiSurface* model, int w, int h, const std::string& name,
  const std::function<void(vtkPiRayCaster*)>& view = nullptr, bool allHits = true)
{
  using Key = std::tuple<int, int, int, int>;
  std::map<Key, std::array<double, 3>> hits[2];
  for (int skip = 0; skip < 2; ++skip)
  {
    vtkNew<vtkPiRayCaster> caster;
    caster->SetPiSurface(model);
    caster->SetViewMode(vtkPiRayCaster::SIX_AXIS_VIEWS);
    if (view)
    {
      view(caster);
    }
    caster->SetResolution(w, h);
    caster->SetAllHits(allHits);
    caster->SetSkipEmptySpace(skip == 1);
    caster->Update();
    vtkPolyData* out = caster->GetOutput();
    vtkDataArray* pixel = Array(out, "PixelIndex");
    vtkDataArray* view = Array(out, "ViewIndex");
    vtkDataArray* index = Array(out, "HitIndex");
    vtkDataArray* depth = Array(out, "Depth");
    vtkDataArray* tangent = Array(out, "Tangent");
    vtkDataArray* singular = Array(out, "Singular");
    for (vtkIdType k = 0; k < out->GetNumberOfPoints(); ++k)
    {
      hits[skip][Key(static_cast<int>(view->GetTuple1(k)),
        static_cast<int>(pixel->GetComponent(k, 0)), static_cast<int>(pixel->GetComponent(k, 1)),
        static_cast<int>(index->GetTuple1(k)))] = { depth->GetTuple1(k), tangent->GetTuple1(k),
        singular->GetTuple1(k) };
    }
  }
  double b[6];
  model->GetModelBounds(b);
  const double size = std::sqrt(
    (b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
  long differences = 0;
  for (const auto& hit : hits[0])
  {
    const auto other = hits[1].find(hit.first);
    if (other == hits[1].end() || std::fabs(other->second[0] - hit.second[0]) > 1e-9 * size ||
      other->second[1] != hit.second[1] || other->second[2] != hit.second[2])
    {
      if (differences < 5)
      {
        std::cerr << name << ": view " << std::get<0>(hit.first) << " pixel ("
                  << std::get<1>(hit.first) << ", " << std::get<2>(hit.first) << ") hit "
                  << std::get<3>(hit.first) << ": depth " << hit.second[0] << " tangent "
                  << hit.second[1] << " singular " << hit.second[2];
        if (other != hits[1].end())
        {
          std::cerr << "; with skipping " << other->second[0] << " tangent " << other->second[1]
                    << " singular " << other->second[2];
        }
        std::cerr << "\n";
      }
      ++differences;
    }
  }
  if (differences > 0 || hits[0].size() != hits[1].size())
  {
    std::cerr << name << ": " << hits[0].size() << " hits without skipping, " << hits[1].size()
              << " with, " << differences << " differ\n";
    return -1;
  }
  return static_cast<long>(hits[0].size());
}
}

int TestPiRayCaster(int, char*[])
{
  int failures = 0;

  // A unit sphere seen along −Z over [-2, 2]³: hits where the pixel centre is inside the
  // unit disc, at depth 2 − sqrt(1 − x² − y²) (all hits: also 2 + sqrt(...)).
  vtkNew<vtkPiSurface> sphere;
  vtkNew<vtkPiPrimitive> unit;
  sphere->AddFactor(unit);
  vtkNew<vtkPiRayCaster> caster;
  pitest::Watch watch(caster);
  caster->SetPiSurface(sphere);
  caster->SetResolution(40, 30);
  caster->SetBounds(-2, 2, -2, 2, -2, 2);
  caster->AllHitsOn();
  caster->Update();
  PI_CHECK(watch.Quiet());
  vtkPolyData* hits = caster->GetOutput();
  int expected = 0;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 30; ++j)
    {
      const double x = -2 + (i + 0.5) * 4 / 40, y = -2 + (j + 0.5) * 4 / 30;
      expected += x * x + y * y < 1 ? 2 : 0;
    }
  PI_CHECK(hits->GetNumberOfPoints() == expected);
  vtkDataArray* depth = Array(hits, "Depth");
  vtkDataArray* pixel = Array(hits, "PixelIndex");
  vtkDataArray* index = Array(hits, "HitIndex");
  vtkDataArray* singular = Array(hits, "Singular");
  vtkDataArray* normals = hits->GetPointData()->GetNormals();
  PI_CHECK(depth && pixel && index && singular && normals && Array(hits, "ViewIndex") &&
    Array(hits, "Tangent") && Array(hits, "Factor") && Array(hits, "GradientMagnitude"));
  for (vtkIdType k = 0; depth && k < hits->GetNumberOfPoints(); ++k)
  {
    const double x = -2 + (pixel->GetComponent(k, 0) + 0.5) * 4 / 40;
    const double y = -2 + (pixel->GetComponent(k, 1) + 0.5) * 4 / 30;
    const double h = std::sqrt(1 - x * x - y * y);
    PI_CHECK_NEAR(depth->GetTuple1(k), index->GetTuple1(k) == 0 ? 2 - h : 2 + h, 1e-9);
    double p[3], n[3];
    hits->GetPoint(k, p);
    normals->GetTuple(k, n);
    PI_CHECK_NEAR(n[0] * p[0] + n[1] * p[1] + n[2] * p[2], 1.0, 1e-6); // outward unit normal
    PI_CHECK(singular->GetTuple1(k) == 0);
  }

  // A torus of minor radius 0.01 seen along −Z: every pixel whose centre is over the tube
  // is hit (zero missed rays), and no other.
  vtkNew<vtkPiSurface> ring;
  vtkNew<vtkPiPrimitive> torus;
  torus->SetTypeToTorus();
  torus->SetMajorRadius(1.0);
  torus->SetMinorRadius(0.01);
  ring->AddFactor(torus);
  caster->SetPiSurface(ring);
  caster->SetBounds(-1.1, 1.1, -1.1, 1.1, -0.1, 0.1);
  caster->SetResolution(301, 301);
  caster->AllHitsOff();
  caster->Update();
  int over = 0;
  for (int i = 0; i < 301; ++i)
    for (int j = 0; j < 301; ++j)
    {
      const double x = -1.1 + (i + 0.5) * 2.2 / 301, y = -1.1 + (j + 0.5) * 2.2 / 301;
      const double rho = std::sqrt(x * x + y * y) - 1;
      over += rho * rho < 0.01 * 0.01 ? 1 : 0;
    }
  std::cout << "thin torus: " << caster->GetOutput()->GetNumberOfPoints() << " hits, " << over
            << " pixels over the tube\n";
  PI_CHECK(over > 100);
  PI_CHECK(caster->GetOutput()->GetNumberOfPoints() == over);

  // Thin and small features for the empty-space skipping, in a blend (r > 0: every
  // factor's zero set shifts, none is a plane of the views): a tilted torus of minor
  // radius 0.01, spheres of radius 0.03 and two spheres 1e-4 apart; every root of the
  // six views with all hits is found with skipping as without.
  {
    vtkNew<vtkPiSurface> thin;
    vtkNew<vtkPiPrimitive> tube;
    tube->SetTypeToTorus();
    tube->SetMajorRadius(0.8);
    tube->SetMinorRadius(0.01);
    tube->SetAxis(0.3, 1, 0.2);
    tube->SetCenter(0.05, -0.02, 0.1);
    thin->AddFactor(tube);
    const double centres[4][3] = { { 0.5, 0.4, -0.3 }, { -0.6, 0.1, 0.5 }, { 0.2, -0.7, 0.0 },
      { 0.2 + 0.0601, -0.7, 0.0 } };
    for (const auto& c : centres)
    {
      vtkNew<vtkPiPrimitive> ball;
      ball->SetCenter(c[0], c[1], c[2]);
      ball->SetRadius(0.03);
      thin->AddFactor(ball);
    }
    thin->SetBlending(1e-12);
    const double cube[6] = { -1, 1, -1, 1, -1, 1 };
    thin->SetModelBounds(cube);
    const long found = SameHitsWithAndWithoutSkipping(thin, 150, 130, "thin features");
    std::cout << "thin features, six views, all hits: " << found
              << " hits with and without skipping\n";
    PI_CHECK(found > 1000);
    PI_CHECK(SameHitsWithAndWithoutSkipping(
               thin, 150, 130, "thin features, first hits", nullptr, false) > 500);
    // Camera views (perspective and parallel, oblique), from outside the bounds and from
    // inside them (the frustum's near end at the eye).
    for (const bool parallel : { false, true })
    {
      for (const bool inside : { false, true })
      {
        const std::string name = std::string("thin features, ") +
          (parallel ? "parallel" : "perspective") + " camera" + (inside ? " inside" : "");
        const long camera = SameHitsWithAndWithoutSkipping(thin, 121, 97, name,
          [&](vtkPiRayCaster* c)
          {
            c->SetViewMode(vtkPiRayCaster::CAMERA);
            c->SetCameraPosition(inside ? 0.1 : 2.5, inside ? -0.2 : -3.0, inside ? 0.05 : 1.7);
            c->SetCameraFocalPoint(0.3, 0.2, -0.1);
            c->SetCameraViewUp(0.1, 0.3, 1.0);
            c->SetViewAngle(inside ? 100.0 : 40.0);
            c->SetParallelProjection(parallel);
            c->SetParallelScale(1.2);
          });
        std::cout << name << ", all hits: " << camera << " hits with and without skipping\n";
        PI_CHECK(camera > 50);
      }
    }
  }

  // Crossed cylinders with r = 0 seen along −Z: their intersection curves project onto
  // x = ±y; the hits there have a vanishing gradient and are Singular.
  vtkNew<vtkPiSurface> crossed;
  vtkNew<vtkPiPrimitive> alongX, alongY;
  alongX->SetTypeToCylinder();
  alongX->SetAxis(1, 0, 0);
  alongY->SetTypeToCylinder();
  alongY->SetAxis(0, 1, 0);
  crossed->AddFactor(alongX);
  crossed->AddFactor(alongY);
  caster->SetPiSurface(crossed);
  caster->SetBounds(-2, 2, -2, 2, -2, 2);
  caster->SetResolution(64, 64);
  caster->Update();
  vtkPolyData* crease = caster->GetOutput();
  vtkDataArray* creaseSingular = Array(crease, "Singular");
  int singularHits = 0;
  for (vtkIdType k = 0; k < crease->GetNumberOfPoints(); ++k)
  {
    if (creaseSingular->GetTuple1(k) != 0)
    {
      double p[3];
      crease->GetPoint(k, p);
      PI_CHECK_NEAR(std::fabs(p[0]), std::fabs(p[1]), 4.0 / 64);
      ++singularHits;
    }
  }
  std::cout << "crossed cylinders: " << singularHits << " singular hits\n";
  PI_CHECK(singularHits >= 8);

  // A cone's apex: the ray along the x axis touches it there (a tangent, singular hit).
  vtkNew<vtkPiSurface> cone;
  vtkNew<vtkPiPrimitive> conePrimitive;
  conePrimitive->SetTypeToCone();
  conePrimitive->SetAngle(30);
  cone->AddFactor(conePrimitive);
  caster->SetPiSurface(cone);
  caster->SetViewMode(vtkPiRayCaster::MINUS_X);
  caster->SetResolution(17, 17); // the middle pixel's ray is the x axis
  caster->AllHitsOn();
  caster->Update();
  vtkPolyData* apexHits = caster->GetOutput();
  bool apex = false;
  for (vtkIdType k = 0; k < apexHits->GetNumberOfPoints(); ++k)
  {
    double p[3];
    apexHits->GetPoint(k, p);
    if (std::fabs(p[0]) < 1e-4 && std::fabs(p[1]) < 1e-12 && std::fabs(p[2]) < 1e-12)
    {
      apex = Array(apexHits, "Singular")->GetTuple1(k) != 0 &&
        Array(apexHits, "Tangent")->GetTuple1(k) != 0;
    }
  }
  PI_CHECK(apex);

  // Through the pipeline: the model comes with the source's output; six views see the
  // paper's two spheres, every hit exact.
  vtkNew<vtkPiSurfaceSource> source;
  source->GeneratePrimitivesOff();
  source->SetResolution(16);
  vtkNew<vtkPiRayCaster> fromInput;
  fromInput->SetInputConnection(source->GetOutputPort());
  fromInput->SetViewMode(vtkPiRayCaster::SIX_AXIS_VIEWS);
  fromInput->SetResolution(48, 48);
  fromInput->Update();
  vtkPolyData* six = fromInput->GetOutput();
  PI_CHECK(Array(six, "ViewIndex") && Array(six, "ViewIndex")->GetRange()[1] == 5);
  vtkNew<vtkPiSurface> twoSpheres;
  PI_CHECK(twoSpheres->SetModelJSON(source->GetModel()));
  double worst = 0;
  for (vtkIdType k = 0; k < six->GetNumberOfPoints(); ++k)
  {
    double p[3], g[3];
    six->GetPoint(k, p);
    twoSpheres->EvaluateGradient(p, g);
    worst = std::max(worst,
      std::fabs(twoSpheres->EvaluateFunction(p)) /
        std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]));
  }
  PI_CHECK(six->GetNumberOfPoints() > 1000);
  PI_CHECK(worst <= 1e-9 * 5);
  PI_CHECK(six->GetFieldData()->GetAbstractArray("PiRayViews") != nullptr);

  // Every paper model, six views: each regular hit is on F = 0 to 1e-9 of the model
  // size (singular hits are excluded: there |F|/|∇F| says nothing about the distance).
  vtkNew<vtkDirectory> listing;
  listing->Open(PISURF_MODELS_DIR);
  int models = 0;
  for (vtkIdType f = 0; f < listing->GetNumberOfFiles(); ++f)
  {
    const std::string file = listing->GetFile(f);
    if (file.size() < 7 || file.substr(file.size() - 7) != ".pisurf")
    {
      continue;
    }
    ++models;
    vtkNew<vtkPiSurface> model;
    PI_CHECK(model->LoadModel(pitest::ModelPath(file).c_str()));
    vtkNew<vtkPiRayCaster> views;
    views->SetPiSurface(model);
    views->SetViewMode(vtkPiRayCaster::SIX_AXIS_VIEWS);
    views->SetResolution(32, 32);
    views->Update();
    vtkPolyData* out = views->GetOutput();
    double b[6];
    model->GetModelBounds(b);
    const double size = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
      (b[5] - b[4]) * (b[5] - b[4]));
    vtkDataArray* flags = Array(out, "Singular");
    double worstHit = 0;
    for (vtkIdType k = 0; flags && k < out->GetNumberOfPoints(); ++k)
    {
      if (flags->GetTuple1(k) != 0)
      {
        continue;
      }
      double p[3], g[3];
      out->GetPoint(k, p);
      model->EvaluateGradient(p, g);
      worstHit = std::max(worstHit,
        std::fabs(model->EvaluateFunction(p)) / std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]));
    }
    if (!(out->GetNumberOfPoints() > 100 && worstHit <= 1e-9 * size))
    {
      std::cerr << file << ": " << out->GetNumberOfPoints() << " hits, worst |F|/|grad F| "
                << worstHit << " (size " << size << ")\n";
      ++failures;
    }
    // Empty-space skipping finds the same roots (an odd image size leaves partial tiles),
    // in the six axis views and in an oblique perspective camera.
    PI_CHECK(SameHitsWithAndWithoutSkipping(model, 75, 61, file) > 100);
    PI_CHECK(
      SameHitsWithAndWithoutSkipping(model, 75, 61, file + ", first hits", nullptr, false) > 100);
    const double centre[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
    for (const bool allHits : { true, false })
    {
      PI_CHECK(SameHitsWithAndWithoutSkipping(
                 model, 67, 53, file + ", camera",
                 [&](vtkPiRayCaster* c)
                 {
                   c->SetViewMode(vtkPiRayCaster::CAMERA);
                   c->SetCameraPosition(
                     centre[0] + 0.9 * size, centre[1] - 1.1 * size, centre[2] + 0.7 * size);
                   c->SetCameraFocalPoint(centre[0], centre[1], centre[2]);
                   c->SetCameraViewUp(0, 0, 1);
                   c->SetViewAngle(35.0);
                 },
                 allHits) > (allHits ? 100 : 30));
    }
  }
  PI_CHECK(models >= 20);

  // CAMERA mode casts the rays a VTK renderer of the image's size casts through its
  // pixel centres: each hit lies on the line vtkRenderer::DisplayToWorld gives for
  // display point (i + ½, j + ½) at depths 0 and 1, for a perspective and a parallel
  // camera looking at the cup from an oblique direction, in a non-square image.
  {
    vtkNew<vtkPiSurface> cup;
    PI_CHECK(cup->LoadModel(pitest::ModelPath("cup_a1.0.pisurf").c_str()));
    for (const bool parallel : { false, true })
    {
      // One camera, given to the caster and to VTK's renderer.
      const int w = 97, h = 61;
      const double position[3] = { 4.0, -6.5, 3.0 }, focal[3] = { 0.4, 0.2, -1.2 },
                   up[3] = { 0.1, 0.2, 1.0 };
      const double angle = 27.0, scale = 2.1;
      vtkNew<vtkPiRayCaster> camera;
      camera->SetPiSurface(cup);
      camera->SetViewMode(vtkPiRayCaster::CAMERA);
      camera->SetResolution(w, h);
      camera->SetCameraPosition(position);
      camera->SetCameraFocalPoint(focal);
      camera->SetCameraViewUp(up);
      camera->SetViewAngle(angle);
      camera->SetParallelProjection(parallel);
      camera->SetParallelScale(scale);
      camera->Update();
      vtkPolyData* out = camera->GetOutput();
      vtkNew<vtkRenderWindow> window;
      window->SetSize(w, h);
      window->OffScreenRenderingOn();
      vtkNew<vtkRenderer> renderer;
      window->AddRenderer(renderer);
      vtkCamera* c = renderer->GetActiveCamera();
      c->SetPosition(position);
      c->SetFocalPoint(focal);
      c->SetViewUp(up);
      c->SetViewAngle(angle);
      c->SetParallelProjection(parallel);
      c->SetParallelScale(scale);
      c->SetClippingRange(0.5, 50.0);
      vtkDataArray* pixel = Array(out, "PixelIndex");
      double worst = 0.0;
      for (vtkIdType k = 0; pixel && k < out->GetNumberOfPoints(); ++k)
      {
        double ends[2][3];
        for (int z = 0; z < 2; ++z)
        {
          renderer->SetDisplayPoint(
            pixel->GetComponent(k, 0) + 0.5, pixel->GetComponent(k, 1) + 0.5, z);
          renderer->DisplayToWorld();
          double world[4];
          renderer->GetWorldPoint(world);
          for (int a = 0; a < 3; ++a)
          {
            ends[z][a] = world[a] / world[3];
          }
        }
        double p[3], u[3], v[3];
        out->GetPoint(k, p);
        for (int a = 0; a < 3; ++a)
        {
          u[a] = ends[1][a] - ends[0][a];
          v[a] = p[a] - ends[0][a];
        }
        // |v × u| / |u|: the distance from the hit to the renderer's pixel ray.
        const double cx = v[1] * u[2] - v[2] * u[1], cy = v[2] * u[0] - v[0] * u[2],
                     cz = v[0] * u[1] - v[1] * u[0];
        worst = std::max(worst,
          std::sqrt(cx * cx + cy * cy + cz * cz) /
            std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]));
      }
      std::cout << (parallel ? "parallel" : "perspective")
                << " camera: " << out->GetNumberOfPoints()
                << " hits, largest distance to VTK's pixel ray " << worst << "\n";
      PI_CHECK(out->GetNumberOfPoints() > 1000);
      PI_CHECK(worst < 1e-6);
    }
  }

  // Bad settings.
  caster->SetPiSurface(sphere);
  caster->SetViewMode(vtkPiRayCaster::MINUS_Z);
  caster->SetResolution(0, 10);
  caster->Update();
  PI_CHECK(watch.Error("Resolution must be at least 1 x 1"));
  caster->SetResolution(10, 10);
  caster->SetViewMode(vtkPiRayCaster::CAMERA);
  caster->SetCameraPosition(0, 0, 0);
  caster->Update();
  PI_CHECK(watch.Error("CameraPosition equals CameraFocalPoint"));
  caster->SetCameraPosition(0, 0, 10);
  caster->SetCameraViewUp(0, 0, 1);
  caster->Update();
  PI_CHECK(watch.Error("parallel to the view direction"));
  vtkNew<vtkPiSurface> plane;
  vtkNew<vtkPiPrimitive> planePrimitive;
  planePrimitive->SetTypeToPlane();
  plane->AddFactor(planePrimitive);
  caster->SetPiSurface(plane);
  caster->SetBounds(0, 0, 0, 0, 0, 0);
  caster->SetCameraViewUp(0, 1, 0);
  caster->Update();
  PI_CHECK(watch.Error("No bounds"));
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
