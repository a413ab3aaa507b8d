// SPDX-License-Identifier: BSD-3-Clause
// What the mesher's passes evaluate: a product kernel or a field with its own
// evaluation structures, behind one non-virtual front.
#ifndef PiMeshEvaluator_h
#define PiMeshEvaluator_h

#include "PiField.h"
#include "PiProductKernel.h"

namespace pisurf
{
// What the passes evaluate: the Pi-surface's product kernel or, when set, a field with
// its own evaluation structures (SetField). Only the product has row restriction.
struct MeshEvaluator
{
  const pisurf::ProductKernel* Kernel = nullptr;
  const pisurf::Field* Field = nullptr;

  int ClassifyBox(const double box[6]) const
  {
    return this->Field ? this->Field->ClassifyBox(box) : this->Kernel->ClassifyBox(box);
  }
  // A block: ClassifyBox, and where that cannot decide, its octants (enclosures
  // tighten on smaller boxes: if all eight exclude the surface, so does the block, F
  // having no zero in it and so one sign throughout).
  int ClassifyBlock(const double box[6]) const
  {
    int octants[8];
    int sign = 0;
    if (this->Field)
    {
      sign = this->Field->ClassifyBox(box);
      for (int o = 0; o < 8 && sign == 0; ++o)
      {
        double sub[6];
        pisurf::OctantBox(box, o, sub);
        octants[o] = this->Field->ClassifyBox(sub);
        if (octants[o] == 0)
        {
          return 0;
        }
      }
      return sign != 0 ? sign : octants[7];
    }
    sign = this->Kernel->ClassifyBoxAndOctants(box, octants);
    if (sign != 0)
    {
      return sign;
    }
    for (int o = 0; o < 8; ++o)
    {
      if (octants[o] == 0)
      {
        return 0;
      }
    }
    return octants[0];
  }
  double Evaluate(const double p[3]) const
  {
    return this->Field ? this->Field->Evaluate(p) : this->Kernel->Evaluate(p);
  }
  double EvaluateCompressed(const double p[3]) const
  {
    return this->Field ? this->Field->EvaluateCompressed(p) : this->Kernel->EvaluateCompressed(p);
  }
  bool OffOuterSide(const double p[3]) const
  {
    return this->Field && this->Field->OffOuterSide(p);
  }
  void EvaluateVertex(const double p[3], double n[3], double& gradientNorm, int& nearest) const
  {
    if (this->Field)
    {
      this->Field->EvaluateVertex(p, n, gradientNorm, nearest);
    }
    else
    {
      this->Kernel->EvaluateVertex(p, n, gradientNorm, nearest);
    }
  }
};
}

#endif
