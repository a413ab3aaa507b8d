// SPDX-License-Identifier: BSD-3-Clause
// GUI test of the default display (pqPiDisplayBehavior) under Xvfb: a small ParaView
// client (like TestPiPrimitiveEditorGUI) loads the PiSurfaces plugin with its Qt
// interfaces, creates a render view and shows sources the way the GUI's Apply does
// (vtkSMParaViewPipelineControllerWithRendering::Show). A Pi Surface shows translucent
// solid grey over its Primitives port coloured by Factor; a Pi Product too; a Pi
// Primitive stays opaque. The user's later changes stay: a hidden and re-shown surface
// keeps them, and a .pvsm state file restores them instead of the defaults.
#include "PiQtTestUtilities.h"
#include "pqApplicationCore.h"
#include "pqDataRepresentation.h"
#include "pqObjectBuilder.h"
#include "pqPiParaViewCompat.h"
#include "pqPipelineSource.h"
#include "pqServer.h"
#include "pqServerManagerModel.h"
#include "pqServerResource.h"
#include "pqView.h"
#include "vtkDataObject.h"
#include "vtkNew.h"
#include "vtkSMParaViewPipelineControllerWithRendering.h"
#include "vtkSMPluginManager.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMViewProxy.h"

#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
std::string ColorArray(vtkSMProxy* representation)
{
  const char* name =
    vtkSMPropertyHelper(representation, "ColorArrayName").GetInputArrayNameToProcess();
  return name ? name : "";
}

double Opacity(vtkSMProxy* representation)
{
  return vtkSMPropertyHelper(representation, "Opacity").GetAsDouble();
}

// Opacity < 1, no scalar colouring, a grey diffuse colour.
bool TranslucentGrey(vtkSMProxy* representation)
{
  double colour[3];
  vtkSMPropertyHelper(representation, "DiffuseColor").Get(colour, 3);
  return Opacity(representation) < 1 && ColorArray(representation).empty() &&
    !pqPiCompat::GetUsingScalarColoring(representation) && colour[0] == colour[1] &&
    colour[1] == colour[2] && colour[0] > 0.3 && colour[0] < 0.9;
}
}

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::cerr << "usage: TestPiDisplayGUI <PiSurfaces plugin .so> <temporary folder>\n";
    return EXIT_FAILURE;
  }
  const std::string plugin = argv[1];
  const std::string state = std::string(argv[2]) + "/TestPiDisplayGUI.pvsm";
  TestApplication<> application(argv[0]);
  pqApplicationCore& core = application.Application;
  pqObjectBuilder* builder = core.getObjectBuilder();
  pqServer* server = StartSession(builder, plugin);
  if (!server)
  {
    return EXIT_FAILURE;
  }
  pqView* view = builder->createView("RenderView", server);
  auto* viewProxy = vtkSMViewProxy::SafeDownCast(view->getProxy());
  vtkNew<vtkSMParaViewPipelineControllerWithRendering> controller;
  auto show = [&](pqPipelineSource* source, int port)
  { return controller->Show(vtkSMSourceProxy::SafeDownCast(source->getProxy()), port, viewProxy); };

  // A Pi Surface: the surface translucent grey, the primitives coloured by Factor.
  pqPipelineSource* surface = builder->createSource("sources", "PiSurface", server);
  vtkSMPropertyHelper(surface->getProxy(), "Resolution").Set(32);
  surface->getProxy()->UpdateVTKObjects();
  vtkSMProxy* surfaceShown = show(surface, 0);
  vtkSMProxy* primitivesShown = show(surface, 1);
  CHECK(surfaceShown && TranslucentGrey(surfaceShown),
    "the Pi Surface is translucent grey: opacity " << Opacity(surfaceShown) << ", colour array '"
                                                   << ColorArray(surfaceShown) << "'");
  CHECK(primitivesShown && ColorArray(primitivesShown) == "Factor" &&
      pqPiCompat::GetUsingScalarColoring(primitivesShown) && Opacity(primitivesShown) == 1,
    "the Primitives port is opaque and coloured by Factor, not '" << ColorArray(primitivesShown)
                                                                  << "'");

  // Pi Primitive sources stay opaque; their Pi Product is translucent grey.
  pqPipelineSource* a = builder->createSource("sources", "PiPrimitive", server);
  pqPipelineSource* b = builder->createSource("sources", "PiPrimitive", server);
  vtkSMPropertyHelper(b->getProxy(), "Center").Set(0, 1.5);
  b->getProxy()->UpdateVTKObjects();
  QMap<QString, QList<pqOutputPort*>> inputs;
  inputs["Input"] = { a->getOutputPort(0), b->getOutputPort(0) };
  pqPipelineSource* product = builder->createFilter("filters", "PiProduct", inputs, server);
  vtkSMProxy* aShown = show(a, 0);
  vtkSMProxy* productShown = show(product, 0);
  CHECK(aShown && Opacity(aShown) == 1, "a Pi Primitive stays opaque");
  CHECK(productShown && TranslucentGrey(productShown), "the Pi Product is translucent grey");

  // The user's choice stays: hidden and shown again, the representation is not new.
  vtkSMPropertyHelper(surfaceShown, "Opacity").Set(0.8);
  pqPiCompat::SetScalarColoring(surfaceShown, "Normals", vtkDataObject::POINT);
  surfaceShown->UpdateVTKObjects();
  controller->Hide(vtkSMSourceProxy::SafeDownCast(surface->getProxy()), 0, viewProxy);
  CHECK(show(surface, 0) == surfaceShown && Opacity(surfaceShown) == 0.8 &&
      ColorArray(surfaceShown) == "Normals",
    "Hide then Show keeps the user's opacity and colouring");

  // A state file restores what the user saved, not the defaults.
  CHECK(core.saveState(QString::fromStdString(state)), "state saved to " << state);
  builder->destroySources(server);
  builder->destroy(view);
  core.loadState(state.c_str(), server);
  QCoreApplication::processEvents();
  pqServerManagerModel* model = core.getServerManagerModel();
  pqPipelineSource* loaded = nullptr;
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>(server))
  {
    if (std::string(source->getProxy()->GetXMLName()) == "PiSurface")
    {
      loaded = source;
    }
  }
  QList<pqView*> views = model->findItems<pqView*>(server);
  CHECK(loaded && !views.empty(), "the state has the Pi Surface and a view");
  if (loaded && !views.empty())
  {
    pqDataRepresentation* restored = loaded->getRepresentation(0, views[0]);
    CHECK(restored && Opacity(restored->getProxy()) == 0.8 &&
        ColorArray(restored->getProxy()) == "Normals",
      "the state restores opacity 0.8 coloured by Normals, not the defaults: opacity "
        << (restored ? Opacity(restored->getProxy()) : -1) << ", '"
        << (restored ? ColorArray(restored->getProxy()) : "") << "'");
    pqDataRepresentation* primitives = loaded->getRepresentation(1, views[0]);
    CHECK(primitives && ColorArray(primitives->getProxy()) == "Factor",
      "the Primitives port is still coloured by Factor");
  }

  builder->destroySources(server);
  builder->destroyAllProxies(server);
  builder->removeServer(server);
  std::cerr << (Failures ? "FAILED" : "passed") << " (" << Failures << " failures)\n";
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
