// SPDX-License-Identifier: BSD-3-Clause
// Molecular Pi-surfaces: the paper's molecules, CML files, proteins, NMR models, bad files.
#include "PiTestUtilities.h"

#include "vtkCMLMoleculeReader.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFlyingEdges3D.h"
#include "vtkImageData.h"
#include "vtkMassProperties.h"
#include "vtkMath.h"
#include "vtkMolecule.h"
#include "vtkNew.h"
#include "vtkPDBReader.h"
#include "vtkPiImageTriangulator.h"
#include "vtkPiMoleculeReader.h"
#include "vtkPiMoleculeSurface.h"
#include "vtkPiRayCaster.h"
#include "vtkPiSampleFunction.h"
#include "vtkPiSurface.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataConnectivityFilter.h"
#include "vtkStaticPointLocator.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <tuple>

namespace
{
const std::string Freesasa = "/usr/share/freesasa/test-data/";
const std::string Chemical = "/usr/share/chemical-structures/";

int Components(vtkPolyData* mesh)
{
  vtkNew<vtkPolyDataConnectivityFilter> c;
  c->SetInputData(mesh);
  c->SetExtractionModeToAllRegions();
  c->Update();
  return c->GetNumberOfExtractedRegions();
}

// The paper's molecule: the model is the paper's product of spheres with r = 1, the
// mesh one component.
int PaperMolecule(const double atoms[][4], int n)
{
  int failures = 0;
  vtkNew<vtkMolecule> molecule;
  for (int i = 0; i < n; ++i)
  {
    molecule->AppendAtom(
      static_cast<unsigned short>(atoms[i][0]), atoms[i][1], atoms[i][2], atoms[i][3]);
  }
  vtkNew<vtkPiMoleculeSurface> surface;
  surface->SetInputData(molecule);
  surface->Update();
  vtkPolyData* out = surface->GetOutput();
  PI_CHECK(out->GetNumberOfCells() > 100);
  PI_CHECK(Components(out) == 1);
  PI_CHECK(out->GetPointData()->GetArray("Normals") && out->GetPointData()->GetArray("Factor") &&
    out->GetPointData()->GetArray("AtomicNumber"));
  auto json = vtkStringArray::SafeDownCast(out->GetFieldData()->GetAbstractArray("PiSurfaceModel"));
  PI_CHECK(json != nullptr);
  if (!json)
  {
    return failures;
  }
  vtkNew<vtkPiSurface> model;
  PI_CHECK(model->SetModelJSON(json->GetValue(0)));
  PI_CHECK(model->GetNumberOfFactors() == n);
  PI_CHECK_NEAR(model->GetBlending(), 1.0, 0.0);
  // F equals the paper's polynomial Π((x−x_i)² + (y−y_i)² + z² − R_i²) − 1 (Bondi radii).
  for (double p[3] = { 1.0, -2.0, 0.5 }; p[0] < 30; p[0] += 7.3, p[1] -= 6.1)
  {
    double expected = 1.0;
    for (int i = 0; i < n; ++i)
    {
      const double R = atoms[i][0] == 8 ? 1.52 : 1.70;
      expected *= (p[0] - atoms[i][1]) * (p[0] - atoms[i][1]) +
        (p[1] - atoms[i][2]) * (p[1] - atoms[i][2]) + (p[2] - atoms[i][3]) * (p[2] - atoms[i][3]) -
        R * R;
    }
    expected -= 1.0;
    // vtkMolecule stores float coordinates: relative 1e-5.
    PI_CHECK_NEAR(model->EvaluateFunction(p), expected, 1e-5 * (std::fabs(expected) + 1));
  }
  return failures;
}

int Mesh(
  vtkAlgorithm* source, int mode, double spacing, vtkIdType minimumTriangles, int components = -1)
{
  int failures = 0;
  vtkNew<vtkPiMoleculeSurface> surface;
  surface->SetInputConnection(source->GetOutputPort());
  surface->SetMode(mode);
  surface->SetSpacing(spacing);
  surface->Update();
  vtkPolyData* out = surface->GetOutput();
  PI_CHECK(out->GetNumberOfCells() >= minimumTriangles);
  if (components > 0)
  {
    PI_CHECK(Components(out) == components);
  }
  // The field data's area and volume are those of the mesh (vtkMassProperties agrees
  // on a closed mesh; the outer envelope is one).
  vtkDataArray* area = out->GetFieldData()->GetArray("SurfaceArea");
  vtkDataArray* volume = out->GetFieldData()->GetArray("EnclosedVolume");
  PI_CHECK(area && volume);
  if (area && volume)
  {
    vtkNew<vtkMassProperties> mass;
    mass->SetInputData(out);
    mass->Update();
    PI_CHECK_NEAR(area->GetTuple1(0), mass->GetSurfaceArea(), 1e-9 * mass->GetSurfaceArea());
    PI_CHECK_NEAR(volume->GetTuple1(0), mass->GetVolume(), 1e-6 * mass->GetVolume());
    PI_CHECK(volume->GetTuple1(0) > 0);
  }
  if (failures)
  {
    std::cerr << "  while meshing (mode " << mode << ", spacing " << spacing << ")\n";
  }
  return failures;
}

int BadFile(const std::string& path, const std::string& text)
{
  int failures = 0;
  vtkNew<vtkPiMoleculeReader> reader;
  pitest::Watch watch(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  PI_CHECK(watch.Error(text));
  PI_CHECK(reader->GetOutput()->GetNumberOfAtoms() == 0);
  return failures;
}
// Pi Ray Cast downstream of the molecular surface. (1) Acetic acid, Global, r = 1 (a
// blended surface): the molecule path (the field rebuilt from PiMoleculeCenters, Radii
// and Settings) gives the hits the polynomial path gives from PiSurfaceModel (the same
// output without PiMoleculeSettings): six views, all hits; each of its hits matched
// within about two tolerances, with its Tangent flag, and none extra. (2) 1a0q (3301 atoms) in
// Local mode, which has no polynomial model: every first hit of the -Z view lies on the mesh of the
// same field (within one grid spacing of its exact vertices), and the Image Based Triangulation of
// its first-hit six views is closed, with the area of all the mesher's sheets (within -20 % for the
// sheets thinner than a pixel, +5 %). (3) A malformed PiMoleculeSettings is an error.
int RayCastDownstream()
{
  int failures = 0;
  // All hits of six views of n² pixels, per pixel (view, i, j): depth and Tangent flag,
  // nearest first.
  using Pixel = std::tuple<int, int, int>;
  using Hits = std::map<Pixel, std::vector<std::pair<double, int>>>;
  auto hits = [](vtkPolyData* input, int n)
  {
    vtkNew<vtkPiRayCaster> caster;
    caster->SetInputData(input);
    caster->SetViewMode(vtkPiRayCaster::SIX_AXIS_VIEWS);
    caster->SetResolution(n, n);
    caster->AllHitsOn();
    caster->Update();
    Hits out;
    vtkPolyData* o = caster->GetOutput();
    vtkPointData* pd = o->GetPointData();
    vtkDataArray* px = pd->GetArray("PixelIndex");
    for (vtkIdType k = 0; px && k < o->GetNumberOfPoints(); ++k)
    {
      const Pixel key{ static_cast<int>(pd->GetArray("ViewIndex")->GetComponent(k, 0)),
        static_cast<int>(px->GetComponent(k, 0)), static_cast<int>(px->GetComponent(k, 1)) };
      out[key].push_back({ pd->GetArray("Depth")->GetComponent(k, 0),
        static_cast<int>(pd->GetArray("Tangent")->GetComponent(k, 0)) });
    }
    return out;
  };
  {
    vtkNew<vtkCMLMoleculeReader> cml;
    cml->SetFileName((Chemical + "carboxylic_acids/acetic_acid.cml").c_str());
    vtkNew<vtkPiMoleculeSurface> surface;
    surface->SetInputConnection(cml->GetOutputPort());
    surface->SetSpacing(0.25);
    surface->Update();
    vtkPolyData* molecule = surface->GetOutput();
    PI_CHECK(molecule->GetFieldData()->GetArray("PiMoleculeSettings") != nullptr);
    vtkNew<vtkPolyData> polynomial;
    polynomial->ShallowCopy(molecule);
    vtkNew<vtkFieldData> fd;
    fd->DeepCopy(molecule->GetFieldData());
    fd->RemoveArray("PiMoleculeSettings");
    polynomial->SetFieldData(fd);
    const Hits pa = hits(molecule, 48), pb = hits(polynomial, 48);
    size_t total = 0;
    for (const auto& pixel : pb)
    {
      total += pixel.second.size();
    }
    PI_CHECK(total > 3000);
    // (the tolerance is 1e-10 of the rays' box, about 15 A here)
    int missed = 0, extra = 0;
    for (const auto& pixel : pb)
    {
      const auto found = pa.find(pixel.first);
      const std::vector<std::pair<double, int>> none;
      const auto& mine = found != pa.end() ? found->second : none;
      for (const auto& hit : pixel.second)
      {
        missed += std::none_of(mine.begin(), mine.end(),
          [&](const std::pair<double, int>& x)
          { return std::fabs(x.first - hit.first) <= 4e-9 && x.second == hit.second; });
      }
      for (const auto& hit : mine)
      {
        if (std::none_of(pixel.second.begin(), pixel.second.end(),
              [&](const std::pair<double, int>& x)
              { return std::fabs(x.first - hit.first) <= 4e-9; }))
        {
          ++extra;
        }
      }
    }
    PI_CHECK(pa.size() == pb.size());
    PI_CHECK(missed == 0);
    PI_CHECK(extra == 0);
    if (missed || extra)
    {
      std::cerr << "  of " << total << " hits: " << missed << " missed, " << extra << " extra\n";
    }
  }
  {
    vtkNew<vtkPiMoleculeReader> reader;
    reader->SetFileName((Freesasa + "1a0q.pdb").c_str());
    vtkNew<vtkPiMoleculeSurface> surface;
    surface->SetInputConnection(reader->GetOutputPort());
    surface->SetMode(vtkPiMoleculeSurface::LOCAL);
    surface->SetSpacing(0.5);
    surface->Update();
    vtkPolyData* mesh = surface->GetOutput();
    PI_CHECK(mesh->GetFieldData()->GetAbstractArray("PiSurfaceModel") == nullptr);
    vtkNew<vtkPiRayCaster> caster;
    caster->SetInputData(mesh);
    caster->SetViewMode(vtkPiRayCaster::MINUS_Z);
    caster->SetResolution(64, 64);
    caster->Update();
    vtkPolyData* cloud = caster->GetOutput();
    PI_CHECK(cloud->GetNumberOfPoints() > 1000);
    vtkNew<vtkStaticPointLocator> locator;
    locator->SetDataSet(mesh);
    locator->BuildLocator();
    double worst = 0.0;
    for (vtkIdType k = 0; k < cloud->GetNumberOfPoints(); ++k)
    {
      double p[3], q[3];
      cloud->GetPoint(k, p);
      mesh->GetPoint(locator->FindClosestPoint(p), q);
      worst = std::max(worst, std::sqrt(vtkMath::Distance2BetweenPoints(p, q)));
    }
    PI_CHECK(worst < 0.5);
    if (!(worst < 0.5))
    {
      std::cerr << "  a hit lies " << worst << " A from the mesh\n";
    }
    // Image Based Triangulation of first-hit six views: the parts they hide come from
    // the same field (Local mode has no PiSurfaceModel: refused before): closed, with
    // the area of the mesher's sheets.
    vtkNew<vtkPiRayCaster> six;
    six->SetInputData(mesh);
    six->SetViewMode(vtkPiRayCaster::SIX_AXIS_VIEWS);
    six->SetResolution(96, 96);
    vtkNew<vtkPiImageTriangulator> triangulator;
    triangulator->SetInputConnection(six->GetOutputPort());
    triangulator->Update();
    vtkPolyData* triangles = triangulator->GetOutput();
    vtkDataArray* boundary = triangles->GetFieldData()->GetArray("BoundaryEdges");
    PI_CHECK(triangles->GetNumberOfCells() > 20000);
    PI_CHECK(boundary && boundary->GetComponent(0, 0) == 0);
    vtkNew<vtkMassProperties> area;
    area->SetInputData(triangles);
    area->Update();
    vtkNew<vtkPiMoleculeSurface> sheets;
    sheets->SetInputConnection(reader->GetOutputPort());
    sheets->SetMode(vtkPiMoleculeSurface::LOCAL);
    sheets->SetSpacing(0.5);
    sheets->OuterEnvelopeOff();
    sheets->Update();
    const double meshArea =
      sheets->GetOutput()->GetFieldData()->GetArray("SurfaceArea")->GetComponent(0, 0);
    // Every sheet of F = 0 (the lens-shaped shells where atoms overlap too), as the
    // mesher's with OuterEnvelope off; sheets thinner than a pixel are left out.
    PI_CHECK(area->GetSurfaceArea() > 0.8 * meshArea && area->GetSurfaceArea() < 1.05 * meshArea);
    if (!(area->GetSurfaceArea() > 0.8 * meshArea && area->GetSurfaceArea() < 1.05 * meshArea))
    {
      std::cerr << "  triangulated area " << area->GetSurfaceArea() << ", mesh " << meshArea
                << "\n";
    }
    PI_CHECK(triangles->GetFieldData()->GetArray("PiMoleculeSettings") != nullptr);
    // Pi Sample Function samples the same field on the mesher's grid (Local mode has no
    // PiSurfaceModel: refused before): contoured at 0 by VTK's flying edges, its signs
    // give exactly the mesher's triangles (all sheets: OuterEnvelope off).
    vtkDataArray* box = sheets->GetOutput()->GetFieldData()->GetArray("PiMoleculeSettings");
    int dims[3];
    for (int a = 0; a < 3; ++a)
    {
      dims[a] = static_cast<int>(
                  std::lround((box->GetComponent(4 + 2 * a, 0) - box->GetComponent(3 + 2 * a, 0)) /
                    sheets->GetLastSpacing())) +
        1;
    }
    vtkNew<vtkPiSampleFunction> sample;
    sample->SetInputConnection(sheets->GetOutputPort());
    sample->SetSampleDimensions(dims);
    vtkNew<vtkFlyingEdges3D> contour;
    contour->SetInputConnection(sample->GetOutputPort());
    contour->SetValue(0, 0.0);
    contour->Update();
    PI_CHECK(contour->GetOutput()->GetNumberOfCells() == sheets->GetOutput()->GetNumberOfCells());
    if (contour->GetOutput()->GetNumberOfCells() != sheets->GetOutput()->GetNumberOfCells())
    {
      std::cerr << "  sampled field: " << contour->GetOutput()->GetNumberOfCells()
                << " triangles, the mesher " << sheets->GetOutput()->GetNumberOfCells() << "\n";
    }
    // ProjectVertices off: the vertices are where flying edges puts them on the same
    // samples (the linear interpolation along each edge), up to the float rounding of
    // its points; on, the exact roots lie visibly off it somewhere.
    vtkNew<vtkPiMoleculeSurface> plain;
    plain->SetInputConnection(reader->GetOutputPort());
    plain->SetMode(vtkPiMoleculeSurface::LOCAL);
    plain->SetSpacing(0.5);
    plain->OuterEnvelopeOff();
    plain->ProjectVerticesOff();
    plain->Update();
    vtkNew<vtkStaticPointLocator> onContour;
    onContour->SetDataSet(contour->GetOutput());
    onContour->BuildLocator();
    auto farthest = [&](vtkPolyData* m)
    {
      double worst = 0.0;
      for (vtkIdType i = 0; i < m->GetNumberOfPoints(); ++i)
      {
        double p[3], q[3];
        m->GetPoint(i, p);
        contour->GetOutput()->GetPoint(onContour->FindClosestPoint(p), q);
        worst = std::max(worst, std::sqrt(vtkMath::Distance2BetweenPoints(p, q)));
      }
      return worst;
    };
    const double plainOff = farthest(plain->GetOutput());
    const double exactOff = farthest(sheets->GetOutput());
    PI_CHECK(plain->GetOutput()->GetNumberOfCells() == contour->GetOutput()->GetNumberOfCells());
    PI_CHECK(plain->GetOutput()->GetNumberOfPoints() == contour->GetOutput()->GetNumberOfPoints());
    PI_CHECK(plainOff < 1e-4 && exactOff > 1e-3);
    if (!(plainOff < 1e-4 && exactOff > 1e-3))
    {
      std::cerr << "  farthest vertex from flying edges': " << plainOff
                << " A (ProjectVertices off), " << exactOff << " A (on)\n";
    }
    vtkDataArray* plainNormals = plain->GetOutput()->GetPointData()->GetArray("Normals");
    PI_CHECK(plainNormals && std::fabs(vtkMath::Norm(plainNormals->GetTuple3(0)) - 1.0) < 1e-6);
    vtkNew<vtkPolyData> bad;
    bad->ShallowCopy(mesh);
    vtkNew<vtkFieldData> fd;
    fd->DeepCopy(mesh->GetFieldData());
    vtkNew<vtkDoubleArray> settings;
    settings->SetName("PiMoleculeSettings");
    settings->SetNumberOfTuples(3);
    fd->AddArray(settings);
    bad->SetFieldData(fd);
    vtkNew<vtkPiRayCaster> badCaster;
    badCaster->SetInputData(bad);
    pitest::Watch watch(badCaster);
    badCaster->Update();
    PI_CHECK(watch.Error("Malformed molecule field data"));
  }
  return failures;
}
}

int TestPiMolecule(int, char*[])
{
  int failures = 0;

  // The paper's formic and acetic acid (its coordinates, Bondi radii).
  const double formic[][4] = { { 8, 2.310, -1.334, 0.0 }, { 6, 3.644, -2.104, 0.0 },
    { 8, 4.977, -1.334, 0.0 } };
  const double acetic[][4] = { { 6, 24.214, -24.150, 0.0 }, { 6, 25.548, -23.380, 0.0 },
    { 8, 26.881, -24.150, 0.0 }, { 8, 25.548, -21.840, 0.0 } };
  failures += PaperMolecule(formic, 3);
  failures += PaperMolecule(acetic, 4);
  failures += RayCastDownstream();

  // CML files through VTK's reader.
  for (const char* name :
    { "carboxylic_acids/formic_acid", "carboxylic_acids/acetic_acid", "nucleobases/adenine",
      "nucleobases/cytosine", "nucleobases/guanine", "nucleobases/thymine", "nucleobases/uracil" })
  {
    vtkNew<vtkCMLMoleculeReader> cml;
    cml->SetFileName((Chemical + name + ".cml").c_str());
    const int before = failures;
    failures += Mesh(cml, vtkPiMoleculeSurface::GLOBAL, 0.25, 500, 1);
    failures += Mesh(cml, vtkPiMoleculeSurface::LOCAL, 0.25, 500, 1);
    if (failures != before)
    {
      std::cerr << "  in " << name << "\n";
    }
  }

  // Proteins: 1ubq Global (our reader: no waters by default, so one component), 1a0q
  // Local, and 1ubq from ParaView's stock PDB reader (polydata with atom_type).
  {
    vtkNew<vtkPiMoleculeReader> reader;
    reader->SetFileName((Freesasa + "1ubq.pdb").c_str());
    reader->Update();
    PI_CHECK(reader->GetOutput()->GetNumberOfAtoms() == 602);
    failures += Mesh(reader, vtkPiMoleculeSurface::GLOBAL, 0.5, 50000);
    reader->IncludeWatersOn();
    reader->Update();
    PI_CHECK(reader->GetOutput()->GetNumberOfAtoms() == 660);
    vtkNew<vtkPiMoleculeReader> large;
    large->SetFileName((Freesasa + "1a0q.pdb").c_str());
    failures += Mesh(large, vtkPiMoleculeSurface::LOCAL, 0.5, 100000);
    vtkNew<vtkPDBReader> stock;
    stock->SetFileName((Freesasa + "1ubq.pdb").c_str());
    failures += Mesh(stock, vtkPiMoleculeSurface::GLOBAL, 0.5, 50000);
  }

  // NMR: 10 models with hydrogens; models differ; a missing model is an error.
  {
    vtkNew<vtkPiMoleculeReader> nmr;
    nmr->SetFileName((Freesasa + "1d3z.pdb").c_str());
    nmr->Update();
    PI_CHECK(nmr->GetNumberOfModels() == 10);
    const vtkIdType all = nmr->GetOutput()->GetNumberOfAtoms();
    double first[3], second[3];
    nmr->GetOutput()->GetAtomPosition(0, first);
    nmr->SetModel(2);
    nmr->Update();
    nmr->GetOutput()->GetAtomPosition(0, second);
    PI_CHECK(nmr->GetOutput()->GetNumberOfAtoms() == all);
    PI_CHECK(first[0] != second[0] || first[1] != second[1] || first[2] != second[2]);
    nmr->IncludeHydrogensOff();
    nmr->Update();
    PI_CHECK(nmr->GetOutput()->GetNumberOfAtoms() < all / 2 + 50);
    pitest::Watch watch(nmr);
    nmr->SetModel(11);
    nmr->Update();
    PI_CHECK(watch.Error("Model 11 requested"));
  }

  // Bad files: missing, empty, garbage, truncated mid-record, mmCIF without atoms.
  const std::string temp = PISURF_TEMP_DIR;
  {
    std::ofstream(temp + "/empty.pdb");
    std::ofstream(temp + "/garbage.pdb") << "this is not\x01\x02 a molecule\n";
    std::ifstream in(Freesasa + "1ubq.pdb");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t cut = text.find("ATOM      2 ");
    std::ofstream(temp + "/truncated.pdb") << text.substr(0, cut + 30);
    std::ofstream(temp + "/noatoms.cif")
      << "data_x\nloop_\n_atom_site.id\n_atom_site.Cartn_x\n1 2\n";
  }
  failures += BadFile(temp + "/missing.pdb", "Cannot open");
  failures += BadFile(temp + "/empty.pdb", "no ATOM/HETATM records");
  failures += BadFile(temp + "/garbage.pdb", "garbage.pdb");
  failures += BadFile(temp + "/truncated.pdb", "truncated.pdb");
  failures += BadFile(temp + "/noatoms.cif", "noatoms.cif");

  // An empty molecule is an error of the filter, not an empty success.
  {
    vtkNew<vtkMolecule> empty;
    vtkNew<vtkPiMoleculeSurface> surface;
    pitest::Watch watch(surface);
    surface->SetInputData(empty);
    surface->Update();
    PI_CHECK(watch.Error("no atoms"));
  }
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
