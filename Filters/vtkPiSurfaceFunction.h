// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiSurfaceFunction
 * @brief a vtkPiSurface defined by a .pisurf file or JSON text (ParaView's "Pi Surface Function")
 *
 * The implicit function behind ParaView's "Pi Surface Function" clip, slice and
 * extract type. It is a vtkPiSurface whose model comes from FileName when that is set,
 * and otherwise from the JSON text in Model. The model is (re)loaded as soon as either
 * property changes; an invalid model is reported with vtkErrorMacro and leaves the
 * previous valid model in place.
 *
 * @sa vtkPiSurface
 */
#ifndef vtkPiSurfaceFunction_h
#define vtkPiSurfaceFunction_h

#include "vtkPiSurface.h"
#include "vtkPiSurfacesFiltersModule.h" // for export macro

#include <string> // for std::string

class VTKPISURFACESFILTERS_EXPORT vtkPiSurfaceFunction : public vtkPiSurface
{
public:
  static vtkPiSurfaceFunction* New();
  vtkTypeMacro(vtkPiSurfaceFunction, vtkPiSurface);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The model as .pisurf JSON text (default empty). Used when FileName is empty.
  void SetModel(const char* json);
  const char* GetModel() { return this->ModelText.c_str(); }
  ///@}

  ///@{
  /// A .pisurf file (default empty). When set, it takes precedence over Model.
  void SetFileName(const char* path);
  const char* GetFileName() { return this->FileNameText.c_str(); }
  ///@}

protected:
  vtkPiSurfaceFunction() = default;
  ~vtkPiSurfaceFunction() override = default;

private:
  vtkPiSurfaceFunction(const vtkPiSurfaceFunction&) = delete;
  void operator=(const vtkPiSurfaceFunction&) = delete;

  void Reload();
  std::string ModelText;
  std::string FileNameText;
};

#endif
