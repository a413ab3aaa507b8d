// SPDX-License-Identifier: BSD-3-Clause
#include "pqPiDisplayBehavior.h"

#include "pqApplicationCore.h"
#include "pqRepresentation.h"
#include "pqServerManagerModel.h"
#include "pqUndoStack.h"
#include "vtkDataObject.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"

#include <cstring>

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
  }
}

void pqPiDisplayBehavior::shutdown()
{
  if (pqApplicationCore* core = pqApplicationCore::instance())
  {
    QObject::disconnect(core->getServerManagerModel(), nullptr, this, nullptr);
  }
}

void pqPiDisplayBehavior::onRepresentationAdded(pqRepresentation* representation)
{
  vtkSMProxy* proxy = representation ? representation->getProxy() : nullptr;
  if (proxy && !RestoringProxies(proxy))
  {
    pqPiDisplayBehavior::ApplyDefaults(proxy);
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
  if (!producer || !IsPiSurfaceProducer(producer) || port > 1)
  {
    return false;
  }
  if (port == 0)
  {
    // Translucent solid grey, as in the paper's figures.
    vtkSMPVRepresentationProxy::SetScalarColoring(representation, nullptr, vtkDataObject::POINT);
    const double grey[3] = { DefaultGrey, DefaultGrey, DefaultGrey };
    vtkSMPropertyHelper(representation, "DiffuseColor").Set(grey, 3);
    if (representation->GetProperty("AmbientColor"))
    {
      vtkSMPropertyHelper(representation, "AmbientColor").Set(grey, 3);
    }
    vtkSMPropertyHelper(representation, "Opacity").Set(DefaultOpacity);
  }
  else
  {
    // Each primitive in its own colour.
    vtkSMPVRepresentationProxy::SetScalarColoring(representation, "Factor", vtkDataObject::POINT);
  }
  representation->UpdateVTKObjects();
  return true;
}
