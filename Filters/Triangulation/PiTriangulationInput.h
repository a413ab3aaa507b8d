// SPDX-License-Identifier: BSD-3-Clause
// Unpacks the input of vtkPiImageTriangulator (a vtkPiRayCaster output): its views, its
// cloud of hits, the model it carries, and the size of the scene.
#ifndef PiTriangulationInput_h
#define PiTriangulationInput_h

#include "PiTiming.h"
#include "PiTriangulation.h"

#include "vtkNew.h"

class vtkDataArray;
class vtkPolyData;
class vtkStringArray;

namespace pisurf
{
namespace triangulator
{

// Fills T.Views, T.C, the model (T.Model, T.Kernel and T.Caster) and T.Size; keeps
// what the output passes on (the model's field data) and the box of the scene.
class TriangulationInput
{
public:
  // false (an error reported on T.Algorithm) if the input is not a ray cast's.
  bool Read(vtkPolyData* input, Triangulation& T, pisurf::PassTimer& lap);

  vtkStringArray* Json = nullptr; // PiSurfaceModel, if the input carries it
  pisurf::MoleculeInput Molecule;
  // The extent of the views' rays and of the hits (empty if there is neither).
  double Box[6];

private:
  bool ReadViews(vtkDataArray* viewData, Triangulation& T);
  bool ReadCloud(vtkPolyData* input, Triangulation& t);
  bool CheckCloud(Triangulation& T);
  bool ReadModel(vtkPolyData* input, Triangulation& T);
  void MeasureSize(Triangulation& T);

  vtkDataArray* Pixel = nullptr;
  vtkDataArray* ViewIndex = nullptr;
  vtkDataArray* Depth = nullptr;
  vtkDataArray* Normals = nullptr;
  vtkNew<vtkPiSurface> Surface;
};

} // namespace triangulator
} // namespace pisurf

#endif
