// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiSIOnDemandSourceProxy
 * @brief server side of a source whose outputs after the first are computed when shown
 *
 * ParaView's server-manager proxy of a source updates every output port of its
 * algorithm whenever it is updated (vtkSMSourceProxy::UpdatePipeline: Apply in the GUI,
 * `Show` and `UpdatePipeline` in pvpython), shown or not. This server-side proxy
 * (`si_class` in the XML) updates the first port as usual and each further port only
 * when something wants it: a visible representation, or a consumer that is neither a
 * representation nor ParaView's selection extractor (a filter, a writer). A port
 * nothing wants keeps its last data; a representation made visible later, a filter
 * connected to it, or `servermanager.Fetch` pulls it through the VTK pipeline as
 * usual.
 *
 * With an algorithm that computes each port only when that port is requested (the
 * Primitives port of vtkPiSurfaceSource, vtkPiSurfaceModelReader and vtkPiProduct with
 * PrimitivesOnDemand), a port that is not shown costs nothing.
 *
 * @sa vtkSISourceProxy vtkPiFlyingEdges
 */
#ifndef vtkPiSIOnDemandSourceProxy_h
#define vtkPiSIOnDemandSourceProxy_h

#include "vtkPiSurfacesServerManagerModule.h" // for export macro
#include "vtkSISourceProxy.h"

class VTKPISURFACESSERVERMANAGER_EXPORT vtkPiSIOnDemandSourceProxy : public vtkSISourceProxy
{
public:
  static vtkPiSIOnDemandSourceProxy* New();
  vtkTypeMacro(vtkPiSIOnDemandSourceProxy, vtkSISourceProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Updates port 0 always, a further port only when it is wanted (see the class doc).
  void UpdatePipeline(int port, double time, bool doTime) override;

  /// Whether a visible representation or a filter consumes output `port`.
  bool IsPortWanted(int port);

protected:
  vtkPiSIOnDemandSourceProxy();
  ~vtkPiSIOnDemandSourceProxy() override;

private:
  vtkPiSIOnDemandSourceProxy(const vtkPiSIOnDemandSourceProxy&) = delete;
  void operator=(const vtkPiSIOnDemandSourceProxy&) = delete;
};

#endif
