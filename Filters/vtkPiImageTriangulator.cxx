// SPDX-License-Identifier: BSD-3-Clause
// The passes live in Triangulation/: TriangulationInput unpacks the ray cast, the
// lattice passes (HitLattice, LatticeCells) or BestView make the triangles, and
// MeshAssembly builds the output mesh.
#include "vtkPiImageTriangulator.h"
#include "PiPieces.h"
#include "PiTiming.h"
#include "Triangulation/PiBestView.h"
#include "Triangulation/PiLattice.h"
#include "Triangulation/PiMeshAssembly.h"
#include "Triangulation/PiTriangulationInput.h"

#include "vtkCellArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include <vector>

vtkStandardNewMacro(vtkPiImageTriangulator);

vtkPiImageTriangulator::vtkPiImageTriangulator() = default;
vtkPiImageTriangulator::~vtkPiImageTriangulator() = default;

int vtkPiImageTriangulator::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkPiImageTriangulator::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  outputVector->GetInformationObject(0)->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkPiImageTriangulator::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // The views are merged and their seams closed across the whole lattice: every piece
  // triangulates the whole cloud (piece 0 of 1 of the input) and keeps its share.
  pisurf::RequestWholeInput(inputVector[0]);
  return 1;
}

int vtkPiImageTriangulator::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  using namespace pisurf::triangulator;
  // PISURF_TIMING=1: the wall time of each pass on stderr.
  pisurf::PassTimer lap("vtkPiImageTriangulator");
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  Triangulation T;
  T.Algorithm = this;
  TriangulationInput in;
  if (!in.Read(input, T, lap))
  {
    return 0;
  }
  const double* box = in.Box;

  Lattice L;
  const bool lattice = FindLattice(T, L);
  int mode = this->MergeMode;
  if (mode == AUTOMATIC)
  {
    mode = lattice ? RAY_LATTICE : BEST_VIEW;
  }
  if (mode == RAY_LATTICE)
  {
    if (!lattice)
    {
      vtkErrorMacro(<< "RAY_LATTICE needs axis views over one box covering the three axes "
                       "with matching resolutions (Six Axis Views or Three Axis Directions)");
      return 0;
    }
    const double cells = double(L.N[0] + 1) * (L.N[1] + 1) * (L.N[2] + 1);
    if (cells > 1.1e10)
    {
      vtkErrorMacro(<< "The ray lattice of " << cells << " cells is too large");
      return 0;
    }
    T.ChooseDiagonals = this->EdgeFlipRounds > 0;
    T.Probe = 1e-3 * T.Size;
    if (T.Caster && box[0] <= box[1] && box[2] <= box[3] && box[4] <= box[5])
    {
      // Points computed off the rays' box take the probes (see RayCaster::PrepareProbes).
      T.Caster->PrepareProbes(box, T.Probe);
    }
    T.SingularTolerance = this->SingularTolerance;
    RunLattice(T, L);
  }
  else
  {
    BestView(T, this->SheetTolerance).Run();
  }
  if (T.Abort)
  {
    output->Initialize();
    return 1;
  }

  lap("triangles of the views");
  MeshAssembly mesh(T, lap);
  mesh.Run(this->EdgeFlipRounds);
  output->SetPoints(mesh.Points);
  output->SetPolys(mesh.Polys);
  output->GetPointData()->SetNormals(mesh.Normals);
  output->GetPointData()->AddArray(mesh.Singular);
  output->GetPointData()->AddArray(mesh.View);
  output->GetPointData()->AddArray(mesh.Factor);
  if (in.Molecule.Present)
  {
    pisurf::MoleculeInput::Forward(input, output);
  }
  else if (in.Json)
  {
    output->GetFieldData()->AddArray(in.Json);
  }
  vtkNew<vtkIdTypeArray> boundaryEdges;
  boundaryEdges->SetName("BoundaryEdges");
  boundaryEdges->InsertNextValue(mesh.BoundaryEdges);
  output->GetFieldData()->AddArray(boundaryEdges);
  vtkNew<vtkIdTypeArray> unused;
  unused->SetName("UnusedHits");
  unused->InsertNextValue(T.C.N - mesh.UsedHits);
  output->GetFieldData()->AddArray(unused);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const pisurf::Piece request = pisurf::PieceOf(outInfo);
  const int piece = request.Piece, pieces = request.Pieces;
  if (pieces > 1)
  {
    KeepShare(output, piece, pieces);
  }
  lap.Total("total");
  this->UpdateProgress(1.0);
  return 1;
}

void vtkPiImageTriangulator::KeepShare(vtkPolyData* mesh, int piece, int pieces)
{
  // Piece p of n keeps the triangles [T p / n, T (p + 1) / n) of the whole mesh and the
  // points they use (a point on the cut is in both pieces, at the same position).
  const vtkIdType triangles = mesh->GetNumberOfPolys();
  const vtkIdType first = triangles * piece / pieces, last = triangles * (piece + 1) / pieces;
  std::vector<vtkIdType> map(mesh->GetNumberOfPoints(), -1);
  vtkNew<vtkIdList> keep;
  vtkNew<vtkCellArray> polys;
  vtkCellArray* all = mesh->GetPolys();
  vtkNew<vtkIdList> cell;
  for (vtkIdType t = first; t < last; ++t)
  {
    all->GetCellAtId(t, cell);
    for (vtkIdType k = 0; k < cell->GetNumberOfIds(); ++k)
    {
      vtkIdType& id = map[cell->GetId(k)];
      if (id < 0)
      {
        id = keep->GetNumberOfIds();
        keep->InsertNextId(cell->GetId(k));
      }
      cell->SetId(k, id);
    }
    polys->InsertNextCell(cell);
  }
  vtkNew<vtkPoints> points;
  points->SetDataType(mesh->GetPoints()->GetDataType());
  points->SetNumberOfPoints(keep->GetNumberOfIds());
  mesh->GetPoints()->GetPoints(keep, points);
  vtkNew<vtkPointData> pd;
  pd->CopyAllocate(mesh->GetPointData(), keep->GetNumberOfIds());
  pd->CopyData(mesh->GetPointData(), keep);
  vtkNew<vtkPolyData> share;
  share->SetPoints(points);
  share->SetPolys(polys);
  share->GetPointData()->ShallowCopy(pd);
  share->GetFieldData()->ShallowCopy(mesh->GetFieldData());
  mesh->ShallowCopy(share);
}

void vtkPiImageTriangulator::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MergeMode: " << this->MergeMode << "\n";
  os << indent << "SheetTolerance: " << this->SheetTolerance << "\n";
  os << indent << "SingularTolerance: " << this->SingularTolerance << "\n";
  os << indent << "EdgeFlipRounds: " << this->EdgeFlipRounds << "\n";
}
