// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiSurfaceModelWriter
 * @brief writes the Pi-surface model carried by a dataset as a .pisurf file
 *
 * Any output of the Pi-surface algorithms (vtkPiSurfaceSource, the model reader,
 * vtkPiPrimitiveSource, vtkPiProduct, vtkPiMoleculeSurface in Global mode) carries its
 * model as the field-data string `PiSurfaceModel`. This writer validates that model and
 * writes it to FileName as .pisurf JSON (version 1), which vtkPiSurfaceModelReader reads
 * back to the same function and, with the same mesher settings, the same mesh
 * (ParaView: File > Save Data, "Pi-surface model").
 *
 * An input without `PiSurfaceModel`, an invalid model, no FileName or a file that
 * cannot be written is an error (vtkErrorMacro, and GetErrorCode() is set); no file is
 * left half-written: the text goes to FileName only once it is complete.
 *
 * @sa vtkPiSurfaceModelReader vtkPiSurface
 */
#ifndef vtkPiSurfaceModelWriter_h
#define vtkPiSurfaceModelWriter_h

#include "vtkPiSurfacesReadersModule.h" // for export macro
#include "vtkWriter.h"

class VTKPISURFACESREADERS_EXPORT vtkPiSurfaceModelWriter : public vtkWriter
{
public:
  static vtkPiSurfaceModelWriter* New();
  vtkTypeMacro(vtkPiSurfaceModelWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .pisurf file to write (default none).
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

protected:
  vtkPiSurfaceModelWriter();
  ~vtkPiSurfaceModelWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  char* FileName = nullptr;

private:
  vtkPiSurfaceModelWriter(const vtkPiSurfaceModelWriter&) = delete;
  void operator=(const vtkPiSurfaceModelWriter&) = delete;
};

#endif
