// SPDX-License-Identifier: BSD-3-Clause
#include "pqPiDisplayBehavior.h"

#include "pqApplicationCore.h"
#include "pqPiParaViewCompat.h"
#include "pqPipelineSource.h"
#include "pqRepresentation.h"
#include "pqServerManagerModel.h"
#include "pqUndoStack.h"
#include "vtkDataObject.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPiModelMesher.h"
#include "vtkPiSurface.h"
#include "vtkSMParaViewPipelineController.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMTransferFunctionManager.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace
{
// The proxies whose port 0 is a Π-surface and port 1 its primitives.
bool IsPiSurfaceProducer(vtkSMProxy* producer)
{
  const char* group = producer->GetXMLGroup();
  const char* name = producer->GetXMLName();
  if (!group || !name)
  {
    return false;
  }
  if (std::strcmp(group, "sources") == 0)
  {
    return std::strcmp(name, "PiSurface") == 0 || std::strcmp(name, "PiSurfaceModelReader") == 0;
  }
  return std::strcmp(group, "filters") == 0 && std::strcmp(name, "PiProduct") == 0;
}

bool IsProxy(vtkSMProxy* proxy, const char* group, const char* name)
{
  return proxy->GetXMLGroup() && proxy->GetXMLName() &&
    std::strcmp(proxy->GetXMLGroup(), group) == 0 && std::strcmp(proxy->GetXMLName(), name) == 0;
}

bool IsMoleculeProducer(vtkSMProxy* producer)
{
  return IsProxy(producer, "filters", "MolecularPiSurface") ||
    IsProxy(producer, "sources", "PiMoleculeReader");
}

// The primitives' colours, as in the paper's figures and the gallery.
constexpr double Palette[8][3] = { { 0.85, 0.22, 0.18 }, { 0.22, 0.42, 0.85 }, { 0.25, 0.7, 0.3 },
  { 0.95, 0.6, 0.15 }, { 0.6, 0.3, 0.75 }, { 0.15, 0.7, 0.7 }, { 0.9, 0.8, 0.2 },
  { 0.8, 0.4, 0.6 } };

// Whether the Π-surface lies inside its primitives (a factor that is negative far away,
// such as a negated sphere digging a dent) rather than around them: F is then negative
// in most directions far from the model. Needs the producer's VTK object (the built-in
// session); false otherwise.
bool SurfaceInsidePrimitives(vtkSMProxy* producer)
{
  auto* mesher = vtkPiModelMesher::SafeDownCast(producer->GetClientSideObject());
  vtkPiSurface* surface = mesher ? mesher->GetPiSurface() : nullptr;
  double bounds[6];
  if (!surface || surface->GetNumberOfFactors() == 0 || !surface->GetModelBounds(bounds))
  {
    return false;
  }
  double centre[3], size = 0;
  for (int k = 0; k < 3; ++k)
  {
    centre[k] = 0.5 * (bounds[2 * k] + bounds[2 * k + 1]);
    size = std::max(size, bounds[2 * k + 1] - bounds[2 * k]);
  }
  // The 26 directions of a cube's faces, edges and corners, at 10 model sizes.
  int negative = 0, total = 0;
  for (int i = -1; i <= 1; ++i)
  {
    for (int j = -1; j <= 1; ++j)
    {
      for (int k = -1; k <= 1; ++k)
      {
        if (i == 0 && j == 0 && k == 0)
        {
          continue;
        }
        const double d[3] = { double(i), double(j), double(k) };
        const double scale = 10 * std::max(size, 1e-300) / vtkMath::Norm(d);
        double p[3] = { centre[0] + scale * d[0], centre[1] + scale * d[1],
          centre[2] + scale * d[2] };
        const double f = surface->EvaluateFunction(p);
        negative += f < 0 ? 1 : 0;
        total += std::isnan(f) ? 0 : 1;
      }
    }
  }
  return total > 0 && 2 * negative > total;
}

// Updates `source` so that its shown ports are computed and its data information is
// fresh: the server side (vtkPiSIOnDemandSourceProxy) computes a port after the first
// only for a visible consumer, such as a representation just created or shown, which
// then pulls the data without the client's data information knowing.
// UpdatePipeline(time) runs even when the source has executed since its last change.
void UpdateShownPorts(vtkSMSourceProxy* source)
{
  vtkNew<vtkSMParaViewPipelineController> controller;
  vtkSMProxy* timeKeeper = controller->FindTimeKeeper(source->GetSession());
  source->UpdatePipeline(timeKeeper ? vtkSMPropertyHelper(timeKeeper, "Time").GetAsDouble() : 0.0);
}

// The number of points of `producer`'s output `port`, updated first.
vtkIdType NumberOfPoints(vtkSMProxy* producer, unsigned int port)
{
  auto* source = vtkSMSourceProxy::SafeDownCast(producer);
  if (!source || port >= source->GetNumberOfOutputPorts())
  {
    return 0;
  }
  UpdateShownPorts(source);
  return source->GetDataInformation(port)->GetNumberOfPoints();
}

// `Factor` as categories, one palette colour per primitive (index 0 to count-1).
void MakeFactorCategorical(vtkSMProxy* representation, int count)
{
  vtkSMProxy* lut = vtkSMPropertyHelper(representation, "LookupTable", true).GetAsProxy();
  if (!lut || !lut->GetProperty("IndexedLookup"))
  {
    return;
  }
  count = std::max(
    count, static_cast<int>(vtkSMPropertyHelper(lut, "Annotations").GetNumberOfElements() / 2));
  std::vector<std::string> annotations;
  std::vector<double> colours;
  for (int i = 0; i < count; ++i)
  {
    annotations.push_back(std::to_string(i));
    annotations.push_back("primitive " + std::to_string(i));
    colours.insert(colours.end(), Palette[i % 8], Palette[i % 8] + 3);
  }
  vtkSMPropertyHelper(lut, "IndexedLookup").Set(1);
  vtkSMPropertyHelper annotationsHelper(lut, "Annotations");
  annotationsHelper.SetNumberOfElements(static_cast<unsigned int>(annotations.size()));
  for (unsigned int i = 0; i < annotations.size(); ++i)
  {
    annotationsHelper.Set(i, annotations[i].c_str());
  }
  vtkSMPropertyHelper(lut, "IndexedColors")
    .Set(colours.data(), static_cast<unsigned int>(colours.size()));
  lut->UpdateVTKObjects();
}

struct Element
{
  int Number;
  const char* Symbol;
  double Colour[3];
};

// CPK colours (as Jmol draws them) of the elements of biomolecules and small molecules.
constexpr Element Elements[] = { { 1, "H", { 1, 1, 1 } }, { 6, "C", { 0.56, 0.56, 0.56 } },
  { 7, "N", { 0.19, 0.31, 0.97 } }, { 8, "O", { 1, 0.05, 0.05 } }, { 9, "F", { 0.56, 0.88, 0.31 } },
  { 11, "Na", { 0.67, 0.36, 0.95 } }, { 12, "Mg", { 0.54, 1, 0 } }, { 15, "P", { 1, 0.5, 0 } },
  { 16, "S", { 1, 1, 0.19 } }, { 17, "Cl", { 0.12, 0.94, 0.12 } },
  { 19, "K", { 0.56, 0.25, 0.83 } }, { 20, "Ca", { 0.24, 1, 0 } }, { 26, "Fe", { 0.88, 0.4, 0.2 } },
  { 29, "Cu", { 0.78, 0.5, 0.2 } }, { 30, "Zn", { 0.49, 0.5, 0.69 } }, { 34, "Se", { 1, 0.63, 0 } },
  { 35, "Br", { 0.65, 0.16, 0.16 } }, { 53, "I", { 0.58, 0, 0.58 } } };

// `AtomicNumber` as categories with the CPK colours, for whichever display colours by it.
void MakeAtomicNumberCategorical(vtkSMSessionProxyManager* pxm)
{
  vtkNew<vtkSMTransferFunctionManager> manager;
  vtkSMProxy* lut = manager->GetColorTransferFunction("AtomicNumber", pxm);
  if (!lut || !lut->GetProperty("IndexedLookup") ||
    vtkSMPropertyHelper(lut, "IndexedLookup").GetAsInt() != 0)
  {
    return; // already categorical (ours, or the user's)
  }
  vtkSMPropertyHelper annotations(lut, "Annotations");
  std::vector<double> colours;
  const unsigned int n = sizeof(Elements) / sizeof(Elements[0]);
  annotations.SetNumberOfElements(2 * n);
  for (unsigned int i = 0; i < n; ++i)
  {
    annotations.Set(2 * i, std::to_string(Elements[i].Number).c_str());
    annotations.Set(2 * i + 1, Elements[i].Symbol);
    colours.insert(colours.end(), Elements[i].Colour, Elements[i].Colour + 3);
  }
  vtkSMPropertyHelper(lut, "IndexedColors")
    .Set(colours.data(), static_cast<unsigned int>(colours.size()));
  vtkSMPropertyHelper(lut, "IndexedLookup").Set(1);
  lut->UpdateVTKObjects();
}

// Re-created proxies (state files, undo/redo) carry the user's saved properties.
bool RestoringProxies(vtkSMProxy* proxy)
{
  if (proxy->GetSessionProxyManager() && proxy->GetSessionProxyManager()->GetInLoadXMLState())
  {
    return true;
  }
  pqApplicationCore* core = pqApplicationCore::instance();
  if (core && core->isLoadingState())
  {
    return true;
  }
  pqUndoStack* undo = core ? core->getUndoStack() : nullptr;
  return undo && (undo->getInUndo() || undo->getInRedo());
}
}

pqPiDisplayBehavior::pqPiDisplayBehavior(QObject* parent)
  : Superclass(parent)
{
}

pqPiDisplayBehavior::~pqPiDisplayBehavior() = default;

void pqPiDisplayBehavior::startup()
{
  if (pqApplicationCore* core = pqApplicationCore::instance())
  {
    QObject::connect(core->getServerManagerModel(), &pqServerManagerModel::representationAdded,
      this, &pqPiDisplayBehavior::onRepresentationAdded, Qt::UniqueConnection);
    QObject::connect(core->getServerManagerModel(), &pqServerManagerModel::sourceAdded, this,
      &pqPiDisplayBehavior::onSourceNamed, Qt::UniqueConnection);
    QObject::connect(core->getServerManagerModel(), &pqServerManagerModel::nameChanged, this,
      [this](pqServerManagerModelItem* item)
      { this->onSourceNamed(qobject_cast<pqPipelineSource*>(item)); });
  }
}

void pqPiDisplayBehavior::shutdown()
{
  if (pqApplicationCore* core = pqApplicationCore::instance())
  {
    QObject::disconnect(core->getServerManagerModel(), nullptr, this, nullptr);
  }
}

void pqPiDisplayBehavior::onSourceNamed(pqPipelineSource* source)
{
  vtkSMProxy* proxy = source ? source->getProxy() : nullptr;
  auto* object = proxy ? vtkObject::SafeDownCast(proxy->GetClientSideObject()) : nullptr;
  if (object && std::strncmp(object->GetClassName(), "vtkPi", 5) == 0)
  {
    // Error messages then name the source as the Pipeline Browser does.
    object->SetObjectName(source->getSMName().toStdString());
  }
}

void pqPiDisplayBehavior::onRepresentationAdded(pqRepresentation* representation)
{
  vtkSMProxy* proxy = representation ? representation->getProxy() : nullptr;
  if (!proxy)
  {
    return;
  }
  if (!RestoringProxies(proxy))
  {
    pqPiDisplayBehavior::ApplyDefaults(proxy);
  }
  // A Primitives port shown again is computed by its representation's render: update
  // its producer then, so that the Information panel tells the data shown.
  vtkSMPropertyHelper input(proxy, "Input", /*quiet=*/true);
  auto* producer = vtkSMSourceProxy::SafeDownCast(input.GetAsProxy());
  if (producer && input.GetOutputPort() == 1 && IsPiSurfaceProducer(producer))
  {
    QObject::connect(representation, &pqRepresentation::visibilityChanged, this,
      [weakProducer = vtkWeakPointer<vtkSMSourceProxy>(producer)](bool visible)
      {
        if (visible && weakProducer)
        {
          UpdateShownPorts(weakProducer);
        }
      });
  }
}

bool pqPiDisplayBehavior::ApplyDefaults(vtkSMProxy* representation)
{
  // Render-view (geometry) representations only: not spreadsheets or charts.
  for (const char* property : { "Input", "Opacity", "DiffuseColor", "ColorArrayName" })
  {
    if (!representation->GetProperty(property))
    {
      return false;
    }
  }
  vtkSMPropertyHelper input(representation, "Input", /*quiet=*/true);
  vtkSMProxy* producer = input.GetAsProxy();
  const unsigned int port = input.GetOutputPort();
  if (!producer)
  {
    return false;
  }
  if (IsMoleculeProducer(producer))
  {
    MakeAtomicNumberCategorical(representation->GetSessionProxyManager());
    return true;
  }
  if (IsProxy(producer, "sources", "PiPrimitive") && port == 0)
  {
    // Each new primitive in the next colour of the palette, as in the paper's figures.
    static int primitives = 0;
    const double* colour = Palette[primitives++ % 8];
    pqPiCompat::SetScalarColoring(representation, nullptr, vtkDataObject::POINT);
    vtkSMPropertyHelper(representation, "DiffuseColor").Set(colour, 3);
    if (representation->GetProperty("AmbientColor"))
    {
      vtkSMPropertyHelper(representation, "AmbientColor").Set(colour, 3);
    }
    representation->UpdateVTKObjects();
    return true;
  }
  if (!IsPiSurfaceProducer(producer) || port > 1)
  {
    return false;
  }
  // The result in front: a Π-surface around its primitives is translucent over them;
  // one inside them (a dent, a concavity) is opaque under translucent primitives.
  const bool inside = SurfaceInsidePrimitives(producer);
  if (port == 0)
  {
    pqPiCompat::SetScalarColoring(representation, nullptr, vtkDataObject::POINT);
    const double grey[3] = { DefaultGrey, DefaultGrey, DefaultGrey };
    vtkSMPropertyHelper(representation, "DiffuseColor").Set(grey, 3);
    if (representation->GetProperty("AmbientColor"))
    {
      vtkSMPropertyHelper(representation, "AmbientColor").Set(grey, 3);
    }
    vtkSMPropertyHelper(representation, "Opacity").Set(inside ? 1.0 : DefaultOpacity);
  }
  else if (NumberOfPoints(producer, 1) == 0)
  {
    // Nothing to show (Pi Product without GeneratePrimitives): no colouring by an
    // absent array.
    pqPiCompat::SetScalarColoring(representation, nullptr, vtkDataObject::POINT);
    vtkSMPropertyHelper(representation, "Visibility").Set(0);
  }
  else
  {
    // Each primitive in its own colour.
    pqPiCompat::SetScalarColoring(representation, "Factor", vtkDataObject::POINT);
    auto* source = vtkSMSourceProxy::SafeDownCast(producer);
    vtkPVArrayInformation* factor =
      source->GetDataInformation(1)->GetArrayInformation("Factor", vtkDataObject::POINT);
    const int count = factor ? static_cast<int>(factor->GetComponentRange(0)[1]) + 1 : 1;
    MakeFactorCategorical(representation, count);
    vtkSMPropertyHelper(representation, "Opacity").Set(inside ? DefaultOpacity : 1.0);
  }
  representation->UpdateVTKObjects();
  return true;
}
